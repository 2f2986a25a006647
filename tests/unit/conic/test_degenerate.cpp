// Degenerate and badly scaled problems: cones at the apex, redundant and empty rows, data
// spanning 1e-6 .. 1e6.
#include <gtest/gtest.h>

#include <cmath>

#include "rbla/conic/solver.hpp"
#include "test_helpers.hpp"

using namespace rbla::conic;
using namespace rbla::conic::testing;

namespace {

// min Σ_k w_k t_k  s.t.  Σ_k u1_k = 1, (t_k, u1_k, u2_k) ∈ Q³, w_k = 1 + k/10.
// Optimum: everything on cone 0 (t_0 = u1_0 = 1), all other cones at the apex; value 1.
ConicProblem apex_problem(int num_cones) {
  ConicProblem p;
  p.A.resize(1, 3 * num_cones);
  p.c = Eigen::VectorXd::Zero(3 * num_cones);
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < num_cones; ++k) {
    t.emplace_back(0, 3 * k + 1, 1.0);
    p.c[3 * k] = 1.0 + 0.1 * k;
    p.cones.soc_dims.push_back(3);
  }
  p.A.setFromTriplets(t.begin(), t.end());
  p.A.makeCompressed();
  p.b = Eigen::VectorXd::Ones(1);
  return p;
}

}  // namespace

TEST(ConicDegenerate, ManyConesAtTheApex) {
  const ConicProblem p = apex_problem(60);
  const Solution sol = solve(p);
  ASSERT_EQ(sol.info.status, SolveStatus::Solved) << sol.info.brief_report();
  EXPECT_NEAR(sol.info.primal_objective, 1.0, 1e-7);
  EXPECT_NEAR(sol.x[0], 1.0, 1e-6);
  for (int k = 1; k < 60; ++k) EXPECT_LT(sol.x[3 * k], 1e-6) << "cone " << k;
  EXPECT_LE(sol.info.iterations, 30);
}

TEST(ConicDegenerate, ManyVariablesAtZeroInAnLp) {
  // min Σ w_j x_j  s.t.  Σ x_j = 1, x ≥ 0, w_j = 1 + j/100: x_0 = 1, the other 199 at zero.
  const int n = 200;
  std::vector<double> A(n, 1.0), c(n);
  for (int j = 0; j < n; ++j) c[static_cast<std::size_t>(j)] = 1.0 + 0.01 * j;
  const ConicProblem p = make_problem(1, n, A, {1.0}, c, n);
  const Solution sol = solve(p);
  ASSERT_EQ(sol.info.status, SolveStatus::Solved) << sol.info.brief_report();
  EXPECT_NEAR(sol.info.primal_objective, 1.0, 1e-7);
  EXPECT_NEAR(sol.x[0], 1.0, 1e-6);
}

TEST(ConicDegenerate, RedundantRowsAndAnEmptyRow) {
  // The small LP of test_lp.cpp with its first row repeated twice (once scaled by 2) and an
  // all-zero row with b = 0: M is singular, the optimum (−5 at x = (3, 1)) is unchanged.
  const ConicProblem p = make_problem(5, 4, {1, 1, 1, 0,  //
                                             1, 3, 0, 1,  //
                                             1, 1, 1, 0,  //
                                             0, 0, 0, 0,  //
                                             2, 2, 2, 0},
                                      {4, 6, 4, 0, 8}, {-1, -2, 0, 0}, 4);
  const Solution sol = solve(p);
  ASSERT_EQ(sol.info.status, SolveStatus::Solved) << sol.info.brief_report();
  EXPECT_NEAR(sol.info.primal_objective, -5.0, 1e-7);
  EXPECT_NEAR(sol.x[0], 3.0, 1e-6);
  EXPECT_NEAR(sol.x[1], 1.0, 1e-6);
}

TEST(ConicDegenerate, InconsistentEmptyRowIsInfeasible) {
  // 0 · x = 1: the certificate is the unit vector on that row.
  const ConicProblem p = make_problem(2, 2, {1, 1, 0, 0}, {1, 1}, {1, 1}, 2);
  const Solution sol = solve(p);
  ASSERT_EQ(sol.info.status, SolveStatus::PrimalInfeasible) << sol.info.brief_report();
  EXPECT_LT(primal_certificate_error(p, sol.y), 1e-7);
}

TEST(ConicDegenerate, ValuesSpanningTwelveOrdersOfMagnitude) {
  // The mixed LP/SOC problem of test_socp.cpp with rows scaled by 1e6 and 1e-6, the orthant
  // variable measured in micro-units (column × 1e-6 ⇒ its value × 1e6) and the cost × 1e3.
  // Optimum: 1e3 (2√3 + 3/2).
  const double big = 1e6, small = 1e-6;
  const ConicProblem p = make_problem(2, 4,
                                      {big * small, 0, big, 0,  //
                                       0, 0, 0, small},
                                      {3 * big, 4 * small}, {0.5e3 * small, 1e3, 0, 0}, 1, {3});
  const Solution sol = solve(p);
  ASSERT_EQ(sol.info.status, SolveStatus::Solved) << sol.info.brief_report();
  EXPECT_NEAR(sol.info.primal_objective / 1e3, 2 * std::sqrt(3.0) + 1.5, 1e-7);
  EXPECT_NEAR(sol.x[0] * small, 3 - 4 / std::sqrt(3.0), 1e-4);
}

TEST(ConicDegenerate, SameAnswerWithoutEquilibration) {
  const ConicProblem p = apex_problem(10);
  Settings s;
  s.equilibrate = false;
  const Solution plain = solve(p, s);
  const Solution scaled = solve(p);
  ASSERT_EQ(plain.info.status, SolveStatus::Solved);
  ASSERT_EQ(scaled.info.status, SolveStatus::Solved);
  EXPECT_NEAR(plain.info.primal_objective, scaled.info.primal_objective, 1e-7);
}

TEST(ConicDegenerate, NoEqualityRows) {
  // min cᵀx over x ≥ 0 alone: 0 if c ≥ 0, unbounded otherwise.
  ConicProblem p;
  p.A.resize(0, 2);
  p.b.resize(0);
  p.c = Eigen::Vector2d(1, 2);
  p.cones.num_nonneg = 2;
  const Solution bounded = solve(p);
  ASSERT_EQ(bounded.info.status, SolveStatus::Solved) << bounded.info.brief_report();
  EXPECT_NEAR(bounded.info.primal_objective, 0.0, 1e-7);
  p.c = Eigen::Vector2d(1, -2);
  const Solution unbounded = solve(p);
  ASSERT_EQ(unbounded.info.status, SolveStatus::DualInfeasible);
  EXPECT_LT(dual_certificate_error(p, unbounded.x), 1e-9);
}

TEST(ConicDegenerate, EmptyColumnWithNegativeCostIsUnbounded) {
  // x1 appears in no row and costs −1: the ray e₁ is an unboundedness certificate.
  const ConicProblem p = make_problem(1, 3, {1, 0, 1}, {1}, {1, -1, 1}, 3);
  const Solution sol = solve(p);
  ASSERT_EQ(sol.info.status, SolveStatus::DualInfeasible) << sol.info.brief_report();
  EXPECT_LT(dual_certificate_error(p, sol.x), 1e-7);
}
