// A ConicSolver reuses its symbolic factorisation across updates of b, c and A's values.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "random_problem.hpp"
#include "rbla/conic/solver.hpp"

using namespace rbla::conic;
using namespace rbla::conic::testing;

namespace {

/// A problem related to `p` (same shape): A's values scaled entry-wise by 1 + spread * ((k % 3) - 1),
/// kept feasible and bounded: b = A x1 for x1, the solution `x` of p moved into the interior of K,
/// and c shifted by `c_shift` along the interior of K* on the orthant.
ConicProblem related_problem(const ConicProblem& p, const Eigen::VectorXd& x, double spread, double c_shift) {
  ConicProblem q = p;
  for (Eigen::Index k = 0; k < q.A.nonZeros(); ++k) q.A.valuePtr()[k] *= 1.0 + spread * ((k % 3) - 1.0);
  Eigen::VectorXd x1 = x;
  for (Eigen::Index j = 0; j < q.cones.num_nonneg; ++j) x1[j] += 0.5;
  for (std::size_t k = 0; k < q.cones.soc_dims.size(); ++k)
    x1[q.cones.num_nonneg + 3 * static_cast<Eigen::Index>(k)] += 0.5;
  q.b = q.A * x1;
  q.c.head(q.cones.num_nonneg).array() += c_shift;
  return q;
}

}  // namespace

TEST(ConicRepeatedSolves, UpdatesMatchFreshSolvesAndKeepTheSymbolicFactor) {
  RandomProblemOptions o;
  o.rows = 80;
  o.num_nonneg = 60;
  o.num_soc3 = 50;
  o.dense_columns = 1;
  o.seed = 9;
  ConicProblem p = random_feasible_problem(o);
  ConicSolver solver(p);
  ASSERT_EQ(solver.num_symbolic_analyses(), 1);
  const Solution first = solver.solve();
  ASSERT_EQ(first.info.status, SolveStatus::Solved);

  // A sequence of related problems: values of A scaled entry-wise, b and c moved.
  for (int step = 1; step <= 5; ++step) {
    const ConicProblem q = related_problem(p, first.x, 0.05 * step, 0.1 * step);
    solver.update_A_values(Eigen::Map<const Eigen::VectorXd>(q.A.valuePtr(), q.A.nonZeros()));
    solver.update_b(q.b);
    solver.update_c(q.c);
    const Solution reused = solver.solve();
    const Solution fresh = solve(q);
    ASSERT_EQ(reused.info.status, SolveStatus::Solved) << "step " << step;
    ASSERT_EQ(fresh.info.status, SolveStatus::Solved) << "step " << step;
    EXPECT_NEAR(reused.info.primal_objective, fresh.info.primal_objective,
                1e-7 * std::max(1.0, std::abs(fresh.info.primal_objective)));
    // Deterministic: the reused solver follows the same iterates as a fresh one.
    EXPECT_EQ(reused.info.iterations, fresh.info.iterations);
  }
  // One analysis, plus at most one more if the bordered dense-column solve ever needed the
  // fallback factor (then kept for all later solves): never one per update.
  EXPECT_LE(solver.num_symbolic_analyses(), 2);
}

TEST(ConicRepeatedSolves, WrongLengthsAreSetupErrors) {
  ConicSolver solver(random_feasible_problem({}));
  EXPECT_THROW(solver.update_b(Eigen::VectorXd::Zero(3)), ConicSetupError);
  EXPECT_THROW(solver.update_c(Eigen::VectorXd::Zero(3)), ConicSetupError);
  EXPECT_THROW(solver.update_A_values(Eigen::VectorXd::Zero(3)), ConicSetupError);
}

TEST(ConicRepeatedSolves, UpdateTakesAWholeProblemOfTheSameShapeOnly) {
  RandomProblemOptions o;
  o.rows = 50;
  o.num_nonneg = 40;
  o.num_soc3 = 30;
  o.seed = 13;
  const ConicProblem p = random_feasible_problem(o);
  ConicSolver solver(p);
  const Solution first = solver.solve();
  ASSERT_EQ(first.info.status, SolveStatus::Solved);

  const ConicProblem q = related_problem(p, first.x, 0.1, 0.2);
  ASSERT_TRUE(same_shape(p, q));
  solver.update(q);
  const Solution reused = solver.solve();
  const Solution fresh = solve(q);
  ASSERT_EQ(reused.info.status, SolveStatus::Solved);
  EXPECT_NEAR(reused.info.primal_objective, fresh.info.primal_objective,
              1e-9 * std::max(1.0, std::abs(fresh.info.primal_objective)));
  EXPECT_EQ(reused.info.iterations, fresh.info.iterations);
  EXPECT_EQ(solver.num_symbolic_analyses(), 1);

  // One entry fewer: another pattern, refused, and the solver keeps its problem.
  ConicProblem sparser = q;
  sparser.A.coeffRef(sparser.A.innerIndexPtr()[0], 0) = 0.0;
  sparser.A.prune(0.0);
  EXPECT_FALSE(same_shape(q, sparser));
  EXPECT_THROW(solver.update(sparser), ConicSetupError);
  ConicProblem other_cones = q;
  other_cones.cones.num_nonneg -= 3;
  other_cones.cones.soc_dims.push_back(3);
  EXPECT_FALSE(same_shape(q, other_cones));
  EXPECT_THROW(solver.update(other_cones), ConicSetupError);
  EXPECT_EQ(solver.solve().info.iterations, reused.info.iterations);
}

TEST(ConicRepeatedSolves, SettingsCanChangeBetweenSolves) {
  ConicSolver solver(random_feasible_problem({}));
  solver.settings().max_iter = 0;  // the starting point alone
  EXPECT_EQ(solver.solve().info.status, SolveStatus::IterationLimit);
  solver.settings().max_iter = 100;
  EXPECT_EQ(solver.solve().info.status, SolveStatus::Solved);
}

TEST(ConicRepeatedSolves, WarmStartReachesTheSameOptimumInFewerIterations) {
  // A nearby problem (b moved by 1 %) started from the previous solution: same optimum as a
  // cold solve, to the tolerances, and no more iterations.
  RandomProblemOptions o;
  o.rows = 60;
  o.num_nonneg = 40;
  o.num_soc3 = 40;
  o.seed = 21;
  const ConicProblem p = random_feasible_problem(o);
  ConicSolver solver(p);
  const Solution first = solver.solve();
  ASSERT_EQ(first.info.status, SolveStatus::Solved);
  EXPECT_FALSE(first.info.warm_started);

  Eigen::VectorXd b = p.b;
  for (Eigen::Index i = 0; i < b.size(); ++i) b[i] *= 1.0 + 0.01 * ((i % 5) - 2.0) / 2.0;
  solver.update_b(b);
  const Solution cold = solver.solve();
  ASSERT_EQ(cold.info.status, SolveStatus::Solved);
  solver.set_warm_start(first.x, first.y, first.z);
  const Solution warm = solver.solve();
  ASSERT_EQ(warm.info.status, SolveStatus::Solved);
  EXPECT_TRUE(warm.info.warm_started);
  EXPECT_NEAR(warm.info.primal_objective, cold.info.primal_objective,
              1e-6 * (1.0 + std::abs(cold.info.primal_objective)));
  EXPECT_LE(warm.info.iterations, cold.info.iterations);
  // Used once: the next solve starts cold again.
  const Solution again = solver.solve();
  EXPECT_FALSE(again.info.warm_started);
  EXPECT_EQ(again.info.iterations, cold.info.iterations);
}

TEST(ConicRepeatedSolves, UnusableWarmStartFallsBackToTheColdStart) {
  RandomProblemOptions o;
  o.rows = 30;
  o.num_nonneg = 20;
  o.num_soc3 = 20;
  o.seed = 5;
  const ConicProblem p = random_feasible_problem(o);
  ConicSolver solver(p);
  const Solution cold = solver.solve();
  Eigen::VectorXd x = cold.x;
  x[0] = std::numeric_limits<double>::quiet_NaN();
  solver.set_warm_start(x, cold.y, cold.z);
  const Solution s = solver.solve();
  EXPECT_FALSE(s.info.warm_started);
  EXPECT_EQ(s.info.status, SolveStatus::Solved);
  EXPECT_EQ(s.info.iterations, cold.info.iterations);
  solver.set_warm_start(Eigen::VectorXd::Ones(3), cold.y, cold.z);  // wrong length
  EXPECT_FALSE(solver.solve().info.warm_started);
}

TEST(ConicRepeatedSolves, FactorLargerThanTheMemoryLimitIsRefusedBeforeFactoring) {
  RandomProblemOptions o;
  o.rows = 60;
  o.num_nonneg = 40;
  o.num_soc3 = 40;
  o.seed = 3;
  const ConicProblem p = random_feasible_problem(o);
  Settings s;
  s.memory_limit_bytes = 1000.0;  // far below any factor of 60 rows
  try {
    ConicSolver solver(p, s);
    FAIL() << "expected ConicResourceError";
  } catch (const ConicResourceError& error) {
    EXPECT_NE(std::string(error.what()).find("needs"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("GB"), std::string::npos) << error.what();
  }
  s.memory_limit_bytes = 1e9;
  ConicSolver solver(p, s);
  const Solution ok = solver.solve();
  EXPECT_EQ(ok.info.status, SolveStatus::Solved);
  EXPECT_GT(ok.info.factor_bytes, 0.0);
  EXPECT_LT(ok.info.factor_bytes, 1e9);
}
