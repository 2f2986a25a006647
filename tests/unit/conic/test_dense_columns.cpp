// A column touching every row is kept out of the sparse factor; the answer must not change.
#include <gtest/gtest.h>

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
