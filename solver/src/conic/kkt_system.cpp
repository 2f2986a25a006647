#include "kkt_system.hpp"

#include <chrono>
#include <cmath>
#include <limits>

namespace rbla::conic::detail {

bool DirectionAccuracy::accepts(const Vec& ep, double eg, double eta, const Vec& abs_y,
                                const Vec& row_scale) const {
  const double error = std::max(inf_norm(ep), std::abs(eg));
  if (error <= exact) return true;
  if (!(std::abs(eg) <= eta * gap)) return false;
  const double limit = eta * feasibility;
  double weighted = 0;
  for (Eigen::Index i = 0; i < ep.size(); ++i) {
    const double e = std::abs(ep[i]);
    if (!(e <= limit * row_scale[i])) return false;
    weighted += abs_y[i] * e;
  }
  return weighted <= eta * objective;
}

DirectionAccuracy direction_accuracy(const ConicProblem& original, const ScaledProblem& scaled,
                                     const Settings& settings, const Residuals& residuals,
                                     const Variables& v) {
  const auto& eq = scaled.equilibration();
  const double tau = v.tau;
  DirectionAccuracy a;
  a.exact = std::max(settings.refine_tol_rel * (1.0 + inf_norm(scaled.b()) * tau),
                     1e-3 * inf_norm(residuals.rp));
  const double gap_scale = eq.c_scale * eq.b_scale * tau;
  a.gap = 0.1 * settings.tol_gap_rel *
          std::max(1.0, std::abs(residuals.metrics.primal_objective)) * gap_scale;
  a.objective = a.gap * tau;
  a.feasibility = 0.1 * settings.tol_feas *
                  std::max(1.0, inf_norm(original.b) + inf_norm(residuals.metrics.x)) *
                  eq.b_scale * tau;
  const double y_norm = v.y.lpNorm<1>();
  const double min_row_scale = eq.row_scale.size() > 0 ? eq.row_scale.minCoeff() : 1.0;
  double uniform = std::min(a.feasibility * min_row_scale, a.gap);
  if (y_norm > 0) uniform = std::min(uniform, a.objective / y_norm);
  a.uniform = std::max(a.exact, uniform);
  return a;
}

KktSystem::KktSystem(std::unique_ptr<NormalEquations> normal, const ScaledProblem& scaled,
                     const ConeSet& cones, const Settings& settings)
    : normal_(std::move(normal)), ne_(normal_.get()), scaled_(scaled), cones_(cones),
      settings_(settings) {}

void KktSystem::set_A_values(const Eigen::SparseMatrix<double>& A) {
  normal_->set_A_values(A);
  if (without_dense_) without_dense_->set_A_values(A);
}

bool KktSystem::factor(const std::vector<double>& packed_W2, int factor_threads, Info& info) {
  const Settings& s = settings_;
  refinement_failed_ = false;
  const FactorReport report =
      ne_->factor(packed_W2, s.reg_static, s.reg_retry_factor, s.reg_max_retries, factor_threads);
  info.assembly_seconds += report.assembly_seconds;
  info.factor_seconds += report.factor_seconds;
  info.num_refactor_retries += report.retries;
  return report.ok;
}

void KktSystem::begin_iteration(const Residuals& residuals, const Variables& v,
                                const DirectionAccuracy& accuracy) {
  residuals_ = &residuals;
  tau_ = v.tau;
  kappa_ = v.kappa;
  accuracy_ = accuracy;
  abs_y_ = v.y.cwiseAbs();
}

int KktSystem::take_refine_steps() {
  const int steps = refine_steps_;
  refine_steps_ = 0;
  return steps;
}

// The right-hand side of M p = −η r_p − A W² r₁ (in rhs_; r₁ in r1_).
void KktSystem::prepare_rhs(double eta, const Vec& d) {
  cones_.lambda_divide(d, ds_tilde_);
  cones_.mul_Winv(ds_tilde_, r1_);
  r1_ -= eta * residuals_->rd;
  cones_.mul_W2(r1_, tmp_);
  scaled_.multiply_A(tmp_, rhs_);
  rhs_ = -eta * residuals_->rp - rhs_;
}

// W²(Aᵀq − c) and the dτ denominator bᵀq − cᵀW²(Aᵀq − c) + κ/τ.
void KktSystem::finish_tau_column() {
  scaled_.multiply_At(q_, Atq_c_);
  Atq_c_ -= scaled_.c();
  cones_.mul_W2(Atq_c_, dxq_);
  denominator_ = scaled_.b().dot(q_) - scaled_.c().dot(dxq_) + kappa_ / tau_;
}

void KktSystem::dz_from_dual_equation(double eta, Direction& dir) {
  scaled_.multiply_At(dir.y, dir.z);
  dir.z = -dir.z + scaled_.c() * dir.tau + eta * residuals_->rd;
}

// The direction from p (and r₁) of prepare_rhs.
void KktSystem::direction_from_p(double eta, double d_kappa, bool refine_it, Direction& out) {
  const Vec& b = scaled_.b();
  const Vec& c = scaled_.c();
  scaled_.multiply_At(p_, tmp_);
  tmp_ += r1_;
  cones_.mul_W2(tmp_, out.x);
  out.tau = (-eta * residuals_->rg - b.dot(p_) + c.dot(out.x) + d_kappa / tau_) / denominator_;
  out.y = p_ + q_ * out.tau;
  out.x += dxq_ * out.tau;
  out.kappa = (d_kappa - kappa_ * out.tau) / tau_;
  if (refine_it)
    refine(eta, d_kappa, false, out);
  else
    dz_from_dual_equation(eta, out);
}

// q is solved plainly. Its error reaches a direction only through q, W²(Aᵀq − c) and the
// denominator, which every direction and correction uses consistently (the gap equation holds
// for whatever q was computed), so what it leaves in the primal equation is part of the e_p each
// refinement measures and removes; refining q by CG costs a solve and a product with M per
// iteration for no fewer iterations. Only a denominator that rounding made non-positive (it is
// ‖W(Aᵀq − c)‖² + κ/τ for the exact q) sends q back to CG. q and the predictor's p share one
// pass over the factor: the triangular solves are memory bound, so the second right-hand side
// costs a fraction of the first.
void KktSystem::solve_affine(const Vec& d, double d_kappa, bool refine_it, Direction& out) {
  const Settings& s = settings_;
  cones_.mul_W2(scaled_.c(), W2c_);
  scaled_.multiply_A(W2c_, q_rhs_);
  q_rhs_ += scaled_.b();
  prepare_rhs(1.0, d);
  ne_->solve_pair(q_rhs_, rhs_, q_, p_);
  finish_tau_column();
  if (!(denominator_ > 0)) {
    const double q_target = s.refine_tol_rel * (1.0 + inf_norm(q_rhs_));
    refine_steps_ += ne_->solve(q_rhs_, q_, s.refine_max_iter, q_target);
    finish_tau_column();
  }
  direction_from_p(1.0, d_kappa, refine_it, out);
}

void KktSystem::solve(double eta, const Vec& d, double d_kappa, Direction& out) {
  prepare_rhs(eta, d);
  refine_steps_ += ne_->solve(rhs_, p_, 0, accuracy_.uniform);
  direction_from_p(eta, d_kappa, false, out);
}

// Refinement of a direction on the unreduced residuals: the normal equations lose accuracy
// through the cancellation in A W² (Aᵀp + r₁) when W² is ill-conditioned (late iterations), so
// the error of the primal equation  e_p = A dx − b dτ + η r_p  is measured directly (A dx is
// accurate) and corrected by the same elimination with right-hand side (−e_p, 0, −e_g, 0). dx is
// updated incrementally and dz is formed once at the end from the dual equation, which keeps
// W dz + W⁻¹dx unchanged (the refinement never reads dz).
bool KktSystem::refine(double eta, double d_kappa, bool dz_current, Direction& dir) {
  const Settings& s = settings_;
  const Vec& b = scaled_.b();
  const Vec& c = scaled_.c();
  const double refine_target = accuracy_.uniform;
  bool corrected = false;
  double previous = std::numeric_limits<double>::infinity();
  double ddtau = 0;  // the last correction's, with dp_ and ddx_ (to take it back)
  for (int pass = 0; pass < s.refine_max_iter; ++pass) {
    scaled_.multiply_A(dir.x, ep_);
    ep_ += eta * residuals_->rp - b * dir.tau;
    const double eg = b.dot(dir.y) - c.dot(dir.x) - dir.kappa + eta * residuals_->rg;
    double error = std::max(inf_norm(ep_), std::abs(eg));
    const bool accepted =
        accuracy_.accepts(ep_, eg, eta, abs_y_, scaled_.equilibration().row_scale);
    // A correction that made the error larger is taken back: the factor is then too far from
    // the operator the error is measured with for refinement to converge (rounding in the
    // assembled M, whose NT blocks late in a solve have condition numbers past 1/ε); each further
    // correction would multiply the error, and such directions block the step.
    const bool worse = pass >= 1 && !accepted && !(error <= previous);
    if (worse) {
      dir.y -= dp_ + q_ * ddtau;
      dir.x -= ddx_ + dxq_ * ddtau;
      dir.tau -= ddtau;
      dir.kappa = (d_kappa - kappa_ * dir.tau) / tau_;
      error = previous;
    }
    // The plain first correction is not judged by the halving test: when the smallest
    // eigenvalue of M falls below the static regularisation δ (nearly infeasible problems, where
    // W² → 0 on most variables), one regularised solve removes only a fraction λ/(λ + δ) of the
    // error along that eigenvector; the embedding then shrinks all iterates together and the
    // infeasibility certificate stalls. CG on the exact M does remove it.
    if (accepted || worse || (pass >= 2 && !(error < 0.5 * previous))) {
      // An error above the residual being removed means the solves are not usable.
      if (!accepted && error > std::max(1e3 * refine_target, inf_norm(residuals_->rp)))
        refinement_failed_ = true;
      break;
    }
    previous = error;
    ep_ = -ep_;
    // First a plain correction (one triangular solve); if that was not enough, CG on M.
    refine_steps_ += 1 + ne_->solve(ep_, dp_, pass == 0 ? 0 : s.refine_max_iter, refine_target);
    scaled_.multiply_At(dp_, tmp_);
    cones_.mul_W2(tmp_, ddx_);
    ddtau = (-eg - b.dot(dp_) + c.dot(ddx_)) / denominator_;
    dir.y += dp_ + q_ * ddtau;
    dir.x += ddx_ + dxq_ * ddtau;
    dir.tau += ddtau;
    dir.kappa = (d_kappa - kappa_ * dir.tau) / tau_;
    corrected = true;
  }
  if (corrected || !dz_current) dz_from_dual_equation(eta, dir);
  return corrected;
}

bool KktSystem::drop_dense_columns(const std::vector<bool>& is_dense, Ordering ordering,
                                   ForkJoin* fork_join, Info& info) {
  if (ne_->num_dense_columns() == 0) return false;
  if (!without_dense_) {
    const auto start = std::chrono::steady_clock::now();
    // The blocks are those of the first normal equations; only the dense flags change.
    without_dense_ = std::make_unique<NormalEquations>(
        scaled_.A(), cones_.scaling_blocks(), std::vector<bool>(is_dense.size(), false),
        ordering, fork_join);
    info.symbolic_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  ne_ = without_dense_.get();
  info.dense_column_fallback = true;
  return true;
}

}  // namespace rbla::conic::detail
