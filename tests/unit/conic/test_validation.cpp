// Setup errors are typed exceptions with readable messages; statuses have names.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "rbla/conic/solver.hpp"
#include "test_helpers.hpp"

using namespace rbla::conic;
using namespace rbla::conic::testing;

namespace {
bool mentions(const std::vector<std::string>& messages, const std::string& needle) {
  for (const auto& m : messages) {
    if (m.find(needle) != std::string::npos) return true;
  }
  return false;
}
}  // namespace

TEST(ConicValidation, ProblemMessagesNameTheProblem) {
  ConicProblem p = make_problem(1, 3, {1, 1, 1}, {1}, {1, 1, 1}, 1, {1});
  auto messages = p.validate();
  EXPECT_TRUE(mentions(messages, "soc_dims[0] = 1")) << messages.size();
  p.cones.soc_dims = {2};
  EXPECT_TRUE(p.validate().empty());
  p.b.resize(2);
  p.b.setOnes();
  EXPECT_TRUE(mentions(p.validate(), "b has 2 entries"));
  p.b = Eigen::VectorXd::Ones(1);
  p.c[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(mentions(p.validate(), "c[1] is not finite"));
  p.c[1] = 0;
  p.cones.num_nonneg = 2;
  EXPECT_TRUE(mentions(p.validate(), "cones cover 4 variables"));
  p.cones.num_nonneg = 1;
  p.A.coeffRef(0, 2) = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(mentions(p.validate(), "A(0, 2) is not finite"));
}

TEST(ConicValidation, SolverThrowsTypedErrorOnBadInput) {
  ConicProblem p = make_problem(1, 2, {1, 1}, {1}, {1, 1}, 3);
  EXPECT_THROW(ConicSolver{p}, ConicSetupError);
  try {
    ConicSolver solver(p);
  } catch (const ConicSetupError& error) {
    EXPECT_NE(std::string(error.what()).find("invalid conic problem"), std::string::npos);
  }
}

TEST(ConicValidation, SettingsMessages) {
  Settings s;
  EXPECT_TRUE(s.validate().empty());
  s.tol_feas = -1;
  s.step_fraction = 1.5;
  s.reg_retry_factor = 0.5;
  const auto messages = s.validate();
  EXPECT_TRUE(mentions(messages, "tol_feas"));
  EXPECT_TRUE(mentions(messages, "step_fraction"));
  EXPECT_TRUE(mentions(messages, "reg_retry_factor"));
  const ConicProblem p = make_problem(1, 2, {1, 1}, {1}, {1, 1}, 2);
  EXPECT_THROW(solve(p, s), ConicSetupError);
}

TEST(ConicValidation, EveryStatusHasADistinctName) {
  const SolveStatus all[] = {SolveStatus::Solved,           SolveStatus::SolvedInaccurate,
                             SolveStatus::PrimalInfeasible, SolveStatus::DualInfeasible,
                             SolveStatus::IterationLimit,   SolveStatus::TimeLimit,
                             SolveStatus::NumericalFailure, SolveStatus::Cancelled};
  std::vector<std::string> names;
  for (SolveStatus s : all) {
    names.push_back(to_string(s));
    EXPECT_NE(names.back(), "unknown");
  }
  std::sort(names.begin(), names.end());
  EXPECT_EQ(std::unique(names.begin(), names.end()), names.end());
  EXPECT_TRUE(has_solution(SolveStatus::SolvedInaccurate));
  EXPECT_FALSE(has_solution(SolveStatus::PrimalInfeasible));
}
