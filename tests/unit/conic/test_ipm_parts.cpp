// The pieces of the interior-point method on their own: the stopping rules
// (Residuals::check_termination and the reduced-accuracy fallback), the iterate's step
// operations (Variables), and the factorisation backends (LinearSolver), which must solve the
// same system to rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "../../../solver/src/conic/linear_solver.hpp"
#include "../../../solver/src/conic/residuals.hpp"
#include "../../../solver/src/conic/variables.hpp"

using namespace rbla::conic;
using namespace rbla::conic::detail;

namespace {

/// Metrics of a point that is neither converged nor a certificate.
Metrics far_from_converged() {
  Metrics m;
  m.res_primal = m.res_dual = 1e-2;
  m.gap_abs = m.gap_rel = 1e-1;
  return m;
}

Variables point(double tau, double kappa) {
  Variables v;
  v.x = Vec::Ones(3);
  v.y = Vec::Zero(2);
  v.z = Vec::Ones(3);
  v.tau = tau;
  v.kappa = kappa;
  return v;
}

}  // namespace

TEST(ConicResiduals, ContinuesAwayFromEveryStoppingRule) {
  Settings s;
  Residuals r;
  r.metrics = far_from_converged();
  r.mu = 1.0;
  EXPECT_FALSE(r.check_termination(s, 3, 0.0, point(1, 1)).has_value());
}

TEST(ConicResiduals, SolvedWhenFeasibleAndEitherGapIsMet) {
  Settings s;
  Residuals r;
  r.mu = 1e-12;
  r.metrics = far_from_converged();
  r.metrics.res_primal = r.metrics.res_dual = 0.5 * s.tol_feas;
  r.metrics.gap_abs = 0.5 * s.tol_gap_abs;  // gap_rel still large: one of the two suffices
  const auto t = r.check_termination(s, 7, 0.0, point(1, 1));
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(t->status, SolveStatus::Solved);
  EXPECT_TRUE(t->reason.empty());
  r.metrics.res_dual = 2 * s.tol_feas;  // feasibility is not optional
  EXPECT_FALSE(r.check_termination(s, 7, 0.0, point(1, 1)).has_value());
}

TEST(ConicResiduals, CertificatesBelowTolInfeas) {
  Settings s;
  Residuals r;
  r.mu = 1.0;
  r.metrics = far_from_converged();
  r.metrics.primal_cert = 0.5 * s.tol_infeas;
  auto t = r.check_termination(s, 4, 0.0, point(1e-3, 1));
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(t->status, SolveStatus::PrimalInfeasible);
  r.metrics = far_from_converged();
  r.metrics.dual_cert = 0.5 * s.tol_infeas;
  t = r.check_termination(s, 4, 0.0, point(1e-3, 1));
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(t->status, SolveStatus::DualInfeasible);
}

TEST(ConicResiduals, StagnatedCertificateAcceptedAtReducedTolerance) {
  Settings s;
  Residuals r;
  r.mu = 1.0;
  const double cert = 0.5 * (s.tol_infeas + s.reduced_tol_infeas);
  int iter = 0;
  std::optional<Termination> t;
  for (; iter < 100 && !t; ++iter) {
    r.metrics = far_from_converged();
    r.metrics.primal_cert = cert;  // never halves again after the first iteration
    t = r.check_termination(s, iter, 0.0, point(1e-3, 1));  // τ < κ: heading for a certificate
  }
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(t->status, SolveStatus::PrimalInfeasible);
  EXPECT_FALSE(t->reason.empty());
  EXPECT_EQ(iter - 1, s.stall_max_iter + 1);
  EXPECT_EQ(r.metrics.primal_cert, cert);
  // The same certificate while τ ≥ κ is not taken: the embedding may still reach a solution.
  Residuals again;
  again.mu = 1.0;
  for (int k = 0; k < 3 * s.stall_max_iter; ++k) {
    again.metrics = far_from_converged();
    again.metrics.primal_cert = cert;
    EXPECT_FALSE(again.check_termination(s, k, 0.0, point(1, 1e-3)).has_value());
  }
}

TEST(ConicResiduals, LimitsAndNonFiniteIterates) {
  Settings s;
  Residuals r;
  r.metrics = far_from_converged();
  r.mu = 1.0;
  auto t = r.check_termination(s, s.max_iter, 0.0, point(1, 1));
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(t->status, SolveStatus::IterationLimit);
  s.time_limit_seconds = 2.0;
  t = r.check_termination(s, 1, 2.5, point(1, 1));
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(t->status, SolveStatus::TimeLimit);
  r.mu = std::numeric_limits<double>::quiet_NaN();
  t = r.check_termination(s, 1, 0.0, point(1, 1));
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(t->status, SolveStatus::NumericalFailure);
  EXPECT_EQ(t->reason, "non-finite iterate");
}

TEST(ConicResiduals, ReducedAccuracyFallbackUsesTheBestIterate) {
  Settings s;
  Residuals r;
  r.mu = 1.0;
  r.metrics = far_from_converged();
  r.metrics.res_primal = r.metrics.res_dual = 0.5 * s.reduced_tol_feas;
  r.metrics.gap_rel = 0.5 * s.reduced_tol_gap_rel;
  r.metrics.primal_objective = 42.0;
  r.track_best(s);
  r.metrics = far_from_converged();  // a later, worse iterate
  r.track_best(s);
  const Termination stalled{SolveStatus::NumericalFailure, "step too short (stalled)"};
  const Termination t = r.reduced_accuracy_fallback(s, stalled, point(1, 1));
  EXPECT_EQ(t.status, SolveStatus::SolvedInaccurate);
  EXPECT_EQ(t.reason, stalled.reason);  // why it stopped early is kept
  EXPECT_EQ(r.metrics.primal_objective, 42.0);
  // A cancelled or converged outcome is never replaced.
  const Termination cancelled{SolveStatus::Cancelled, {}};
  EXPECT_EQ(r.reduced_accuracy_fallback(s, cancelled, point(1, 1)).status, SolveStatus::Cancelled);
}

TEST(ConicVariables, StepMuAndHomogeneousRescaling) {
  Variables v;
  v.set_identity(Vec::Ones(3), 2);
  EXPECT_EQ(v.y.size(), 2);
  EXPECT_DOUBLE_EQ(v.mu(3.0), (3.0 + 1.0) / 4.0);
  Direction d;
  d.x = Vec::Constant(3, -1.0);
  d.y = Vec::Constant(2, 2.0);
  d.z = Vec::Constant(3, 0.5);
  d.tau = -0.5;
  d.kappa = 1.0;
  v.take_step(d, 0.5);
  EXPECT_DOUBLE_EQ(v.x[0], 0.5);
  EXPECT_DOUBLE_EQ(v.y[1], 1.0);
  EXPECT_DOUBLE_EQ(v.z[2], 1.25);
  EXPECT_DOUBLE_EQ(v.tau, 0.75);
  EXPECT_DOUBLE_EQ(v.kappa, 1.5);
  // Inside [1e-4, 1e4] the iterate keeps its scale; outside, max(τ, κ) becomes 1 and the
  // normalised quantities (x/τ, κ/τ) do not change.
  EXPECT_FALSE(v.normalise());
  v.x *= 1e6;
  v.y *= 1e6;
  v.z *= 1e6;
  v.tau *= 1e6;
  v.kappa *= 1e6;
  const double x_over_tau = v.x[0] / v.tau;
  EXPECT_TRUE(v.normalise());
  EXPECT_DOUBLE_EQ(std::max(v.tau, v.kappa), 1.0);
  EXPECT_DOUBLE_EQ(v.x[0] / v.tau, x_over_tau);
  Direction other;
  other.tau = 7.0;
  other.x = Vec::Zero(1);
  d.swap(other);
  EXPECT_EQ(d.tau, 7.0);
  EXPECT_EQ(other.x.size(), 3);
}

namespace {

/// The 2-D five-point Laplacian on a k × k grid plus the identity (SPD), lower triangle in
/// compressed columns with sorted rows (the diagonal first), as NormalEquations builds M.
struct GridMatrix {
  int n = 0;
  std::vector<int> col_ptr, row_ind;
  std::vector<double> values;
  explicit GridMatrix(int k) : n(k * k) {
    col_ptr.push_back(0);
    for (int j = 0; j < n; ++j) {
      row_ind.push_back(j);
      values.push_back(5.0);
      if (j % k + 1 < k) {  // right neighbour
        row_ind.push_back(j + 1);
        values.push_back(-1.0);
      }
      if (j + k < n) {  // upper neighbour
        row_ind.push_back(j + k);
        values.push_back(-1.0);
      }
      col_ptr.push_back(static_cast<int>(row_ind.size()));
    }
  }
  Vec multiply(const Vec& v, double shift) const {
    Vec out = shift * v;
    for (int j = 0; j < n; ++j) {
      for (int p = col_ptr[j]; p < col_ptr[j + 1]; ++p) {
        const int i = row_ind[p];
        out[i] += values[p] * v[j];
        if (i != j) out[j] += values[p] * v[i];
      }
    }
    return out;
  }
};

}  // namespace

TEST(ConicLinearSolver, BackendsSolveTheSameSystem) {
  const GridMatrix M(40);
  ForkJoin fork_join;
  auto split = SplitDomainSolver::create(Ordering::Best, fork_join, M.n, M.col_ptr.data(),
                                         M.row_ind.data());
  ASSERT_NE(split, nullptr) << "a 40 x 40 grid is large enough to split";
  // SplitDomainSolver needs each domain's share of the separator–separator entries: here all
  // of an entry goes to domain 0.
  const auto& slot_of = split->split().separator_slot();
  for (std::size_t p = 0; p < slot_of.size(); ++p) {
    if (slot_of[p] < 0) continue;
    split->share(0)[static_cast<std::size_t>(slot_of[p])] = M.values[p];
    split->share(1)[static_cast<std::size_t>(slot_of[p])] = 0.0;
  }
  const std::unique_ptr<LinearSolver> one =
      make_linear_solver(Ordering::Best, nullptr, M.n, M.col_ptr.data(), M.row_ind.data());
  EXPECT_EQ(one->name().rfind("CHOLMOD", 0), 0u);
  EXPECT_EQ(split->blas_threads(4), 1);
  EXPECT_EQ(one->blas_threads(4), 4);
  const double shift = 1e-3;
  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd rhs(M.n, 2);
  for (Eigen::Index k = 0; k < rhs.size(); ++k) rhs.data()[k] = normal(random);
  for (LinearSolver* solver : {one.get(), static_cast<LinearSolver*>(split.get())}) {
    SCOPED_TRACE(solver->name());
    ASSERT_TRUE(solver->factorize(M.values.data(), shift));
    EXPECT_GT(solver->factor_nonzeros(), static_cast<long>(M.values.size()) - 1);
    Eigen::MatrixXd x = rhs;
    solver->solve(x.data(), 2);
    for (int c = 0; c < 2; ++c) {
      const Vec residual = M.multiply(x.col(c), shift) - rhs.col(c);
      EXPECT_LT(residual.lpNorm<Eigen::Infinity>(), 1e-12 * rhs.col(c).lpNorm<Eigen::Infinity>());
    }
  }
  Eigen::MatrixXd a = rhs, b = rhs;
  one->solve(a.data(), 2);
  split->solve(b.data(), 2);
  EXPECT_LT((a - b).lpNorm<Eigen::Infinity>(), 1e-12 * a.lpNorm<Eigen::Infinity>());
}

TEST(ConicLinearSolver, BackendsReportAnIndefiniteMatrix) {
  const GridMatrix M(40);
  ForkJoin fork_join;
  auto split = SplitDomainSolver::create(Ordering::Amd, fork_join, M.n, M.col_ptr.data(),
                                         M.row_ind.data());
  ASSERT_NE(split, nullptr);
  const auto& slot_of = split->split().separator_slot();
  for (std::size_t p = 0; p < slot_of.size(); ++p)
    if (slot_of[p] >= 0) split->share(0)[static_cast<std::size_t>(slot_of[p])] = M.values[p];
  const std::unique_ptr<LinearSolver> one =
      make_linear_solver(Ordering::Amd, nullptr, M.n, M.col_ptr.data(), M.row_ind.data());
  // The Laplacian part's eigenvalues lie in (0, 8): a shift of −20 leaves 5 − 20 + (0..8) < 0.
  EXPECT_FALSE(one->factorize(M.values.data(), -20.0));
  EXPECT_FALSE(split->factorize(M.values.data(), -20.0));
  EXPECT_TRUE(one->factorize(M.values.data(), 0.0));
  EXPECT_TRUE(split->factorize(M.values.data(), 0.0));
}
