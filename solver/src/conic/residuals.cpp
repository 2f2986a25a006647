#include "residuals.hpp"

#include <cmath>

namespace rbla::conic::detail {

Metrics evaluate_metrics(const ConicProblem& P, const ScaledProblem& scaled, const Vec& x,
                         const Vec& y, const Vec& z, double tau, const Vec* scaled_Ax,
                         const Vec* scaled_Aty) {
  const auto& eq = scaled.equilibration();
  Metrics r;
  const Vec x_hat = eq.col_scale.cwiseProduct(x);  // ∝ x, original units up to 1/(s_b τ)
  const Vec y_hat = eq.row_scale.cwiseProduct(y);
  const Vec z_hat = z.cwiseQuotient(eq.col_scale);
  r.x = x_hat / (eq.b_scale * tau);
  r.y = y_hat / (eq.c_scale * tau);
  r.z = z_hat / (eq.c_scale * tau);
  r.primal_objective = P.c.dot(r.x);
  r.dual_objective = P.b.dot(r.y);
  // Both gaps: |cᵀx − bᵀy| alone can be small while the complementarity xᵀz is not, when the
  // dual residual's contribution r_dᵀx cancels it (many variables, large x); ECOS uses xᵀz.
  r.gap_abs = std::max(std::abs(r.primal_objective - r.dual_objective), std::abs(r.x.dot(r.z)));
  r.gap_rel = r.gap_abs /
              std::max(1.0, std::min(std::abs(r.primal_objective), std::abs(r.dual_objective)));
  const bool two_threads = scaled.two_threads();
  Vec Ax, Aty;
  if (two_threads) {
    // Through the scaled matrix on both threads: A = D⁻¹ Ã E⁻¹ (equilibration.hpp), so
    // A x_orig = D⁻¹ Ã x / (s_b τ) and Aᵀ y_orig = E⁻¹ Ãᵀ y / (s_c τ); the certificates'
    // products are these rescaled.
    if (scaled_Ax)
      Ax = *scaled_Ax;
    else
      scaled.multiply_A(x, Ax);
    Ax = Ax.cwiseQuotient(eq.row_scale) / (eq.b_scale * tau);
    if (scaled_Aty)
      Aty = *scaled_Aty;
    else
      scaled.multiply_At(y, Aty);
    Aty = Aty.cwiseQuotient(eq.col_scale) / (eq.c_scale * tau);
  } else {
    Ax = P.A * r.x;
    Aty = P.A.transpose() * r.y;
  }
  r.res_primal = inf_norm(Ax - P.b) / std::max(1.0, inf_norm(P.b) + inf_norm(r.x));
  r.res_dual =
      inf_norm(Aty + r.z - P.c) / std::max(1.0, inf_norm(P.c) + inf_norm(r.y) + inf_norm(r.z));
  const double bty = P.b.dot(y_hat);
  if (bty > 0) {
    r.y_cert = y_hat / bty;
    r.z_cert = z_hat / bty;
    r.primal_cert = two_threads ? inf_norm(Aty * (eq.c_scale * tau / bty) + r.z_cert)
                                : inf_norm(P.A.transpose() * r.y_cert + r.z_cert);
  }
  const double ctx = P.c.dot(x_hat);
  if (ctx < 0) {
    r.x_cert = x_hat / (-ctx);
    r.dual_cert = two_threads ? inf_norm(Ax * (eq.b_scale * tau / -ctx))
                              : inf_norm(P.A * r.x_cert);
  }
  return r;
}

void Residuals::update(const ConicProblem& original, const ScaledProblem& scaled,
                       const Variables& v, double degree, const Settings& settings) {
  scaled.multiply_A(v.x, scaled_Ax);
  rp = scaled_Ax - scaled.b() * v.tau;
  scaled.multiply_At(v.y, scaled_Aty);
  rd = -scaled_Aty + scaled.c() * v.tau - v.z;
  rg = scaled.b().dot(v.y) - scaled.c().dot(v.x) - v.kappa;
  mu = v.mu(degree);
  metrics = evaluate_metrics(original, scaled, v.x, v.y, v.z, v.tau, &scaled_Ax, &scaled_Aty);
  track_best(settings);
}

void Residuals::track_best(const Settings& s) {
  const double merit = metrics.merit(s.tol_feas, s.tol_gap_abs, s.tol_gap_rel);
  if (!(merit >= best_merit_)) {
    best_merit_ = merit;
    best_metrics_ = metrics;
  }
}

std::optional<Termination> Residuals::check_termination(const Settings& s, int iter,
                                                         double elapsed_seconds,
                                                         const Variables& v) {
  if (metrics.meets(s.tol_feas, s.tol_gap_abs, s.tol_gap_rel))
    return Termination{SolveStatus::Solved, {}};
  if (metrics.primal_cert <= s.tol_infeas) return Termination{SolveStatus::PrimalInfeasible, {}};
  if (metrics.dual_cert <= s.tol_infeas) return Termination{SolveStatus::DualInfeasible, {}};
  if (metrics.primal_cert < 0.5 * best_primal_cert_.primal_cert) {
    best_primal_cert_ = metrics;
    primal_cert_improved_at_ = iter;
  }
  if (metrics.dual_cert < 0.5 * best_dual_cert_.dual_cert) {
    best_dual_cert_ = metrics;
    dual_cert_improved_at_ = iter;
  }
  const char* stagnated = "certificate stagnated above tol_infeas (reduced accuracy)";
  if (v.tau < v.kappa && best_primal_cert_.primal_cert <= s.reduced_tol_infeas &&
      iter - primal_cert_improved_at_ > s.stall_max_iter) {
    metrics = best_primal_cert_;
    return Termination{SolveStatus::PrimalInfeasible, stagnated};
  }
  if (v.tau < v.kappa && best_dual_cert_.dual_cert <= s.reduced_tol_infeas &&
      iter - dual_cert_improved_at_ > s.stall_max_iter) {
    metrics = best_dual_cert_;
    return Termination{SolveStatus::DualInfeasible, stagnated};
  }
  if (!std::isfinite(mu) || !std::isfinite(v.tau) || !std::isfinite(v.kappa))
    return Termination{SolveStatus::NumericalFailure, "non-finite iterate"};
  if (iter >= s.max_iter) return Termination{SolveStatus::IterationLimit, {}};
  if (elapsed_seconds >= s.time_limit_seconds) return Termination{SolveStatus::TimeLimit, {}};
  return std::nullopt;
}

Termination Residuals::reduced_accuracy_fallback(const Settings& s, Termination t,
                                                 const Variables& v) {
  if (t.status != SolveStatus::IterationLimit && t.status != SolveStatus::TimeLimit &&
      t.status != SolveStatus::NumericalFailure)
    return t;
  const char* reduced = "certificate above tol_infeas (reduced accuracy)";
  if (best_metrics_.meets(s.reduced_tol_feas, s.reduced_tol_gap_abs, s.reduced_tol_gap_rel)) {
    metrics = best_metrics_;
    t.status = SolveStatus::SolvedInaccurate;  // the failure's reason, if any, is kept
  } else if (v.tau < v.kappa && best_primal_cert_.primal_cert <= s.reduced_tol_infeas) {
    metrics = best_primal_cert_;
    t = Termination{SolveStatus::PrimalInfeasible, reduced};
  } else if (v.tau < v.kappa && best_dual_cert_.dual_cert <= s.reduced_tol_infeas) {
    metrics = best_dual_cert_;
    t = Termination{SolveStatus::DualInfeasible, reduced};
  }
  return t;
}

}  // namespace rbla::conic::detail
