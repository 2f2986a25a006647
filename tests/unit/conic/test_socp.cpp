// Second-order cone programs with closed-form optima and their infeasible / unbounded twins.
#include <gtest/gtest.h>

#include <cmath>

#include "rbla/conic/solver.hpp"
#include "test_helpers.hpp"

using namespace rbla::conic;
using namespace rbla::conic::testing;

TEST(ConicSocp, NormOfFixedVector) {
  // min t  s.t.  u = (3, 4), (t, u) ∈ Q³  →  t = 5; dual: z = c − Aᵀy = (1, −y) must be
  // complementary to x = (5, 3, 4), so y = (3/5, 4/5) and bᵀy = 5.
  const ConicProblem p = make_problem(2, 3, {0, 1, 0, 0, 0, 1}, {3, 4}, {1, 0, 0}, 0, {3});
  const Solution sol = solve(p);
  ASSERT_EQ(sol.info.status, SolveStatus::Solved) << sol.info.brief_report();
  EXPECT_NEAR(sol.info.primal_objective, 5.0, 1e-7);
  EXPECT_NEAR(sol.x[0], 5.0, 1e-7);
  EXPECT_NEAR(sol.y[0], 0.6, 1e-6);
  EXPECT_NEAR(sol.y[1], 0.8, 1e-6);
}

TEST(ConicSocp, LinearObjectiveOverUnitDisc) {
  // min −u1 − u2  s.t.  t = 1, (t, u) ∈ Q³  →  u = (1, 1)/√2, value −√2.
  const ConicProblem p = make_problem(1, 3, {1, 0, 0}, {1}, {0, -1, -1}, 0, {3});
  const Solution sol = solve(p);
  ASSERT_EQ(sol.info.status, SolveStatus::Solved) << sol.info.brief_report();
  EXPECT_NEAR(sol.info.primal_objective, -std::sqrt(2.0), 1e-7);
  EXPECT_NEAR(sol.x[1], 1.0 / std::sqrt(2.0), 1e-6);
  EXPECT_NEAR(sol.x[2], 1.0 / std::sqrt(2.0), 1e-6);
}

TEST(ConicSocp, MixedOrthantAndCone) {
  // Variables s ≥ 0, (t, u1, u2) ∈ Q³; u1 + s = 3, u2 = 4; min t + s/2.
  // f(s) = √((3 − s)² + 16) + s/2 is minimal where (3 − s)/t = 1/2: t = 8/√3, s = 3 − 4/√3,
  // value 2√3 + 3/2.
  const ConicProblem p =
      make_problem(2, 4, {1, 0, 1, 0, 0, 0, 0, 1}, {3, 4}, {0.5, 1, 0, 0}, 1, {3});
  const Solution sol = solve(p);
  ASSERT_EQ(sol.info.status, SolveStatus::Solved) << sol.info.brief_report();
  EXPECT_NEAR(sol.info.primal_objective, 2 * std::sqrt(3.0) + 1.5, 1e-7);
  // The objective is quadratic around a smooth optimum, so x is only accurate to about
  // √(gap) (gap ~ 1e-8 here).
  EXPECT_NEAR(sol.x[0], 3 - 4 / std::sqrt(3.0), 1e-4);
  EXPECT_NEAR(sol.x[1], 8 / std::sqrt(3.0), 1e-4);
}

TEST(ConicSocp, InfeasibleTwinGivesFarkasCertificate) {
  // t = −1 with (t, u) ∈ Q³ is impossible; a certificate is y = −1 (bᵀy = 1, −Aᵀy = e ∈ Q³).
  const ConicProblem p = make_problem(2, 3, {1, 0, 0, 0, 1, 0}, {-1, 0.5}, {1, 0, 0}, 0, {3});
  const Solution sol = solve(p);
  ASSERT_EQ(sol.info.status, SolveStatus::PrimalInfeasible) << sol.info.brief_report();
  EXPECT_LT(primal_certificate_error(p, sol.y), 1e-7);
}

TEST(ConicSocp, InfeasibleNormBoundGivesCertificate) {
  // t = 1, u1 = 2 violates ‖u‖ ≤ t: the certificate must separate the two.
  const ConicProblem p = make_problem(2, 3, {1, 0, 0, 0, 1, 0}, {1, 2}, {0, 0, 1}, 0, {3});
  const Solution sol = solve(p);
  ASSERT_EQ(sol.info.status, SolveStatus::PrimalInfeasible) << sol.info.brief_report();
  EXPECT_LT(primal_certificate_error(p, sol.y), 1e-7);
}

TEST(ConicSocp, UnboundedTwinGivesRayCertificate) {
  // min −u1 s.t. u2 = 0, (t, u1, u2) ∈ Q³: the boundary ray (1, 1, 0) decreases without bound.
  const ConicProblem p = make_problem(1, 3, {0, 0, 1}, {0}, {0, -1, 0}, 0, {3});
  const Solution sol = solve(p);
  ASSERT_EQ(sol.info.status, SolveStatus::DualInfeasible) << sol.info.brief_report();
  EXPECT_LT(dual_certificate_error(p, sol.x), 1e-7);
}

TEST(ConicSocp, TwoDimensionalConeIsAnAbsoluteValue) {
  // Q² = {(t, u): |u| ≤ t}. min t s.t. u = −2.5 → t = 2.5.
  const ConicProblem p = make_problem(1, 2, {0, 1}, {-2.5}, {1, 0}, 0, {2});
  const Solution sol = solve(p);
  ASSERT_EQ(sol.info.status, SolveStatus::Solved) << sol.info.brief_report();
  EXPECT_NEAR(sol.info.primal_objective, 2.5, 1e-7);
}
