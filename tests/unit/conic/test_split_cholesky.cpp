// The normal matrix split over two threads (detail::SplitCholesky) must solve what one CHOLMOD
// factor solves, on limit-analysis structure and with badly scaled terms, and the solver must
// reach the same optimum with it.
#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <stdexcept>

#include "../../../solver/src/conic/normal_equations.hpp"
#include "rbla/conic/solver.hpp"
#include "test_helpers.hpp"
#include "wall_problem.hpp"

using namespace rbla::conic;
using namespace rbla::conic::testing;
using rbla::conic::detail::ForkJoin;
using rbla::conic::detail::NormalEquations;
using rbla::conic::detail::ScalingBlock;

namespace {

// The wall's A with one scaling block per cone (variable 0, the load multiplier, is a scalar)
// and W² blocks G Gᵀ + 0.1 I scaled by 10^u, u uniform in [−decades, decades]: late in an
// interior-point solve W² spans many decades, which is what makes a factor's pivots small.
struct NormalCase {
  Eigen::SparseMatrix<double> A;
  std::vector<ScalingBlock> blocks;
  std::vector<double> packed_W2;
  Eigen::SparseMatrix<double> W2;  // block diagonal
};

NormalCase wall_normal_case(int nx, int ny, double decades, unsigned seed) {
  WallOptions o;
  o.nx = nx;
  o.ny = ny;
  const WallProblem wall = make_wall_problem(o);
  NormalCase c;
  c.A = wall.problem.A;
  const Eigen::Index n = c.A.cols();
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> exponent(-decades, decades);
  Eigen::Index first = 0;
  for (int k = 0; k < wall.problem.cones.num_nonneg; ++k) c.blocks.push_back({first++, 1});
  for (int q : wall.problem.cones.soc_dims) {
    c.blocks.push_back({first, q});
    first += q;
  }
  EXPECT_EQ(first, n);
  std::vector<Eigen::Triplet<double>> w2;
  for (const ScalingBlock& block : c.blocks) {
    const auto q = block.size;
    const Eigen::MatrixXd G = Eigen::MatrixXd::NullaryExpr(q, q, [&] { return normal(rng); });
    const Eigen::MatrixXd spd = std::pow(10.0, exponent(rng)) *
                                (G * G.transpose() + 0.1 * Eigen::MatrixXd::Identity(q, q));
    for (Eigen::Index j = 0; j < q; ++j) {
      for (Eigen::Index i = 0; i < q; ++i) {
        c.packed_W2.push_back(spd(i, j));
        w2.emplace_back(block.first + i, block.first + j, spd(i, j));
      }
    }
  }
  c.W2.resize(n, n);
  c.W2.setFromTriplets(w2.begin(), w2.end());
  return c;
}

/// The wall case with a capped copy of each cone, as the non-associative fixed-point test builds
/// them: (ρ, T₁, T₂) with T's columns those of the cone's last two coordinates and ρ fixed by a
/// row of its own. The fixed rows come last; W² of the new blocks as in wall_normal_case.
NormalCase capped_wall_case(int nx, int ny, double decades, unsigned seed) {
  NormalCase c = wall_normal_case(nx, ny, decades, seed);
  const Eigen::Index m = c.A.rows(), n = c.A.cols();
  std::vector<Eigen::Triplet<double>> triplets;
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(c.A, j); it; ++it)
      triplets.emplace_back(static_cast<int>(it.row()), static_cast<int>(j), it.value());
  }
  std::mt19937 rng(seed + 1);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> exponent(-decades, decades);
  const std::vector<ScalingBlock> cones = c.blocks;
  Eigen::Index col = n, row = m;
  std::vector<Eigen::Triplet<double>> w2;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::SparseMatrix<double>::InnerIterator it(c.W2, i); it; ++it)
      w2.emplace_back(static_cast<int>(it.row()), static_cast<int>(i), it.value());
  for (const ScalingBlock& cone : cones) {
    if (cone.size != 3) continue;
    triplets.emplace_back(static_cast<int>(row++), static_cast<int>(col), 1.0 + 0.5 * normal(rng) * normal(rng));
    for (int k = 1; k < 3; ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(c.A, cone.first + k); it; ++it)
        triplets.emplace_back(static_cast<int>(it.row()), static_cast<int>(col + k), it.value());
    }
    c.blocks.push_back({col, 3});
    const Eigen::MatrixXd G = Eigen::MatrixXd::NullaryExpr(3, 3, [&] { return normal(rng); });
    const Eigen::MatrixXd spd =
        std::pow(10.0, exponent(rng)) * (G * G.transpose() + 0.1 * Eigen::MatrixXd::Identity(3, 3));
    for (Eigen::Index j = 0; j < 3; ++j) {
      for (Eigen::Index i = 0; i < 3; ++i) {
        c.packed_W2.push_back(spd(i, j));
        w2.emplace_back(static_cast<int>(col + i), static_cast<int>(col + j), spd(i, j));
      }
    }
    col += 3;
  }
  c.A.resize(row, col);
  c.A.setFromTriplets(triplets.begin(), triplets.end());
  c.W2.resize(col, col);
  c.W2.setFromTriplets(w2.begin(), w2.end());
  return c;
}

}  // namespace

TEST(ConicSplitCholesky, SolvesWhatOneFactorSolves) {
  for (const double decades : {0.0, 4.0}) {
    const NormalCase c = wall_normal_case(14, 18, decades, 7);
    const std::vector<bool> no_dense(static_cast<std::size_t>(c.A.cols()), false);
    ForkJoin fork_join;
    NormalEquations one(c.A, c.blocks, no_dense, Ordering::Best, nullptr);
    NormalEquations split(c.A, c.blocks, no_dense, Ordering::Best, &fork_join);
    ASSERT_FALSE(one.is_split());
    ASSERT_TRUE(split.is_split()) << "a wall's normal matrix has a small balanced separator";
    EXPECT_NE(split.backend_name().find("two domains"), std::string::npos);
    ASSERT_TRUE(one.factor(c.packed_W2, 1e-10, 100.0, 8).ok);
    ASSERT_TRUE(split.factor(c.packed_W2, 1e-10, 100.0, 8).ok);

    const Eigen::SparseMatrix<double> AW2 = c.A * c.W2;
    const Eigen::SparseMatrix<double> M = AW2 * Eigen::SparseMatrix<double>(c.A.transpose());
    std::mt19937 rng(11);
    std::normal_distribution<double> normal;
    const Eigen::VectorXd x = Eigen::VectorXd::NullaryExpr(M.rows(), [&] { return normal(rng); });
    const Eigen::VectorXd rhs = M * x;
    Eigen::VectorXd x_one, x_split;
    one.solve(rhs, x_one, 0, 0.0);  // the factors alone, no refinement
    split.solve(rhs, x_split, 0, 0.0);
    // Both solve (M + δI) y = rhs: the same answer to rounding, and M's residual as small.
    const double scale = x_one.lpNorm<Eigen::Infinity>();
    EXPECT_LT((x_split - x_one).lpNorm<Eigen::Infinity>(), 1e-8 * scale) << "decades " << decades;
    const double residual_one = (M * x_one - rhs).lpNorm<Eigen::Infinity>();
    const double residual_split = (M * x_split - rhs).lpNorm<Eigen::Infinity>();
    EXPECT_LT(residual_split, 10 * residual_one + 1e-12 * rhs.lpNorm<Eigen::Infinity>())
        << "decades " << decades;
  }
}

TEST(ConicSplitCholesky, PairSolveIsTwoSingleSolves) {
  // solve_pair carries two right-hand sides through one pass over the factor (CHOLMOD's
  // multi-column solve; the split's domains, separator and bordering column by column). Each
  // column must come out as its own solve would: one factor, the split, and both with the
  // load multiplier (variable 0) kept out of the factor as a dense column.
  const NormalCase c = wall_normal_case(14, 18, 4.0, 3);
  std::mt19937 rng(13);
  std::normal_distribution<double> normal;
  const Eigen::Index m = c.A.rows();
  const Eigen::VectorXd rhs_a = Eigen::VectorXd::NullaryExpr(m, [&] { return normal(rng); });
  const Eigen::VectorXd rhs_b = Eigen::VectorXd::NullaryExpr(m, [&] { return normal(rng); });
  ForkJoin fork_join;
  for (const bool dense_load : {false, true}) {
    std::vector<bool> dense(static_cast<std::size_t>(c.A.cols()), false);
    dense[0] = dense_load;
    for (ForkJoin* threads : {static_cast<ForkJoin*>(nullptr), &fork_join}) {
      NormalEquations ne(c.A, c.blocks, dense, Ordering::Best, threads);
      ASSERT_EQ(ne.is_split(), threads != nullptr);
      ASSERT_EQ(ne.num_dense_columns(), dense_load ? 1 : 0);
      ASSERT_TRUE(ne.factor(c.packed_W2, 1e-10, 100.0, 8).ok);
      Eigen::VectorXd a, b, a_pair, b_pair;
      ne.solve(rhs_a, a, 0, 0.0);
      ne.solve(rhs_b, b, 0, 0.0);
      const long before = ne.num_factor_solves();
      ne.solve_pair(rhs_a, rhs_b, a_pair, b_pair);
      EXPECT_EQ(ne.num_factor_solves() - before, 2);
      const std::string where = std::string(threads ? "split" : "one factor") +
                                (dense_load ? ", dense column" : "");
      EXPECT_LE((a_pair - a).lpNorm<Eigen::Infinity>(), 1e-12 * a.lpNorm<Eigen::Infinity>())
          << where;
      EXPECT_LE((b_pair - b).lpNorm<Eigen::Infinity>(), 1e-12 * b.lpNorm<Eigen::Infinity>())
          << where;
      EXPECT_GT((a_pair - b_pair).lpNorm<Eigen::Infinity>(), 1e-3 * a.lpNorm<Eigen::Infinity>())
          << where << ": the columns were not kept apart";
    }
  }
}

TEST(ConicSplitCholesky, DeclinesWhereNoSmallBalancedSeparatorExists) {
  // A dense normal matrix (every variable touches every row) has no separator short of all
  // rows but one: the split is refused and one factor is used.
  const int rows = 40, cols = 60;
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  std::vector<Eigen::Triplet<double>> triplets;
  for (int j = 0; j < cols; ++j)
    for (int i = 0; i < rows; ++i) triplets.emplace_back(i, j, normal(rng));
  Eigen::SparseMatrix<double> A(rows, cols);
  A.setFromTriplets(triplets.begin(), triplets.end());
  std::vector<ScalingBlock> blocks;
  for (int j = 0; j < cols; ++j) blocks.push_back({j, 1});
  ForkJoin fork_join;
  NormalEquations normal_equations(A, blocks, std::vector<bool>(cols, false), Ordering::Amd,
                                   &fork_join);
  EXPECT_FALSE(normal_equations.is_split());
  ASSERT_TRUE(normal_equations.factor(std::vector<double>(cols, 1.0), 1e-10, 100.0, 8).ok);
}

TEST(ConicSplitCholesky, SolverReachesTheSameOptimumOnTwoThreads) {
  for (const bool pyramid : {false, true}) {
    WallOptions o;
    o.nx = 14;
    o.ny = 18;
    o.pyramid = pyramid;
    const WallProblem wall = make_wall_problem(o);
    Settings serial;
    serial.threads = 1;
    Settings split;
    split.threads = 2;
    split.split_min_rows = 0;
    const Solution a = solve(wall.problem, serial);
    const Solution b = solve(wall.problem, split);
    const Solution b_again = solve(wall.problem, split);
    ASSERT_EQ(a.info.status, SolveStatus::Solved) << a.info.brief_report();
    ASSERT_EQ(b.info.status, SolveStatus::Solved) << b.info.brief_report();
    EXPECT_EQ(a.info.backend.find("two domains"), std::string::npos);
    EXPECT_NE(b.info.backend.find("two domains"), std::string::npos) << b.info.backend;
    EXPECT_NEAR(a.info.primal_objective, b.info.primal_objective,
                1e-7 * std::abs(a.info.primal_objective));
    EXPECT_LT(b.info.res_primal, 1e-8);
    // Two threads, the same arithmetic: repeatable to the last bit.
    EXPECT_EQ(b.info.primal_objective, b_again.info.primal_objective);
    EXPECT_EQ(b.info.iterations, b_again.info.iterations);
  }
}

TEST(ConicSplitCholesky, CertificatesOnTwoThreads) {
  // The infeasible twin (weight pointing up) keeps its certificate with the split factor.
  WallOptions o;
  o.nx = 14;
  o.ny = 18;
  WallProblem wall = make_wall_problem(o);
  wall.problem.b = -wall.problem.b;
  Settings split;
  split.split_min_rows = 0;
  const Solution s = solve(wall.problem, split);
  EXPECT_NE(s.info.backend.find("two domains"), std::string::npos) << s.info.backend;
  ASSERT_EQ(s.info.status, SolveStatus::PrimalInfeasible) << s.info.brief_report();
  EXPECT_LT(primal_certificate_error(wall.problem, s.y), 1e-7);
}

TEST(ConicForkJoin, RunsBothHalvesAndPassesOnExceptions) {
  ForkJoin fork_join;
  std::vector<int> seen(1000, 0);
  auto count_range = [&seen](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) ++seen[i];
  };
  const std::function<void()> first_half = [&] { count_range(0, 500); };
  const std::function<void()> second_half = [&] { count_range(500, 1000); };
  for (int round = 0; round < 50; ++round) fork_join.run(first_half, second_half);
  for (int count : seen) EXPECT_EQ(count, 50);
  const std::function<void()> fine = [] {};
  const std::function<void()> throws = [] { throw std::runtime_error("helper side"); };
  EXPECT_THROW(fork_join.run(fine, throws), std::runtime_error);
  EXPECT_THROW(fork_join.run(throws, fine), std::runtime_error);
  // Still usable afterwards.
  int calls = 0;
  const std::function<void()> count_call = [&calls] { ++calls; };
  const std::function<void()> nothing = [] {};
  fork_join.run(count_call, nothing);
  EXPECT_EQ(calls, 1);
}

TEST(ConicSplitCholesky, FixedRowsOnTwoThreads) {
  // Capped cones' radius rows are eliminated before factoring (normal_equations.hpp); on two
  // threads the elimination's separator terms go to the domains' shares. A refined solve must
  // reach the explicit M's answer with one factor and with the split alike.
  const NormalCase c = capped_wall_case(14, 18, 2.0, 5);
  const std::vector<bool> no_dense(static_cast<std::size_t>(c.A.cols()), false);
  ForkJoin fork_join;
  const Eigen::SparseMatrix<double> M =
      (c.A * c.W2) * Eigen::SparseMatrix<double>(c.A.transpose());
  std::mt19937 rng(17);
  std::normal_distribution<double> normal;
  const Eigen::VectorXd x = Eigen::VectorXd::NullaryExpr(M.rows(), [&] { return normal(rng); });
  const Eigen::VectorXd rhs = M * x;
  std::vector<Eigen::VectorXd> plain;
  for (ForkJoin* threads : {static_cast<ForkJoin*>(nullptr), &fork_join}) {
    NormalEquations ne(c.A, c.blocks, no_dense, Ordering::Best, threads, 1);
    const std::string where = threads ? "split" : "one factor";
    ASSERT_EQ(ne.is_split(), threads != nullptr);
    ASSERT_GT(ne.num_fixed_rows(), 100) << where;
    ASSERT_TRUE(ne.factor(c.packed_W2, 1e-12, 100.0, 8).ok) << where;
    Eigen::VectorXd product;
    ne.multiply(x, product);
    EXPECT_LT((product - rhs).lpNorm<Eigen::Infinity>(), 1e-12 * rhs.lpNorm<Eigen::Infinity>()) << where;
    plain.emplace_back();
    ne.solve(rhs, plain.back(), 0, 0.0);  // the factor alone
    Eigen::VectorXd solved;
    ne.solve(rhs, solved, 50, 1e-10 * rhs.lpNorm<Eigen::Infinity>());
    EXPECT_LT((M * solved - rhs).lpNorm<Eigen::Infinity>(), 1e-9 * rhs.lpNorm<Eigen::Infinity>()) << where;
    EXPECT_LT((solved - x).lpNorm<Eigen::Infinity>(), 1e-5 * x.lpNorm<Eigen::Infinity>()) << where;
  }
  // Unrefined, the two factors solve the same regularised system.
  EXPECT_LT((plain[1] - plain[0]).lpNorm<Eigen::Infinity>(), 1e-8 * plain[0].lpNorm<Eigen::Infinity>());
}
