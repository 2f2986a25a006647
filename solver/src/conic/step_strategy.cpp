#include "step_strategy.hpp"

#include <algorithm>
#include <cmath>

namespace rbla::conic::detail {

void StepStrategy::begin_iteration(const Variables& v, double mu) {
  tau_ = v.tau;
  kappa_ = v.kappa;
  mu_ = mu;
  if (e_.size() != v.x.size()) {
    e_.resize(v.x.size());
    cones_.set_identity(e_);
  }
  cones_.lambda(lambda_);
}

double StepStrategy::max_step(const Direction& d) {
  cones_.mul_Winv(d.x, scaled_dx_);
  cones_.mul_W(d.z, scaled_dz_);
  double alpha =
      std::min(cones_.max_step_from_lambda(scaled_dx_), cones_.max_step_from_lambda(scaled_dz_));
  if (d.tau < 0) alpha = std::min(alpha, -tau_ / d.tau);
  if (d.kappa < 0) alpha = std::min(alpha, -kappa_ / d.kappa);
  return alpha;
}

void StepStrategy::compute(KktSystem& kkt, Step& step, Info& info) {
  // The predictor only sets σ and the second-order term, heuristics that do not need the
  // refined accuracy; the direction taken is solved from its full right-hand side and refined.
  // It is refined while τ < κ, where the embedding heads for an infeasibility certificate:
  // there a plain solve can miss much of the step (KktSystem::refine), and an unrefined
  // predictor can leave the certificate of a nearly infeasible problem stalled just above
  // tol_infeas.
  cones_.jordan_product(lambda_, lambda_, lambda_sq_);
  ds_ = -lambda_sq_;
  kkt.solve_affine(ds_, -tau_ * kappa_, tau_ < kappa_, affine_);
  const double alpha_aff = affine_step();
  step.sigma = std::clamp(std::pow(1.0 - sigma_step(alpha_aff), 3), 0.0, 1.0);
  corrector(kkt, affine_, step);
  centrality_correctors(kkt, step, info);
  // Only the direction that is taken is refined. The corrector and the centrality correctors
  // are judged by their unrefined steps: refinement moves step lengths by less than 0.01, and
  // refining each kept corrector would waste that work whenever a later one replaced it.
  if (kkt.refine(1.0 - step.sigma, kappa_rhs_, true, step.direction))
    step.alpha = settings_.step_fraction * std::min(1.0, max_step(step.direction));
}

int StepStrategy::skipped_blockers() const {
  return static_cast<int>(std::ceil(settings_.sigma_skip_fraction * static_cast<double>(cones_.degree())));
}

// The predictor's step length, min(1, max_step(affine_)). When σ skips blockers it is taken from
// the list of every factor's step below 1 (blocking_), which sigma_step needs too: one pass over
// the cones instead of two. Leaves W⁻¹dx_a, W dz_a in scaled_dx_, scaled_dz_ either way.
double StepStrategy::affine_step() {
  if (skipped_blockers() == 0) return std::min(1.0, max_step(affine_));
  cones_.mul_Winv(affine_.x, scaled_dx_);
  cones_.mul_W(affine_.z, scaled_dz_);
  blocking_.clear();
  cones_.append_steps_from_lambda(scaled_dx_, 1.0, blocking_);
  cones_.append_steps_from_lambda(scaled_dz_, 1.0, blocking_);
  if (affine_.tau < 0 && -tau_ / affine_.tau < 1.0) blocking_.push_back(-tau_ / affine_.tau);
  if (affine_.kappa < 0 && -kappa_ / affine_.kappa < 1.0) blocking_.push_back(-kappa_ / affine_.kappa);
  return blocking_.empty() ? 1.0 : *std::min_element(blocking_.begin(), blocking_.end());
}

// The affine step that sets σ: past the first ⌈sigma_skip_fraction ν⌉ factors that block it. In
// degenerate problems one to ten pairs out of 10⁴–10⁵ stop the predictor at α 0.01–0.3 (a pair
// changing sides: its direction moves it by many times its size), and σ = (1 − α)³ then asks
// for almost pure centring while the rest of the iterate could go most of the way; the
// centrality correctors bring those few pairs back. Needs blocking_ from affine_step().
double StepStrategy::sigma_step(double alpha_aff) {
  const int skip = skipped_blockers();
  if (skip == 0 || alpha_aff >= 1.0) return alpha_aff;
  if (static_cast<int>(blocking_.size()) <= skip) return 1.0;
  std::nth_element(blocking_.begin(), blocking_.begin() + skip, blocking_.end());
  return blocking_[static_cast<std::size_t>(skip)];
}

// Mehrotra's second-order term (W⁻¹dx_a)∘(W dz_a) and the centring σμe. W⁻¹dx_a and W dz_a are
// in scaled_dx_, scaled_dz_ from affine_step().
void StepStrategy::corrector(KktSystem& kkt, const Direction& affine, Step& step) {
  const double sigma = step.sigma;
  cones_.jordan_product(scaled_dx_, scaled_dz_, corr_);
  ds_ = -lambda_sq_ - corr_ + (sigma * mu_) * e_;
  kkt.solve(1.0 - sigma, ds_, -tau_ * kappa_ - affine.tau * affine.kappa + sigma * mu_,
            step.direction);
  step.alpha = settings_.step_fraction * std::min(1.0, max_step(step.direction));
  kappa_rhs_ = -tau_ * kappa_ - affine.tau * affine.kappa + sigma * mu_;
}

// Degenerate problems (most contact points end at the cone apex with a zero dual too) have a
// few pairs that block every step: well centred, but turned by the direction by more than their
// size. Each corrector asks for a longer step α̃ = α + 0.3, looks at the complementarity
// products the current direction would give there, moves the outliers back into
// [β_min σμ, β_max σμ] = [0.1 σμ, 10 σμ] (Colombo & Gondzio 2008, §3) and re-solves with the same
// factor (one triangular solve). It is kept only if the step grows by 1 %.
void StepStrategy::centrality_correctors(KktSystem& kkt, Step& step, Info& info) {
  const double sigma = step.sigma;
  Direction& dir = step.direction;
  for (int k = 0; k < settings_.max_centrality_correctors && step.alpha < settings_.step_fraction;
       ++k) {
    const double alpha_trial = std::min(1.0, step.alpha + 0.3);
    // scaled_dx_ = W⁻¹dx and scaled_dz_ = W dz are already there: the last max_step call was
    // for the current direction (the corrector's, when one was just accepted).
    trial_s_ = lambda_ + alpha_trial * scaled_dx_;
    trial_z_ = lambda_ + alpha_trial * scaled_dz_;
    cones_.jordan_product(trial_s_, trial_z_, trial_v_);
    const double lo = 0.1 * sigma * mu_, hi = 10.0 * sigma * mu_;
    cones_.centrality_correction(trial_v_, lo, hi, corr_);
    const double kappa_change = centrality_change(
        (tau_ + alpha_trial * dir.tau) * (kappa_ + alpha_trial * dir.kappa), lo, hi);
    ds_c_ = ds_ + corr_;
    trial_.tau = trial_.kappa = 0;
    kkt.solve(1.0 - sigma, ds_c_, kappa_rhs_ + kappa_change, trial_);
    ++info.num_centrality_correctors;
    const double alpha_c = settings_.step_fraction * std::min(1.0, max_step(trial_));
    if (!(alpha_c >= 1.01 * step.alpha)) break;
    ds_.swap(ds_c_);
    kappa_rhs_ += kappa_change;
    dir.swap(trial_);
    step.alpha = alpha_c;
    ++info.num_centrality_correctors_accepted;
  }
}

}  // namespace rbla::conic::detail
