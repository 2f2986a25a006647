// libFuzzer harness for the conic solver alone: bytes read as a CBF problem
// (rbla::conic::read_cbf, the format `rbla solve --dump-problem` writes and
// bench/conic's rbla_conic_cbf_solve reads), then solved with the default settings under small
// limits (kMaxDimension rows and variables, kMaxNonzeros entries, kTimeLimitSeconds,
// kMaxIterations).
//
// Not findings: a rejection with ConicSetupError (bad file or problem data; ConicResourceError
// is one), and any status that does not claim an answer (iteration or time limit, numerical
// failure). Findings: crashes and sanitizer reports, any other exception, hangs and runaway
// memory, and a status whose claim does not hold on the problem as read: a solution that is not
// one (residuals, cones, gap recomputed here), or an infeasibility certificate that is not one.
#include "rbla/conic/io.hpp"
#include "rbla/conic/solver.hpp"
#include "unit/conic/test_helpers.hpp"

#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

namespace {

using rbla::conic::ConeSpec;
using rbla::conic::ConicProblem;
using rbla::conic::SolveStatus;
using Eigen::VectorXd;

constexpr Eigen::Index kMaxDimension = 400;
constexpr Eigen::Index kMaxNonzeros = 4000;
constexpr double kTimeLimitSeconds = 2.0;
constexpr int kMaxIterations = 100;
/// The recomputed measures may exceed the solver's tolerances by this factor: they are the same
/// formulas, evaluated again in another order of summation.
constexpr double kSlack = 10.0;

[[noreturn]] void broken(const std::string& what) {
  std::fprintf(stderr, "fuzz_conic: the outcome breaks its claim: %s\n", what.c_str());
  std::abort();
}

double inf_norm(const VectorXd& v) { return v.size() ? v.lpNorm<Eigen::Infinity>() : 0.0; }

/// How far v is outside K (0 if inside), as the conic unit tests measure it.
double outside(const VectorXd& v, const ConeSpec& cones) { return rbla::conic::testing::cone_violation(v, cones); }

/// outside() relative to max(1, |v|inf).
double cone_violation(const VectorXd& v, const ConeSpec& cones) { return outside(v, cones) / std::max(1.0, inf_norm(v)); }

/// Settings::tol_* as documented in rbla/conic/settings.hpp, recomputed on the problem as read.
void check_solved(const ConicProblem& p, const rbla::conic::Solution& s, const rbla::conic::Settings& settings) {
  const bool accurate = s.info.status == SolveStatus::Solved;
  const double tol_feas = accurate ? settings.tol_feas : settings.reduced_tol_feas;
  const double tol_gap_abs = accurate ? settings.tol_gap_abs : settings.reduced_tol_gap_abs;
  const double tol_gap_rel = accurate ? settings.tol_gap_rel : settings.reduced_tol_gap_rel;
  if (!s.x.allFinite() || !s.y.allFinite() || !s.z.allFinite()) broken("solution not finite");
  const double res_primal = inf_norm(p.A * s.x - p.b) / std::max(1.0, inf_norm(p.b) + inf_norm(s.x));
  const VectorXd aty = p.A.transpose() * s.y;
  const double res_dual =
      inf_norm(aty + s.z - p.c) / std::max(1.0, inf_norm(p.c) + inf_norm(s.y) + inf_norm(s.z));
  if (res_primal > kSlack * tol_feas) broken("primal residual " + std::to_string(res_primal));
  if (res_dual > kSlack * tol_feas) broken("dual residual " + std::to_string(res_dual));
  // x and z are interior iterates (divided by tau): in the cone up to rounding.
  if (cone_violation(s.x, p.cones) > 1e-9) broken("x outside the cone");
  if (cone_violation(s.z, p.cones) > 1e-9) broken("z outside the dual cone");
  const double cx = p.c.dot(s.x), by = p.b.dot(s.y);
  const double gap_abs = std::max(std::abs(cx - by), s.x.dot(s.z));
  const double gap_rel = gap_abs / std::max(1.0, std::min(std::abs(cx), std::abs(by)));
  if (gap_abs > kSlack * tol_gap_abs && gap_rel > kSlack * tol_gap_rel) broken("duality gap " + std::to_string(gap_rel));
}

/// A certificate of primal infeasibility: b'y > 0 and -A'y in K* (= K), after scaling to b'y = 1.
void check_primal_certificate(const ConicProblem& p, const rbla::conic::Solution& s,
                              const rbla::conic::Settings& settings) {
  const double bty = p.b.dot(s.y);
  if (!(bty > 0.0) || !s.y.allFinite()) broken("primal infeasible without b'y > 0");
  const VectorXd slack = -(p.A.transpose() * (s.y / bty));
  // The solver's test is |A'y + z|inf <= tol with z in K; the distance of -A'y from K is at most
  // sqrt(q) times that for a cone of size q.
  double q_max = 1.0;
  for (Eigen::Index q : p.cones.soc_dims) q_max = std::max(q_max, static_cast<double>(q));
  const double allowed = kSlack * std::sqrt(q_max) * std::max(settings.tol_infeas, settings.reduced_tol_infeas);
  const double worst = outside(slack, p.cones);
  if (worst > allowed) broken("primal infeasibility certificate off by " + std::to_string(worst));
}

/// A certificate of dual infeasibility (primal unbounded): c'x < 0, A x = 0, x in K, with c'x = -1.
void check_dual_certificate(const ConicProblem& p, const rbla::conic::Solution& s,
                            const rbla::conic::Settings& settings) {
  const double ctx = p.c.dot(s.x);
  if (!(ctx < 0.0) || !s.x.allFinite()) broken("dual infeasible without c'x < 0");
  const VectorXd x = s.x / (-ctx);
  const double allowed = kSlack * std::max(settings.tol_infeas, settings.reduced_tol_infeas);
  if (inf_norm(p.A * x) > allowed) broken("unboundedness certificate: A x = " + std::to_string(inf_norm(p.A * x)));
  const double worst = outside(x, p.cones);
  if (worst > allowed) broken("unboundedness certificate outside the cone by " + std::to_string(worst));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  rbla::conic::CbfLimits limits;
  limits.max_variables = kMaxDimension;
  limits.max_constraints = kMaxDimension;
  limits.max_nonzeros = kMaxNonzeros;
  ConicProblem problem;
  try {
    problem = rbla::conic::read_cbf(in, limits);
  } catch (const rbla::conic::ConicSetupError&) {
    return 0;  // not a CBF problem we read, or invalid problem data: rejected as documented
  }
  rbla::conic::Settings settings;
  settings.time_limit_seconds = kTimeLimitSeconds;
  settings.max_iter = kMaxIterations;
  settings.threads = 1;
  rbla::conic::Solution solution;
  try {
    solution = rbla::conic::solve(problem, settings);
  } catch (const rbla::conic::ConicSetupError&) {
    return 0;  // e.g. a factor over the memory limit (ConicResourceError)
  }
  const Eigen::Index n = problem.A.cols(), m = problem.A.rows();
  if (solution.x.size() != n || solution.y.size() != m || solution.z.size() != n) broken("solution sizes");
  switch (solution.info.status) {
    case SolveStatus::Solved:
    case SolveStatus::SolvedInaccurate: check_solved(problem, solution, settings); break;
    case SolveStatus::PrimalInfeasible: check_primal_certificate(problem, solution, settings); break;
    case SolveStatus::DualInfeasible: check_dual_certificate(problem, solution, settings); break;
    case SolveStatus::IterationLimit:
    case SolveStatus::TimeLimit:
    case SolveStatus::NumericalFailure:
    case SolveStatus::Cancelled: break;
  }
  return 0;
}
