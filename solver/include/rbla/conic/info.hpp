#pragma once
// Solve outcome: status, summary numbers mirroring the log columns, per-phase timings and the
// per-iteration history (for convergence plots).

#include <Eigen/Core>
#include <string>
#include <vector>

namespace rbla::conic {

enum class SolveStatus {
  Solved,            ///< all tolerances met; x, y, z are the primal/dual solution
  SolvedInaccurate,  ///< stopped early, but the reduced tolerances are met
  PrimalInfeasible,  ///< y is a certificate: bᵀy = 1, z = −Aᵀy ∈ K* up to tol_infeas (or
                     ///< reduced_tol_infeas, see failure_reason / certificate_residual); x NaN
  DualInfeasible,  ///< x is a certificate: cᵀx = −1, x ∈ K, A x ≈ 0 (primal unbounded); y, z NaN
  IterationLimit,    ///< max_iter reached; x, y, z are the last iterate
  TimeLimit,         ///< time_limit_seconds reached; last iterate
  NumericalFailure,  ///< factorisation failed after all retries, or the steps stalled
  Cancelled,         ///< the progress callback returned false
};
const char* to_string(SolveStatus status);
/// True for Solved and SolvedInaccurate.
bool has_solution(SolveStatus status);

/// One row of the iteration log (also passed to the progress callback).
struct IterationRow {
  int iteration = 0;
  double primal_objective = 0;  ///< cᵀx, x = x̂/τ, original units
  double dual_objective = 0;    ///< bᵀy
  double gap_rel = 0;           ///< see Settings::tol_gap_rel
  double res_primal = 0;        ///< see Settings::tol_feas
  double res_dual = 0;
  double mu = 0;   ///< complementarity (x̂ᵀẑ + τκ)/(ν+1), scaled problem
  double tau = 0;  ///< homogeneous embedding variables
  double kappa = 0;
  double step = 0;             ///< step length that produced this iterate (0 at iteration 0)
  double sigma = 0;            ///< centring parameter of that step
  int refine_steps = 0;        ///< iterative-refinement steps in the solves of that step
  double elapsed_seconds = 0;  ///< since the start of solve()
};

struct Info {
  SolveStatus status = SolveStatus::NumericalFailure;
  int iterations = 0;
  double primal_objective = 0;
  double dual_objective = 0;
  double gap_abs = 0;
  double gap_rel = 0;
  double res_primal = 0;
  double res_dual = 0;
  double certificate_residual = 0;  ///< ‖Aᵀȳ + z̄‖∞ or ‖A x̄‖∞ when infeasible, else 0
  double step = 0;                  ///< last step length

  double setup_seconds = 0;  ///< construction: validation, equilibration, pattern (incl. symbolic)
  double symbolic_seconds = 0;  ///< CHOLMOD analyse (part of setup)
  double assembly_seconds = 0;  ///< filling M's values, summed over iterations
  double factor_seconds =
      0;  ///< CHOLMOD numeric factorisations incl. retries and dense-column Schur
  double solve_seconds = 0;  ///< triangular solves incl. refinement
  double total_seconds = 0;  ///< solve() wall time (excludes setup)

  std::string failure_reason;    ///< why a NumericalFailure happened (kept when the
                                 ///< reduced-accuracy fallback made it SolvedInaccurate)
  int num_refactor_retries = 0;  ///< factorisations repeated with larger regularisation
  double factor_bytes = 0;      ///< memory of the Cholesky factor (from the symbolic analysis)
  bool warm_started = false;                   ///< started from set_warm_start's point
  bool least_squares_start = false;  ///< started from Settings::least_squares_start's point
  /// The solve from the least-squares start ran into numerical trouble and was repeated from
  /// x = z = e; the other fields describe the better of the two solves, total_seconds both.
  bool restarted = false;
  int num_centrality_correctors = 0;           ///< Gondzio correctors tried (extra solves)
  int num_centrality_correctors_accepted = 0;  ///< of which kept
  int num_dense_columns = 0;     ///< columns handled outside the sparse factor
  /// True if the bordered dense-column solve lost accuracy and the dense columns were moved into
  /// the sparse factor for the rest of the solve (one extra symbolic analysis).
  bool dense_column_fallback = false;
  long num_factor_nonzeros = 0;  ///< nnz(L) (with dense columns outside it, even after a fallback)
  std::string backend;           ///< e.g. "CHOLMOD supernodal LL' (AMD)"
  std::vector<IterationRow> history;

  /// One line: status, iterations, objective, gap, time.
  std::string brief_report() const;
};

/// An iterate in the original variables (x, y, z = iterate / τ).
struct Iterate {
  Eigen::VectorXd x, y, z;
  bool empty() const { return x.size() == 0; }
};

/// Solution in the original variables. Which vectors hold what depends on status (see SolveStatus).
struct Solution {
  Eigen::VectorXd x;  ///< primal, length n
  Eigen::VectorXd y;  ///< equality multipliers, length m
  Eigen::VectorXd z;  ///< dual slack c − Aᵀy, length n
  Info info;
  /// The first iterate below Settings::snapshot_gap_rel (empty when that is 0 or never reached):
  /// a warm start for ConicSolver::set_warm_start on a nearby problem.
  Iterate snapshot;
};

}  // namespace rbla::conic
