#pragma once
// Residuals of the homogeneous embedding (variables.hpp) at the current iterate, the quality of
// the iterate measured on the original (unscaled) problem, and the stopping rules.
//
//   r_p = A x − b τ,   r_d = −Aᵀy + c τ − z,   r_g = bᵀy − cᵀx − κ   (scaled problem)
//
// Converged (Settings::tol_*): with x/τ, y/τ, z/τ in original units,
//   ‖A x − b‖∞ / max(1, ‖b‖∞ + ‖x‖∞) ≤ tol_feas,
//   ‖Aᵀy + z − c‖∞ / max(1, ‖c‖∞ + ‖y‖∞ + ‖z‖∞) ≤ tol_feas,
//   gap_abs ≤ tol_gap_abs or gap_rel ≤ tol_gap_rel.
// Infeasible: a certificate normalised to bᵀȳ = 1 (primal) or cᵀx̄ = −1 (dual) with a residual
// ‖Aᵀȳ + z̄‖∞ or ‖A x̄‖∞ at most tol_infeas (ECOS's and Clarabel's tests).

#include <algorithm>
#include <limits>
#include <optional>
#include <string>

#include "rbla/conic/info.hpp"
#include "scaled_problem.hpp"
#include "variables.hpp"

namespace rbla::conic::detail {

/// Quality of an iterate, measured on the original (unscaled) problem.
struct Metrics {
  Vec x, y, z;  // iterate / τ, original units
  double primal_objective = 0, dual_objective = 0;
  double gap_abs = 0, gap_rel = 0, res_primal = 0, res_dual = 0;
  double primal_cert = std::numeric_limits<double>::infinity();  // ‖Aᵀȳ + z̄‖∞ (bᵀȳ = 1)
  double dual_cert = std::numeric_limits<double>::infinity();    // ‖A x̄‖∞ (cᵀx̄ = −1)
  Vec y_cert, z_cert, x_cert;

  /// ≤ 1 exactly when meets(tol_feas, tol_gap_abs, tol_gap_rel): how far from converged.
  double merit(double tol_feas, double tol_gap_abs, double tol_gap_rel) const {
    return std::max({res_primal / tol_feas, res_dual / tol_feas,
                     std::min(gap_abs / tol_gap_abs, gap_rel / tol_gap_rel)});
  }
  bool meets(double tol_feas, double tol_gap_abs, double tol_gap_rel) const {
    return res_primal <= tol_feas && res_dual <= tol_feas &&
           (gap_abs <= tol_gap_abs || gap_rel <= tol_gap_rel);
  }
};

/// Metrics of (x, y, z, τ) of `scaled`. scaled_Ax, scaled_Aty: Ã x and Ãᵀ y when the caller has
/// them (used with two threads).
Metrics evaluate_metrics(const ConicProblem& original, const ScaledProblem& scaled, const Vec& x,
                         const Vec& y, const Vec& z, double tau, const Vec* scaled_Ax = nullptr,
                         const Vec* scaled_Aty = nullptr);

/// Why a solve stops: its status, and a reason for a failure or a reduced-accuracy verdict.
struct Termination {
  SolveStatus status = SolveStatus::NumericalFailure;
  std::string reason;
};

class Residuals {
 public:
  Vec rp, rd;
  double rg = 0;
  double mu = 0;
  Vec scaled_Ax, scaled_Aty;  // Ã x and Ãᵀ y of the current iterate
  Metrics metrics;            // of the current iterate; the returned point at the end

  /// Residuals, μ and metrics of v, and the best iterate and certificates so far.
  void update(const ConicProblem& original, const ScaledProblem& scaled, const Variables& v,
              double degree, const Settings& settings);
  /// Records metrics as the best point so far where it is (what update() does after measuring).
  void track_best(const Settings& settings);

  /// The outcome if the solve stops at iteration `iter` (after update()), else nothing:
  /// converged, infeasible (also a certificate that stagnated at the reduced tolerance),
  /// non-finite iterate, iteration or time limit. May replace metrics by a stored certificate.
  std::optional<Termination> check_termination(const Settings& settings, int iter,
                                               double elapsed_seconds, const Variables& v);

  /// For a run that stopped without meeting the tolerances (iteration or time limit, numerical
  /// failure): the best iterate if it meets the reduced tolerances (SolvedInaccurate), or a
  /// certificate at reduced_tol_infeas while τ < κ; else `t` unchanged.
  Termination reduced_accuracy_fallback(const Settings& settings, Termination t,
                                        const Variables& v);

 private:
  // Late iterations of degenerate problems can lose accuracy; the best iterate is kept for the
  // reduced-accuracy fallback.
  Metrics best_metrics_;
  double best_merit_ = std::numeric_limits<double>::infinity();
  // Infeasibility certificates whose residual stagnates: on some nearly infeasible problems the
  // embedding's iterates shrink towards zero together (τ and κ alike), and the normalised
  // certificate stops improving above tol_infeas.
  Metrics best_primal_cert_, best_dual_cert_;
  int primal_cert_improved_at_ = 0, dual_cert_improved_at_ = 0;
};

}  // namespace rbla::conic::detail
