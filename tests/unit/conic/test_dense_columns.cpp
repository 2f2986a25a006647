// A column touching every row is kept out of the sparse factor; the answer must not change.
#include <gtest/gtest.h>

#include <random>

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
    for (int t = 0; t < 3; ++t) triplets.emplace_back(static_cast<int>(rng() % rows), j, normal(rng));
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

TEST(ConicNormalEquations, FixedRowsAreEliminatedExactly) {
  // Rows with one nonzero in a column with no other nonzero (a cone coordinate fixed by its own
  // row, as a capped friction cone's radius) are eliminated before factoring: the product, the
  // solve and the pair solve must be those of the explicit M = A W² Aᵀ over every row.
  using namespace rbla::conic::detail;
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  const int coupled_rows = 20;
  std::vector<ScalingBlock> blocks;
  std::vector<Eigen::Triplet<double>> triplets;
  int n = 0, rows = coupled_rows;
  for (int k = 0; k < 6; ++k) blocks.push_back({n++, 1});
  for (int k = 0; k < 8; ++k) {
    blocks.push_back({n, 3});
    n += 3;
  }
  for (int j = 0; j < n; ++j) {
    for (int t = 0; t < 3; ++t) triplets.emplace_back(static_cast<int>(rng() % coupled_rows), j, normal(rng));
  }
  // The first coordinate of each 3-cone fixed by a row of its own; one 4-cone with two fixed.
  std::vector<Eigen::Triplet<double>> all;
  for (const auto& t : triplets) {
    const bool fixed = t.col() >= 6 && (t.col() - 6) % 3 == 0;
    if (!fixed) all.push_back(t);
  }
  for (int k = 0; k < 8; ++k) all.emplace_back(rows++, 6 + 3 * k, 0.5 + k);
  blocks.push_back({n, 4});
  for (int j = n + 2; j < n + 4; ++j) all.emplace_back(static_cast<int>(rng() % coupled_rows), j, normal(rng));
  all.emplace_back(rows++, n, -2.0);
  all.emplace_back(rows++, n + 1, 3.0);
  n += 4;
  Eigen::SparseMatrix<double> A(rows, n);
  A.setFromTriplets(all.begin(), all.end());
  NormalEquations normal_equations(A, blocks, std::vector<bool>(static_cast<std::size_t>(n), false),
                                   rbla::conic::Ordering::Amd, nullptr, 1);
  ASSERT_EQ(normal_equations.num_fixed_rows(), 10);
  EXPECT_EQ(NormalEquations(A, blocks, std::vector<bool>(static_cast<std::size_t>(n), false),
                            rbla::conic::Ordering::Amd, nullptr, 11)
                .num_fixed_rows(),
            0)
      << "fewer fixed rows than asked for stay in M";

  Eigen::MatrixXd W2;
  const std::vector<double> packed = random_W2(blocks, n, rng, W2);
  ASSERT_TRUE(normal_equations.factor(packed, 1e-12, 10.0, 5).ok);
  const Eigen::MatrixXd M = Eigen::MatrixXd(A) * W2 * Eigen::MatrixXd(A).transpose();
  const Eigen::VectorXd v = Eigen::VectorXd::NullaryExpr(rows, [&] { return normal(rng); });
  Eigen::VectorXd product;
  normal_equations.multiply(v, product);
  EXPECT_LT((product - M * v).norm(), 1e-12 * (M * v).norm());
  const Eigen::VectorXd rhs = M * v;
  Eigen::VectorXd dy;
  normal_equations.solve(rhs, dy, 10, 1e-11);
  EXPECT_LT((dy - v).lpNorm<Eigen::Infinity>(), 1e-8 * v.lpNorm<Eigen::Infinity>());
  Eigen::VectorXd a, b;
  normal_equations.solve_pair(rhs, 2.0 * rhs, a, b);
  EXPECT_LT((a - v).lpNorm<Eigen::Infinity>(), 1e-6 * v.lpNorm<Eigen::Infinity>());
  EXPECT_LT((b - 2.0 * v).lpNorm<Eigen::Infinity>(), 2e-6 * v.lpNorm<Eigen::Infinity>());
}
