// Linear programs with known optima and their infeasible / unbounded twins.
#include <gtest/gtest.h>

#include <sstream>

#include "rbla/conic/solver.hpp"
#include "test_helpers.hpp"

using namespace rbla::conic;
using namespace rbla::conic::testing;

namespace {

// min −x1 − 2 x2  s.t.  x1 + x2 + s1 = 4,  x1 + 3 x2 + s2 = 6,  x, s ≥ 0.
// By hand: vertices (0,0), (4,0), (0,2), (3,1); the optimum is (3,1) with value −5, and the
// dual y = (−1/2, −1/2) (c − Aᵀy = (0, 0, 1/2, 1/2) ≥ 0, bᵀy = −5).
ConicProblem small_lp() {
  return make_problem(2, 4, {1, 1, 1, 0, 1, 3, 0, 1}, {4, 6}, {-1, -2, 0, 0}, 4);
}

}  // namespace

TEST(ConicLp, SmallLpPrimalAndDualOptimum) {
  const ConicProblem p = small_lp();
  const Solution sol = solve(p);
  ASSERT_EQ(sol.info.status, SolveStatus::Solved) << sol.info.brief_report();
  EXPECT_NEAR(sol.info.primal_objective, -5.0, 1e-7);
  EXPECT_NEAR(sol.info.dual_objective, -5.0, 1e-7);
  EXPECT_NEAR(sol.x[0], 3.0, 1e-6);
  EXPECT_NEAR(sol.x[1], 1.0, 1e-6);
  EXPECT_NEAR(sol.y[0], -0.5, 1e-6);
  EXPECT_NEAR(sol.y[1], -0.5, 1e-6);
  EXPECT_LT((p.c - p.A.transpose() * sol.y - sol.z).lpNorm<Eigen::Infinity>(), 1e-7);
  EXPECT_LT(cone_violation(sol.x, p.cones), 1e-12);
  EXPECT_LT(cone_violation(sol.z, p.cones), 1e-12);
  EXPECT_GT(sol.info.iterations, 0);
  EXPECT_EQ(sol.info.history.size(), static_cast<std::size_t>(sol.info.iterations + 1));
}

TEST(ConicLp, InfeasibleTwinGivesFarkasCertificate) {
  // x1 + x2 = 4 and x1 + x2 + s = 2 with x, s ≥ 0 cannot both hold.
  const ConicProblem p = make_problem(2, 3, {1, 1, 0, 1, 1, 1}, {4, 2}, {-1, -2, 0}, 3);
  const Solution sol = solve(p);
  ASSERT_EQ(sol.info.status, SolveStatus::PrimalInfeasible) << sol.info.brief_report();
  EXPECT_NEAR(p.b.dot(sol.y), 1.0, 1e-9);
  EXPECT_LT(primal_certificate_error(p, sol.y), 1e-7);
  EXPECT_LT(sol.info.certificate_residual, 1e-7);
  EXPECT_TRUE(sol.x.hasNaN());
}

TEST(ConicLp, UnboundedTwinGivesRayCertificate) {
  // min −x1 − 2 x2  s.t.  x1 − x2 + s1 = 1: the ray x2 → ∞ (x1 = x2) is unbounded.
  const ConicProblem p = make_problem(1, 3, {1, -1, 1}, {1}, {-1, -2, 0}, 3);
  const Solution sol = solve(p);
  ASSERT_EQ(sol.info.status, SolveStatus::DualInfeasible) << sol.info.brief_report();
  EXPECT_NEAR(p.c.dot(sol.x), -1.0, 1e-9);
  EXPECT_LT(dual_certificate_error(p, sol.x), 1e-7);
  EXPECT_TRUE(sol.y.hasNaN());
}

TEST(ConicLp, IterationLimitReportsLastIterate) {
  Settings s;
  s.max_iter = 2;
  const Solution sol = solve(small_lp(), s);
  EXPECT_EQ(sol.info.status, SolveStatus::IterationLimit);
  EXPECT_EQ(sol.info.iterations, 2);
  EXPECT_EQ(sol.x.size(), 4);
  EXPECT_TRUE(sol.x.allFinite());
}

TEST(ConicLp, TimeLimitStopsBeforeTheFirstStep) {
  Settings s;
  s.time_limit_seconds = 1e-300;
  const Solution sol = solve(small_lp(), s);
  EXPECT_EQ(sol.info.status, SolveStatus::TimeLimit);
  EXPECT_EQ(sol.info.iterations, 0);
}

TEST(ConicLp, CallbackCanCancelAndSeesEveryRow) {
  ConicSolver solver(small_lp());
  std::vector<int> seen;
  solver.set_progress_callback([&seen](const IterationRow& row) {
    seen.push_back(row.iteration);
    return row.iteration < 2;
  });
  const Solution sol = solver.solve();
  EXPECT_EQ(sol.info.status, SolveStatus::Cancelled);
  EXPECT_EQ(seen, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(sol.info.history.size(), 3u);
}

TEST(ConicLp, LogGoesToTheConfiguredStream) {
  std::ostringstream log;
  Settings s;
  s.verbose = true;
  s.log_stream = &log;
  const Solution sol = solve(small_lp(), s);
  ASSERT_EQ(sol.info.status, SolveStatus::Solved);
  const std::string text = log.str();
  EXPECT_NE(text.find("status: solved"), std::string::npos);
  EXPECT_NE(text.find("iter  primal obj"), std::string::npos);
  // One fixed-width line per iteration row, starting with the right-aligned iteration number.
  EXPECT_NE(text.find("\n   0  "), std::string::npos);
  std::ostringstream quiet;
  s.verbose = false;
  s.log_stream = &quiet;
  solve(small_lp(), s);
  EXPECT_TRUE(quiet.str().empty());
}

TEST(ConicLp, InfoHasTimingsAndBackend) {
  const Solution sol = solve(small_lp());
  EXPECT_NE(sol.info.backend.find("CHOLMOD"), std::string::npos);
  EXPECT_GE(sol.info.total_seconds, 0.0);
  EXPECT_GE(sol.info.factor_seconds, 0.0);
  EXPECT_GE(sol.info.setup_seconds, sol.info.symbolic_seconds);
  EXPECT_GT(sol.info.num_factor_nonzeros, 0);
  EXPECT_NE(sol.info.brief_report().find("solved"), std::string::npos);
}
