// The interior-point method: homogeneous self-dual embedding (variables.hpp), Nesterov–Todd
// scaling (cone.hpp), the Newton system reduced to the normal equations (kkt_system.hpp),
// Mehrotra predictor–corrector with Gondzio's centrality correctors (step_strategy.hpp),
// residuals and stopping rules (residuals.hpp), starting points (starting_point.hpp) and the
// iteration log (iteration_log.hpp). ConicSolver::Impl holds what lives from one solve to the
// next (equilibrated data, symbolic factorisation); a Run holds one solve's state, and its loop
// is the list of steps of Clarabel's solver.rs: residuals, termination, scaling, factorisation,
// directions and step, take the step.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <limits>
#include <optional>

#include "iteration_log.hpp"
#include "kkt_system.hpp"
#include "sparse_cholesky.hpp"
#include "rbla/conic/solver.hpp"
#include "residuals.hpp"
#include "scaled_problem.hpp"
#include "starting_point.hpp"
#include "step_strategy.hpp"

namespace rbla::conic {

using detail::Vec;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// MemAvailable from /proc/meminfo in bytes, 0 when it cannot be read (not Linux).
double available_memory_bytes() {
  std::FILE* file = std::fopen("/proc/meminfo", "r");
  if (!file) return 0.0;
  char line[256];
  double kib = 0.0;
  while (std::fgets(line, sizeof line, file)) {
    if (std::sscanf(line, "MemAvailable: %lf kB", &kib) == 1) break;
  }
  std::fclose(file);
  return kib * 1024.0;
}

void throw_if_invalid(const Settings& settings) {
  const auto messages = settings.validate();
  if (!messages.empty()) throw ConicSetupError::from_messages("invalid solver settings", messages);
}

}  // namespace

struct ConicSolver::Impl {
  ConicProblem problem;
  Settings settings;
  ProgressCallback callback;
  // The second thread (Settings::threads), for problems of at least split_min_rows rows: the
  // split normal matrix, its assembly, the products with A and the cone operations.
  std::unique_ptr<detail::ForkJoin> fork_join;
  detail::ConeSet cones;
  std::vector<detail::ScalingBlock> blocks;
  std::vector<bool> is_dense;
  detail::ScaledProblem scaled;
  std::unique_ptr<detail::KktSystem> kkt;
  std::vector<double> packed_W2;
  double setup_seconds = 0;
  double symbolic_seconds = 0;
  bool has_warm_start = false;
  Vec warm_x, warm_y, warm_z;  // original units, consumed by the next solve()

  Impl(ConicProblem p, Settings s);
  void check_memory() const;
  void detect_dense_columns();
  void rescale();
  Solution solve(bool allow_least_squares_start);
  class Run;
};

ConicSolver::Impl::Impl(ConicProblem p, Settings s)
    : problem(std::move(p)), settings(std::move(s)) {
  const auto start = Clock::now();
  const auto messages = problem.validate();
  if (!messages.empty()) throw ConicSetupError::from_messages("invalid conic problem", messages);
  throw_if_invalid(settings);
  if (settings.threads >= 2 && problem.A.rows() >= settings.split_min_rows)
    fork_join = std::make_unique<detail::ForkJoin>();
  cones = detail::ConeSet(problem.cones.num_nonneg, problem.cones.soc_dims, fork_join.get());
  blocks = cones.scaling_blocks();
  std::size_t packed_size = 0;
  for (const auto& blk : blocks) packed_size += static_cast<std::size_t>(blk.size * blk.size);
  packed_W2.assign(packed_size, 0.0);
  detect_dense_columns();
  scaled = detail::ScaledProblem(fork_join.get());
  rescale();
  const auto symbolic_start = Clock::now();
  auto normal = std::make_unique<detail::NormalEquations>(scaled.A(), blocks, is_dense,
                                                          settings.ordering, fork_join.get());
  kkt = std::make_unique<detail::KktSystem>(std::move(normal), scaled, cones, settings);
  symbolic_seconds = seconds_since(symbolic_start);
  check_memory();
  setup_seconds = seconds_since(start);
}

// Refuses a factor larger than the memory limit (Settings::memory_limit_bytes) before the
// numeric factorisation allocates it.
void ConicSolver::Impl::check_memory() const {
  double limit = settings.memory_limit_bytes;
  if (limit == 0) limit = 0.8 * available_memory_bytes();
  const detail::NormalEquations& normal = kkt->first_normal();
  const double need = normal.factor_bytes();
  if (limit > 0 && need > limit) {
    char text[400];
    std::snprintf(text, sizeof text,
                  "the Cholesky factor of the normal matrix (%lld rows, %ld nonzeros in L) "
                  "needs %.2f GB, more than the %.2f GB this solve may use; use a coarser "
                  "model, the planar formulation or a pyramid cone, or a machine with more "
                  "memory",
                  static_cast<long long>(problem.A.rows()), normal.factor_nonzeros(),
                  need / 1e9, limit / 1e9);
    throw ConicResourceError(text);
  }
  // What MemAvailable does not see: an address-space limit (ulimit -v), under which OpenBLAS
  // would wait forever for its buffers (detail::blas_buffer_bytes_to_reserve). The probe adds
  // 16 MiB for CHOLMOD's workspace and the solve's vectors.
  const int blas_callers = fork_join ? 2 : 1;
  const double probe = need + detail::blas_buffer_bytes_to_reserve(blas_callers) + 16.0 * (1 << 20);
  if (!detail::can_allocate(probe)) {
    char text[300];
    std::snprintf(text, sizeof text,
                  "the Cholesky factor of the normal matrix and the BLAS work space need "
                  "%.2f GB more, which this process may not allocate (its address-space "
                  "limit, ulimit -v, or the system's memory)",
                  probe / 1e9);
    throw ConicResourceError(text);
  }
}

// Dense columns: see Settings::dense_column_*. Only nonnegative variables qualify, because an
// SOC's W² couples its columns and cannot be split off column by column.
void ConicSolver::Impl::detect_dense_columns() {
  const Eigen::Index n = problem.A.cols();
  is_dense.assign(static_cast<std::size_t>(n), false);
  if (!settings.dense_columns || settings.dense_column_max == 0) return;
  const double mean = static_cast<double>(problem.A.nonZeros()) /
                      static_cast<double>(std::max<Eigen::Index>(n, 1));
  const double threshold = std::max(static_cast<double>(settings.dense_column_min_nnz),
                                    settings.dense_column_ratio * mean);
  std::vector<std::pair<long, Eigen::Index>> candidates;
  for (Eigen::Index j = 0; j < problem.cones.num_nonneg; ++j) {
    const long nnz = problem.A.outerIndexPtr()[j + 1] - problem.A.outerIndexPtr()[j];
    if (static_cast<double>(nnz) >= threshold) candidates.push_back({nnz, j});
  }
  std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  const std::size_t keep =
      std::min(candidates.size(), static_cast<std::size_t>(settings.dense_column_max));
  for (std::size_t k = 0; k < keep; ++k)
    is_dense[static_cast<std::size_t>(candidates[k].second)] = true;
}

// Recomputes the equilibration from the current problem data and refreshes A, b, c.
void ConicSolver::Impl::rescale() {
  scaled.rescale(problem, settings, blocks);
  if (kkt) kkt->set_A_values(scaled.A());
}

/// One solve's state: the iterate, its residuals, the step and the record (Info, log).
class ConicSolver::Impl::Run {
 public:
  Run(Impl& impl, detail::KktSystem& kkt, bool allow_least_squares_start);
  Solution execute();

 private:
  void start_info();
  void choose_start();
  IterationRow record_row(int iter);
  std::optional<detail::Termination> take_step();
  bool compute_direction();
  Solution finish(detail::Termination outcome);

  Impl& impl_;
  detail::KktSystem& kkt_;
  const Settings& s_;
  const bool allow_least_squares_start_;
  const Clock::time_point start_ = Clock::now();
  // One BLAS thread except inside the factorisations (Settings::blas_threads).
  const int factor_threads_;
  const detail::BlasThreads one_blas_thread_{1};
  std::ostream* log_;
  const double degree_;
  Info info_;
  detail::Variables v_;
  detail::Residuals residuals_;
  detail::StepStrategy strategy_;
  detail::Step step_;
  Iterate snapshot_;
  double last_step_ = 0, last_sigma_ = 0;
  int last_refine_ = 0;
  int short_steps_ = 0;
};

ConicSolver::Impl::Run::Run(Impl& impl, detail::KktSystem& kkt, bool allow_least_squares_start)
    : impl_(impl),
      kkt_(kkt),
      s_(impl.settings),
      allow_least_squares_start_(allow_least_squares_start),
      factor_threads_(s_.blas_threads > 0 ? s_.blas_threads : detail::current_blas_threads()),
      log_(s_.verbose ? (s_.log_stream ? s_.log_stream : &std::cout) : nullptr),
      degree_(static_cast<double>(impl.cones.degree())),
      strategy_(impl.cones, impl.settings) {
  kkt_.reset();
  kkt_.take_refine_steps();
}

Solution ConicSolver::Impl::Run::execute() {
  start_info();
  choose_start();
  detail::Termination outcome;
  for (int iter = 0;; ++iter) {
    residuals_.update(impl_.problem, impl_.scaled, v_, degree_, s_);
    const IterationRow row = record_row(iter);
    if (auto stop = residuals_.check_termination(s_, iter, seconds_since(start_), v_)) {
      outcome = *stop;
      break;
    }
    if (impl_.callback && !impl_.callback(row)) {
      outcome = {SolveStatus::Cancelled, {}};
      break;
    }
    if (auto stop = take_step()) {
      outcome = *stop;
      break;
    }
  }
  return finish(residuals_.reduced_accuracy_fallback(s_, outcome, v_));
}

void ConicSolver::Impl::Run::start_info() {
  const detail::NormalEquations& normal = kkt_.first_normal();
  info_.backend = normal.backend_name();
  info_.setup_seconds = impl_.setup_seconds;
  info_.symbolic_seconds = impl_.symbolic_seconds;
  info_.num_dense_columns = normal.num_dense_columns();
  info_.num_factor_nonzeros = normal.factor_nonzeros();
  info_.factor_bytes = normal.factor_bytes();
  if (log_) detail::print_banner(*log_, impl_.problem, normal, info_);
}

// x = z = e unless a warm start (used once) or the least-squares point applies.
void ConicSolver::Impl::Run::choose_start() {
  const Eigen::Index n = impl_.scaled.A().cols(), m = impl_.scaled.A().rows();
  Vec e(n);
  impl_.cones.set_identity(e);
  v_.set_identity(e, m);
  if (impl_.has_warm_start) {
    impl_.has_warm_start = false;
    info_.warm_started = detail::warm_start(impl_.scaled, impl_.cones, s_, impl_.warm_x,
                                            impl_.warm_y, impl_.warm_z, v_);
    if (!info_.warm_started) v_.set_identity(e, m);
  }
  if (!info_.warm_started && s_.least_squares_start && allow_least_squares_start_)
    info_.least_squares_start = detail::least_squares_start(
        kkt_.normal(), impl_.scaled, impl_.cones, s_, factor_threads_, v_, info_);
}

IterationRow ConicSolver::Impl::Run::record_row(int iter) {
  const detail::Metrics& metrics = residuals_.metrics;
  IterationRow row;
  row.iteration = iter;
  row.primal_objective = metrics.primal_objective;
  row.dual_objective = metrics.dual_objective;
  row.gap_rel = metrics.gap_rel;
  row.res_primal = metrics.res_primal;
  row.res_dual = metrics.res_dual;
  row.mu = residuals_.mu;
  row.tau = v_.tau;
  row.kappa = v_.kappa;
  row.step = last_step_;
  row.sigma = last_sigma_;
  row.refine_steps = last_refine_;
  row.elapsed_seconds = seconds_since(start_);
  info_.history.push_back(row);
  info_.iterations = iter;
  if (log_) detail::print_row(*log_, row);
  if (s_.snapshot_gap_rel > 0 && snapshot_.empty() && metrics.gap_rel < s_.snapshot_gap_rel)
    snapshot_ = {metrics.x, metrics.y, metrics.z};
  return row;
}

// Scaling, factorisation, direction and step length; then the step itself.
std::optional<detail::Termination> ConicSolver::Impl::Run::take_step() {
  if (!impl_.cones.update_scaling(v_.x, v_.z))
    return detail::Termination{SolveStatus::NumericalFailure,
                               "iterate left the cone interior (NT scaling undefined)"};
  impl_.cones.pack_W2(impl_.packed_W2);
  kkt_.begin_iteration(residuals_,
                       v_, detail::direction_accuracy(impl_.problem, impl_.scaled, s_, residuals_, v_));
  strategy_.begin_iteration(v_, residuals_.mu);
  if (!compute_direction())
    return detail::Termination{SolveStatus::NumericalFailure,
                               "factorisation failed after all regularisation retries"};
  const double alpha = step_.alpha;
  short_steps_ = alpha < s_.stall_step ? short_steps_ + 1 : 0;
  if (!(alpha >= s_.step_min) || short_steps_ > s_.stall_max_iter)
    return detail::Termination{SolveStatus::NumericalFailure, "step too short (stalled)"};
  v_.take_step(step_.direction, alpha);
  last_step_ = alpha;
  last_sigma_ = step_.sigma;
  last_refine_ = kkt_.take_refine_steps();
  v_.normalise();
  return std::nullopt;
}

// Factors M and computes the step; if the bordered dense-column solve lost accuracy, once more
// with the dense columns inside the sparse factor. False when the factorisation failed.
bool ConicSolver::Impl::Run::compute_direction() {
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (!kkt_.factor(impl_.packed_W2, factor_threads_, info_)) return false;
    const auto solve_start = Clock::now();
    strategy_.compute(kkt_, step_, info_);
    info_.solve_seconds += seconds_since(solve_start);
    if (!kkt_.refinement_failed()) break;
    if (!kkt_.drop_dense_columns(impl_.is_dense, s_.ordering, impl_.fork_join.get(), info_)) break;
    if (log_)
      *log_ << "      dense columns moved into the sparse factor (bordered solve inaccurate)\n";
  }
  return true;
}

Solution ConicSolver::Impl::Run::finish(detail::Termination outcome) {
  const detail::Metrics& metrics = residuals_.metrics;
  const Eigen::Index n = impl_.scaled.A().cols(), m = impl_.scaled.A().rows();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Solution solution;
  switch (outcome.status) {
    case SolveStatus::PrimalInfeasible:
      solution.x = Vec::Constant(n, nan);
      solution.y = metrics.y_cert;
      solution.z = metrics.z_cert;
      info_.certificate_residual = metrics.primal_cert;
      break;
    case SolveStatus::DualInfeasible:
      solution.x = metrics.x_cert;
      solution.y = Vec::Constant(m, nan);
      solution.z = Vec::Constant(n, nan);
      info_.certificate_residual = metrics.dual_cert;
      break;
    case SolveStatus::Solved:
    case SolveStatus::SolvedInaccurate:
    case SolveStatus::IterationLimit:
    case SolveStatus::TimeLimit:
    case SolveStatus::NumericalFailure:
    case SolveStatus::Cancelled:
      solution.x = metrics.x;
      solution.y = metrics.y;
      solution.z = metrics.z;
      break;
  }
  // A run that stopped before its first measures (data whose norms overflow, such as a cost of
  // 1.1e301, found by the fuzz smoke run) still returns vectors of the problem's sizes: NaN where
  // nothing was computed.
  if (solution.x.size() != n) solution.x = Vec::Constant(n, nan);
  if (solution.y.size() != m) solution.y = Vec::Constant(m, nan);
  if (solution.z.size() != n) solution.z = Vec::Constant(n, nan);
  // Nor does it claim a solution it cannot give in double precision.
  const bool claims_solution = outcome.status == SolveStatus::Solved || outcome.status == SolveStatus::SolvedInaccurate;
  if (claims_solution && !(solution.x.allFinite() && solution.y.allFinite() && solution.z.allFinite())) {
    outcome = {SolveStatus::NumericalFailure, "the solution is not finite in double precision (data too large?)"};
  }
  info_.status = outcome.status;
  info_.failure_reason = outcome.reason;
  info_.primal_objective = metrics.primal_objective;
  info_.dual_objective = metrics.dual_objective;
  info_.gap_abs = metrics.gap_abs;
  info_.gap_rel = metrics.gap_rel;
  info_.res_primal = metrics.res_primal;
  info_.res_dual = metrics.res_dual;
  info_.step = last_step_;
  info_.total_seconds = seconds_since(start_);
  if (log_) {
    const detail::NormalEquations& first = kkt_.first_normal();
    const detail::NormalEquations* fallback = kkt_.fallback_normal();
    detail::print_footer(
        *log_, info_, first.num_factor_solves() + (fallback ? fallback->num_factor_solves() : 0),
        first.num_multiplies() + (fallback ? fallback->num_multiplies() : 0));
  }
  solution.info = std::move(info_);
  solution.snapshot = std::move(snapshot_);
  return solution;
}

Solution ConicSolver::Impl::solve(bool allow_least_squares_start) {
  throw_if_invalid(settings);
  return Run(*this, *kkt, allow_least_squares_start).execute();
}

// ---- Public wrapper ----

ConicSolver::ConicSolver(ConicProblem problem, Settings settings)
    : impl_(std::make_unique<Impl>(std::move(problem), std::move(settings))) {}
ConicSolver::~ConicSolver() = default;
ConicSolver::ConicSolver(ConicSolver&&) noexcept = default;
ConicSolver& ConicSolver::operator=(ConicSolver&&) noexcept = default;

Solution ConicSolver::solve() {
  Solution solution = impl_->solve(true);
  // The least-squares start can sit badly with extreme data (unit weights 1e6 apart: the first
  // step stalled; a random SOCP stalled at iteration 10 and was only "solved inaccurate"). A solve
  // from it that ended in a numerical failure, or was rescued from one by the reduced tolerances,
  // is repeated once from x = z = e, and the better outcome is returned.
  Settings& s = impl_->settings;
  const SolveStatus status = solution.info.status;
  const bool numerical_trouble =
      status == SolveStatus::NumericalFailure ||
      (status == SolveStatus::SolvedInaccurate && !solution.info.failure_reason.empty());
  const double spent = solution.info.total_seconds;
  if (!solution.info.least_squares_start || !numerical_trouble || !(spent < s.time_limit_seconds))
    return solution;
  if (s.verbose)
    *(s.log_stream ? s.log_stream : &std::cout)
        << "      numerical trouble from the least-squares start; solving again from x = z = e\n";
  const double time_limit = s.time_limit_seconds;
  s.time_limit_seconds = time_limit - spent;
  Solution again = impl_->solve(false);
  s.time_limit_seconds = time_limit;
  const bool better = again.info.status == SolveStatus::Solved ||
                      (again.info.status == SolveStatus::SolvedInaccurate &&
                       status == SolveStatus::NumericalFailure);
  Solution& kept = better ? again : solution;
  kept.info.total_seconds = spent + again.info.total_seconds;
  kept.info.restarted = true;
  return std::move(kept);
}

void ConicSolver::update_b(const Eigen::VectorXd& b) {
  if (b.size() != impl_->problem.b.size()) throw ConicSetupError("update_b: wrong length");
  if (!b.allFinite()) throw ConicSetupError("update_b: b is not finite");
  impl_->problem.b = b;
  impl_->rescale();
}

void ConicSolver::update_c(const Eigen::VectorXd& c) {
  if (c.size() != impl_->problem.c.size()) throw ConicSetupError("update_c: wrong length");
  if (!c.allFinite()) throw ConicSetupError("update_c: c is not finite");
  impl_->problem.c = c;
  impl_->rescale();
}

void ConicSolver::update_A_values(const Eigen::VectorXd& values) {
  auto& A = impl_->problem.A;
  if (values.size() != A.nonZeros()) throw ConicSetupError("update_A_values: wrong length");
  if (!values.allFinite()) throw ConicSetupError("update_A_values: values are not finite");
  std::copy(values.data(), values.data() + values.size(), A.valuePtr());
  impl_->rescale();
}

void ConicSolver::update(const ConicProblem& problem) {
  if (!same_shape(impl_->problem, problem))
    throw ConicSetupError("update: another shape, sparsity pattern or cones than the solver's problem");
  if (problem.b.size() != problem.A.rows() || problem.c.size() != problem.A.cols())
    throw ConicSetupError("update: wrong length of b or c");
  if (!problem.A.coeffs().allFinite() || !problem.b.allFinite() || !problem.c.allFinite())
    throw ConicSetupError("update: data are not finite");
  impl_->problem.A = problem.A;
  impl_->problem.b = problem.b;
  impl_->problem.c = problem.c;
  impl_->rescale();
}

void ConicSolver::set_warm_start(const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                                 const Eigen::VectorXd& z) {
  impl_->warm_x = x;
  impl_->warm_y = y;
  impl_->warm_z = z;
  impl_->has_warm_start = true;
}

void ConicSolver::set_progress_callback(ProgressCallback callback) {
  impl_->callback = std::move(callback);
}
Settings& ConicSolver::settings() { return impl_->settings; }
const ConicProblem& ConicSolver::problem() const { return impl_->problem; }
int ConicSolver::num_symbolic_analyses() const {
  const detail::NormalEquations* fallback = impl_->kkt->fallback_normal();
  return impl_->kkt->first_normal().num_analyses() + (fallback ? fallback->num_analyses() : 0);
}

Solution solve(const ConicProblem& problem, const Settings& settings) {
  return ConicSolver(problem, settings).solve();
}

}  // namespace rbla::conic
