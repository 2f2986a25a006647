#pragma once
// Solver settings: a plain struct, the default at each field, the criterion and unit in the
// comment (Clarabel / OSQP style). Stopping criteria are stated once, at Settings::tol_*.

#include <limits>
#include <ostream>
#include <string>
#include <vector>

namespace rbla::conic {

/// Fill-reducing ordering used by CHOLMOD for the normal matrix (symbolic analysis, once).
/// Best: both AMD and METIS nested dissection, keeping the one with the smaller factor. On
/// masonry walls (a planar mesh of blocks, 3 or 6 rows each) METIS wins as soon as extra rows tie
/// neighbouring blocks (the per-block load-multiplier copies): 3.4e8 against 7.2e8 flops per
/// factorisation on the 1920-block façade in 3-D, with AMD slightly ahead without them.
enum class Ordering { Best, Amd, Metis, CholmodDefault };
const char* to_string(Ordering ordering);

struct Settings {
  // ---- Termination (all measured on the original, unscaled problem; x, y, z = iterate / τ) ----
  // Solved when all of:
  //   res_primal = ‖A x − b‖∞ / max(1, ‖b‖∞ + ‖x‖∞)                  ≤ tol_feas
  //   res_dual   = ‖Aᵀy + z − c‖∞ / max(1, ‖c‖∞ + ‖y‖∞ + ‖z‖∞)       ≤ tol_feas
  //   gap_abs = max(|cᵀx − bᵀy|, xᵀz) ≤ tol_gap_abs   or
  //   gap_rel = gap_abs / max(1, min(|cᵀx|, |bᵀy|)) ≤ tol_gap_rel
  double tol_gap_abs = 1e-8;  ///< absolute duality gap, objective units
  double tol_gap_rel = 1e-8;  ///< relative duality gap, dimensionless
  double tol_feas = 1e-8;     ///< relative primal and dual residual, dimensionless
  // Primal infeasible when bᵀŷ > 0 and, with ȳ = ŷ/bᵀŷ, z̄ = ẑ/bᵀŷ (so bᵀȳ = 1, z̄ ∈ K*):
  //   ‖Aᵀȳ + z̄‖∞ ≤ tol_infeas.
  // Dual infeasible (unbounded) when cᵀx̂ < 0 and, with x̄ = x̂/(−cᵀx̂) ∈ K:  ‖A x̄‖∞ ≤ tol_infeas.
  // (A feasible problem can only pass the primal test if its solutions have ‖x‖₁ ≥ 1/tol_infeas.)
  double tol_infeas = 1e-8;  ///< certificate residual, units of A
  // When the iteration stops without meeting the tolerances above (iteration or time limit,
  // numerical failure, stalled steps), the best iterate seen (smallest max of the three ratios
  // residual/tolerance) is reported as SolvedInaccurate if it meets the same tests with these
  // looser values; otherwise the status stays and the last iterate is returned.
  double reduced_tol_gap_abs = 5e-5;
  double reduced_tol_gap_rel = 5e-5;
  double reduced_tol_feas = 1e-4;
  // An infeasibility certificate whose residual stops improving (no halving for more than
  // stall_max_iter iterations) while τ < κ is accepted at this looser tolerance; also at the
  // fallback above. Info::certificate_residual and Info::failure_reason then say so.
  double reduced_tol_infeas = 1e-5;

  /// Interior-point iterations. Degenerate problems (large planar settlement LPs) converge
  /// slowly near the end and need several times the iterations of small ones
  /// (docs/benchmark/measurements.md).
  int max_iter = 200;
  /// Start from the least-squares point (CVXOPT's and ECOS's default: min ‖x‖ s.t. Ax = b, min ‖z‖
  /// s.t. Aᵀy + z = c, shifted into the cone) instead of x = z = e; costs one factorisation.
  bool least_squares_start = true;
  double time_limit_seconds =
      std::numeric_limits<double>::infinity();  ///< wall time, checked per iteration

  // ---- Step ----
  double step_fraction = 0.99;
  /// Gondzio centrality correctors per iteration, each one extra solve with the current factor
  /// (kept only when it lengthens the step by 1 %); 0 gives plain Mehrotra.
  int max_centrality_correctors = 3;
  /// σ = (1 − α)³ with α the affine step past the first ⌈f ν⌉ factors that block it (ν the
  /// degree of K: one per R_+ entry and per second-order cone, primal and dual counted apart);
  /// 0 is Mehrotra's rule with the affine step itself. See StepStrategy::sigma_step.
  double sigma_skip_fraction = 1e-3;
  /// λ of ConicSolver::set_warm_start: the weight of the given point against the central start
  /// e, in (0, 1).
  double warm_start_weight = 0.9;
  /// When > 0, the first iterate whose relative gap falls below this is kept in
  /// Solution::snapshot: a well-centred point from which a nearby problem (same A, b, slightly
  /// different c or b) can be warm-started (Gondzio & Grothey 2008, "A new unblocking technique to
  /// warmstart interior point methods based on sensitivity analysis", SIAM J. Optim. 19: an
  /// iterate short of optimality warm-starts better than the optimum, which sits on the boundary).
  double snapshot_gap_rel = 0.0;
  double step_min = 1e-8;       ///< a step shorter than this is a stall: the solve stops
  /// More than stall_max_iter consecutive steps shorter than stall_step also stop the solve
  /// (NumericalFailure, or SolvedInaccurate if the best iterate meets the reduced tolerances).
  double stall_step = 1e-3;
  int stall_max_iter = 5;

  // ---- Scaling ----
  bool equilibrate = true;                ///< Ruiz equilibration of A (plus scalar scaling of b, c)
  int equilibrate_max_iter = 15;          ///< Ruiz sweeps
  double equilibrate_min_scaling = 1e-4;  ///< clamp of the accumulated row/column factors and
  double equilibrate_max_scaling = 1e4;   ///< of the scalar factors of b and c

  // ---- Linear algebra: normal equations M = A W² Aᵀ, CHOLMOD supernodal LLᵀ ----
  /// Static regularisation: M + δI with δ = reg_static + ε² · max diag M (ε = machine epsilon),
  /// in units of the equilibrated M (whose data entries are O(1)).
  double reg_static = 1e-10;
  /// Recovery when CHOLMOD reports "not positive definite": δ ← δ · reg_retry_factor, refactor.
  double reg_retry_factor = 100.0;
  int reg_max_retries = 8;
  /// Iterative refinement (scaled problem). Each Newton direction is corrected on its primal
  /// and gap equations (e_p = A dx − b dτ + η r_p, e_g) until max(‖e_p‖∞, |e_g|) ≤
  /// max(refine_tol_rel · (1 + ‖b‖∞ τ), 1e-3 ‖r_p‖∞), or until the residual the errors leave
  /// (about e/η) would stay under a tenth of tol_gap_rel in the objective (measured as
  /// |y|ᵀ|e_p| and |e_g|) and of tol_feas in the primal residual, in original units. The first
  /// correction is one plain solve, later ones use preconditioned CG on M. A loop stops after
  /// refine_max_iter steps, when a correction made the error larger (it is taken back), or
  /// when the error stops halving (only after its first CG correction: a regularised plain
  /// solve can leave most of the error when M has eigenvalues below δ). The solve for q
  /// (M q = A W² c + b, shared by every direction) is plain; it is refined by CG to
  /// refine_tol_rel · (1 + ‖rhs‖∞) only if rounding made the dτ denominator non-positive. Of
  /// an iteration's directions only the one taken (the corrector or its last kept centrality
  /// corrector) is refined, and the predictor while τ < κ.
  int refine_max_iter = 10;
  double refine_tol_rel = 1e-13;
  Ordering ordering = Ordering::Best;
  /// Memory the Cholesky factor may take, bytes (read at construction). The factor's size is
  /// known exactly after the symbolic analysis; a larger one raises ConicResourceError instead
  /// of letting the system kill the process mid-solve. 0: 80 % of MemAvailable
  /// (/proc/meminfo), no limit where that cannot be read.
  double memory_limit_bytes = 0.0;
  /// OpenBLAS threads in the numeric factorisations; 0 keeps the library's own setting (usually
  /// one per core). Everything else in a solve (triangular solves, products) runs on one BLAS
  /// thread (see detail::BlasThreads). Restored after the solve. One thread by default: the
  /// factors here are many small supernodes, where a second BLAS thread costs more in hand-overs
  /// and idle spinning than it gains (measurements: docs/benchmark/measurements.md). One thread
  /// also makes runs repeatable: with more, the order of blocked sums varies between runs, and
  /// with it the iteration count.
  int blas_threads = 1;
  /// Threads for the normal equations, 1 or 2 (read at construction). With 2, a normal matrix
  /// of at least split_min_rows rows is split by a node separator into two domains that are
  /// factored and solved concurrently (detail::SplitCholesky); below that size, or when the
  /// split is unbalanced or its separator large, one factor on one thread is used.
  int threads = 2;
  int split_min_rows = 4000;

  // ---- Dense columns (read at construction) ----
  // A column j of the nonnegative block is dense when
  //   nnz_j ≥ max(dense_column_min_nnz, dense_column_ratio · (mean nnz per column)).
  // Dense columns are kept out of the sparse factor and added back by a bordered (Schur
  // complement) solve of size ≤ dense_column_max; the densest are taken first.
  bool dense_columns = true;
  int dense_column_min_nnz = 40;
  double dense_column_ratio = 10.0;
  int dense_column_max = 20;

  // ---- Output ----
  bool verbose = false;                ///< write the iteration log
  std::ostream* log_stream = nullptr;  ///< where the log goes; null with verbose = std::cout

  /// Readable messages for every invalid field; empty if valid.
  std::vector<std::string> validate() const;
};

}  // namespace rbla::conic
