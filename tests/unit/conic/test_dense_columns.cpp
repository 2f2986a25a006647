// A column touching every row is kept out of the sparse factor; the answer must not change.
#include <gtest/gtest.h>

#include <random>

#include "../../../solver/src/conic/fork_join.hpp"
#include "../../../solver/src/conic/normal_equations.hpp"
#include "random_problem.hpp"
#include "rbla/conic/solver.hpp"
#include "test_helpers.hpp"

using namespace rbla::conic;
using namespace rbla::conic::testing;

TEST(ConicDenseColumns, SameSolutionWithAndWithoutDenseColumnHandling) {
  RandomProblemOptions o;
  o.rows = 300;
  o.num_nonneg = 200;
  o.num_soc3 = 150;
  o.dense_columns = 2;
  o.band = 8;
  o.seed = 3;
  const ConicProblem p = random_feasible_problem(o);

  Settings with;
  Settings without;
  without.dense_columns = false;
  const Solution a = solve(p, with);
  const Solution b = solve(p, without);
  ASSERT_EQ(a.info.status, SolveStatus::Solved) << a.info.brief_report();
  ASSERT_EQ(b.info.status, SolveStatus::Solved) << b.info.brief_report();
  EXPECT_EQ(a.info.num_dense_columns, 2);
  EXPECT_EQ(b.info.num_dense_columns, 0);
  // Two dense columns make M (and L) dense; kept out, L of the banded rest is much sparser.
  EXPECT_LT(a.info.num_factor_nonzeros * 2, b.info.num_factor_nonzeros);
  const double scale = std::max(1.0, std::abs(b.info.primal_objective));
  EXPECT_NEAR(a.info.primal_objective, b.info.primal_objective, 1e-7 * scale);
  EXPECT_LT((a.x - b.x).lpNorm<Eigen::Infinity>(),
            1e-4 * std::max(1.0, b.x.lpNorm<Eigen::Infinity>()));
  EXPECT_LT((p.A * a.x - p.b).lpNorm<Eigen::Infinity>(),
            1e-6 * std::max(1.0, p.b.lpNorm<Eigen::Infinity>()));
}

TEST(ConicDenseColumns, DetectionFollowsTheThresholds) {
  RandomProblemOptions o;
  o.rows = 60;
  o.num_nonneg = 80;
  o.num_soc3 = 10;
  o.dense_columns = 1;
  const ConicProblem p = random_feasible_problem(o);
  Settings s;
  s.dense_column_min_nnz = 61;  // the dense column has 60 (or 61) entries
  s.dense_column_ratio = 1.0;
  const long nnz0 = p.A.outerIndexPtr()[1] - p.A.outerIndexPtr()[0];
  const Solution high = solve(p, s);
  EXPECT_EQ(high.info.num_dense_columns, nnz0 >= 61 ? 1 : 0);
  s.dense_column_min_nnz = 40;
  const Solution low = solve(p, s);
  EXPECT_EQ(low.info.num_dense_columns, 1);
  ASSERT_EQ(low.info.status, SolveStatus::Solved);
  EXPECT_NEAR(low.info.primal_objective, high.info.primal_objective,
              1e-7 * std::max(1.0, std::abs(high.info.primal_objective)));
}

TEST(ConicDenseColumns, OnlyDenseColumnCoversSomeRows) {
  // Rows 0..4 are touched only by the dense column 0 (and b there is consistent): M_s is
  // singular on those rows, which the regularised bordered solve plus refinement must handle.
  // min x0 + Σ x_j  s.t.  x0 = 1 (rows 0..4 all say so), x_j − x0 = 1 for j = 1..5.
  // Optimum x0 = 1, x_j = 2: value 11.
  const int m = 10, n = 6;
  std::vector<double> A(static_cast<std::size_t>(m * n), 0.0);
  std::vector<double> b(static_cast<std::size_t>(m), 1.0);
  for (int i = 0; i < 5; ++i) A[static_cast<std::size_t>(i * n)] = 1.0;
  for (int j = 1; j < 6; ++j) {
    const int i = 4 + j;
    A[static_cast<std::size_t>(i * n)] = -1.0;
    A[static_cast<std::size_t>(i * n + j)] = 1.0;
  }
  const ConicProblem p = make_problem(m, n, A, b, {1, 1, 1, 1, 1, 1}, n);
  Settings s;
  s.dense_column_min_nnz = 5;
  s.dense_column_ratio = 2.0;
  const Solution sol = solve(p, s);
  EXPECT_EQ(sol.info.num_dense_columns, 1);
  ASSERT_EQ(sol.info.status, SolveStatus::Solved) << sol.info.brief_report();
  EXPECT_NEAR(sol.info.primal_objective, 11.0, 1e-7);
}

namespace {
/// W² blocks G Gᵀ + 0.1 I (G standard normal), packed as ConeSet::pack_W2 does, and the whole
/// block-diagonal W² in `W2`.
std::vector<double> random_W2(const std::vector<rbla::conic::detail::ScalingBlock>& blocks, int n,
                              std::mt19937& rng, Eigen::MatrixXd& W2) {
  std::normal_distribution<double> normal;
  W2 = Eigen::MatrixXd::Zero(n, n);
  std::vector<double> packed;
  for (const auto& block : blocks) {
    const auto q = block.size;
    const Eigen::MatrixXd G = Eigen::MatrixXd::NullaryExpr(q, q, [&] { return normal(rng); });
    const Eigen::MatrixXd spd = G * G.transpose() + 0.1 * Eigen::MatrixXd::Identity(q, q);
    W2.block(block.first, block.first, q, q) = spd;
    for (Eigen::Index j = 0; j < q; ++j)
      for (Eigen::Index i = 0; i < q; ++i) packed.push_back(spd(i, j));
  }
  return packed;
}
}  // namespace

TEST(ConicNormalEquations, ProductEqualsTheExplicitNormalMatrix) {
  // M v = A W² Aᵀ v with W² block diagonal (scalars, 3×3 and 4×4 SOC blocks) and one dense
  // column kept out of the sparse factor: the product CG refines with must be the exact M.
  using namespace rbla::conic::detail;
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  const int rows = 30;
  std::vector<ScalingBlock> blocks;
  int n = 0;
  for (int k = 0; k < 10; ++k) blocks.push_back({n++, 1});
  for (int k = 0; k < 8; ++k) {
    blocks.push_back({n, 3});
    n += 3;
  }
  blocks.push_back({n, 4});
  n += 4;
  std::vector<Eigen::Triplet<double>> triplets;
  for (int j = 0; j < n; ++j) {
    for (int t = 0; t < 3; ++t) {
      const int row = static_cast<int>(rng() % rows);  // drawn first on every compiler
      triplets.emplace_back(row, j, normal(rng));
    }
  }
  for (int i = 0; i < rows; ++i) triplets.emplace_back(i, 0, normal(rng));  // column 0 is dense
  Eigen::SparseMatrix<double> A(rows, n);
  A.setFromTriplets(triplets.begin(), triplets.end());
  std::vector<bool> is_dense(static_cast<std::size_t>(n), false);
  is_dense[0] = true;
  NormalEquations normal_equations(A, blocks, is_dense, rbla::conic::Ordering::Amd, nullptr);
  ASSERT_EQ(normal_equations.num_dense_columns(), 1);

  Eigen::MatrixXd W2;
  const std::vector<double> packed = random_W2(blocks, n, rng, W2);
  ASSERT_TRUE(normal_equations.factor(packed, 1e-8, 10.0, 5).ok);
  const Eigen::MatrixXd M = Eigen::MatrixXd(A) * W2 * Eigen::MatrixXd(A).transpose();
  const Eigen::VectorXd v = Eigen::VectorXd::NullaryExpr(rows, [&] { return normal(rng); });
  Eigen::VectorXd product;
  normal_equations.multiply(v, product);
  EXPECT_LT((product - M * v).norm(), 1e-12 * (M * v).norm());
  // And a refined solve meets its target on the exact M.
  Eigen::VectorXd dy;
  normal_equations.solve(M * v, dy, 10, 1e-10);
  EXPECT_LT((M * dy - M * v).lpNorm<Eigen::Infinity>(), 1e-10);
}

namespace {

/// A problem with fixed rows: 20 coupled rows; 6 scalars and 8 3-cones each with its first
/// coordinate fixed by a row of its own; a 4-cone with two fixed. With `extras`, column 0 touches
/// every coupled row (a dense column) and one more scalar is fixed by a row of its own (a block
/// with nothing left in M).
struct FixedRowsCase {
  Eigen::SparseMatrix<double> A;
  std::vector<rbla::conic::detail::ScalingBlock> blocks;
  std::vector<bool> is_dense;
  int num_fixed = 0;
};

FixedRowsCase fixed_rows_case(std::mt19937& rng, bool extras) {
  std::normal_distribution<double> normal;
  const int coupled_rows = 20;
  FixedRowsCase c;
  std::vector<Eigen::Triplet<double>> all;
  int n = 0, rows = coupled_rows;
  for (int k = 0; k < 6; ++k) c.blocks.push_back({n++, 1});
  for (int k = 0; k < 8; ++k) {
    c.blocks.push_back({n, 3});
    n += 3;
  }
  // Each free column's first entry goes to the next coupled row in turn, so that every coupled
  // row is reached (a row with no entry would make M singular but for the regularisation); its
  // other two go to random rows. The draws are sequenced: the order in which function arguments
  // are evaluated is unspecified (GCC and clang differ), and with it the case.
  int next_row = 0;
  auto random_entry = [&](int row, int column) {
    const double value = normal(rng);
    all.emplace_back(row, column, value);
  };
  for (int j = 0; j < n; ++j) {
    const bool fixed = j >= 6 && (j - 6) % 3 == 0;
    if (fixed) {
      all.emplace_back(rows++, j, 0.5 + j);
      continue;
    }
    random_entry(next_row++ % coupled_rows, j);
    for (int t = 0; t < 2; ++t) random_entry(static_cast<int>(rng() % coupled_rows), j);
  }
  if (extras) {
    // Column 0 on every row; each row also on one of the scalars 1-5, so that M without the dense
    // column is not singular (then the bordered solve loses accuracy, normal_equations.hpp).
    for (int i = 0; i < coupled_rows; ++i) {
      random_entry(i, 0);
      random_entry(i, 1 + i % 5);
    }
  }
  c.blocks.push_back({n, 4});
  for (int j = n + 2; j < n + 4; ++j) random_entry(static_cast<int>(rng() % coupled_rows), j);
  all.emplace_back(rows++, n, -2.0);
  all.emplace_back(rows++, n + 1, 3.0);
  n += 4;
  if (extras) {
    c.blocks.push_back({n, 1});
    all.emplace_back(rows++, n++, 4.0);
  }
  c.A.resize(rows, n);
  c.A.setFromTriplets(all.begin(), all.end());  // duplicates (column 0) are summed
  c.is_dense.assign(static_cast<std::size_t>(n), false);
  c.is_dense[0] = extras;
  c.num_fixed = rows - coupled_rows;
  return c;
}

/// Factors with random W² blocks; the product, the refined solve and the pair solve must be
/// those of the explicit M = A W² Aᵀ over every row.
void expect_explicit_M(rbla::conic::detail::NormalEquations& ne, const FixedRowsCase& c,
                       std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd W2;
  const std::vector<double> packed = random_W2(c.blocks, static_cast<int>(c.A.cols()), rng, W2);
  ASSERT_TRUE(ne.factor(packed, 1e-12, 10.0, 5).ok);
  const Eigen::MatrixXd M = Eigen::MatrixXd(c.A) * W2 * Eigen::MatrixXd(c.A).transpose();
  const Eigen::VectorXd v = Eigen::VectorXd::NullaryExpr(c.A.rows(), [&] { return normal(rng); });
  const Eigen::VectorXd rhs = M * v;
  Eigen::VectorXd product;
  ne.multiply(v, product);
  EXPECT_LT((product - rhs).norm(), 1e-12 * rhs.norm());
  Eigen::VectorXd dy;
  ne.solve(rhs, dy, 10, 1e-11);
  EXPECT_LT((dy - v).lpNorm<Eigen::Infinity>(), 1e-8 * v.lpNorm<Eigen::Infinity>());
  // The pair solve (unrefined) is two plain solves in one pass. It sums in another order (two
  // columns through the factor's dense kernels), and M, regularised by only 1e-12, amplifies the
  // rounding: the two agreed to 5.5e-12 relative on an AMD EPYC. A wrong pairing is O(1) off.
  Eigen::VectorXd plain, a, b;
  ne.solve(rhs, plain, 0, 0.0);
  ne.solve_pair(rhs, 2.0 * rhs, a, b);
  EXPECT_LT((a - plain).lpNorm<Eigen::Infinity>(), 1e-10 * plain.lpNorm<Eigen::Infinity>());
  EXPECT_LT((b - 2.0 * plain).lpNorm<Eigen::Infinity>(), 2e-10 * plain.lpNorm<Eigen::Infinity>());
  EXPECT_LT((plain - v).lpNorm<Eigen::Infinity>(), 1e-3 * v.lpNorm<Eigen::Infinity>());
}

}  // namespace

TEST(ConicNormalEquations, FixedRowsAreEliminatedExactly) {
  // Rows with one nonzero in a column with no other nonzero (a cone coordinate fixed by its own
  // row, as a capped friction cone's radius) are eliminated before factoring.
  using namespace rbla::conic::detail;
  std::mt19937 rng(5);
  const FixedRowsCase c = fixed_rows_case(rng, false);
  NormalEquations ne(c.A, c.blocks, c.is_dense, rbla::conic::Ordering::Amd, nullptr, 1);
  ASSERT_EQ(ne.num_fixed_rows(), 10);
  EXPECT_EQ(NormalEquations(c.A, c.blocks, c.is_dense, rbla::conic::Ordering::Amd, nullptr, 11).num_fixed_rows(), 0)
      << "fewer fixed rows than asked for stay in M";
  expect_explicit_M(ne, c, rng);
}

TEST(ConicNormalEquations, FixedRowsWithADenseColumnTwoThreadsAndNewValues) {
  // The same with a dense column kept out of the factor, a block whose only coordinate is
  // fixed, the reduction and recovery on two threads (a random matrix has no small separator,
  // so the factor itself is one), and then new values of A in the same pattern.
  using namespace rbla::conic::detail;
  std::mt19937 rng(9);
  FixedRowsCase c = fixed_rows_case(rng, true);
  ForkJoin fork_join;
  NormalEquations ne(c.A, c.blocks, c.is_dense, rbla::conic::Ordering::Best, &fork_join, 1);
  ASSERT_EQ(ne.num_fixed_rows(), 11);
  ASSERT_EQ(ne.num_dense_columns(), 1);
  ASSERT_FALSE(ne.is_split());
  expect_explicit_M(ne, c, rng);
  std::uniform_real_distribution<double> factor(0.5, 2.0);
  for (Eigen::Index p = 0; p < c.A.nonZeros(); ++p) c.A.valuePtr()[p] *= factor(rng);
  ne.set_A_values(c.A);
  expect_explicit_M(ne, c, rng);
}
