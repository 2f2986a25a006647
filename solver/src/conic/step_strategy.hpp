#pragma once
// Step length and centring: Mehrotra's predictor–corrector (Mehrotra 1992; for symmetric cones
// as in CVXOPT's conelp, Vandenberghe 2010, §5) with Gondzio's multiple centrality correctors
// (Gondzio 1996; Colombo & Gondzio 2008).
//
//   predictor: η = 1, d = −λ∘λ, d_κ = −τκ; α_aff its longest step past the few factors that
//              block it first (sigma_step), σ = (1 − α_aff)³;
//   corrector: η = 1 − σ, d = −λ∘λ − (W⁻¹dx_a)∘(W dz_a) + σμe, d_κ = −τκ − dτ_a dκ_a + σμ.

#include "kkt_system.hpp"

namespace rbla::conic::detail {

/// The direction an iteration takes and its step length.
struct Step {
  Direction direction;
  double alpha = 0;  ///< step length, step_fraction times the longest
  double sigma = 0;  ///< centring parameter
};

class StepStrategy {
 public:
  StepStrategy(const ConeSet& cones, const Settings& settings) : cones_(cones), settings_(settings) {}

  /// Needs update_scaling() done for v: reads λ from the cones.
  void begin_iteration(const Variables& v, double mu);

  /// Predictor, corrector, centrality correctors and the refinement of the direction taken,
  /// all with KKT's current factor. Correctors tried and kept are counted in info.
  void compute(KktSystem& kkt, Step& step, Info& info);

  /// Largest step keeping x, z in K and τ, κ ≥ 0, measured in the scaled space around λ
  /// (leaves W⁻¹dx, W dz in scaled_dx_, scaled_dz_).
  double max_step(const Direction& d);

 private:
  int skipped_blockers() const;
  double affine_step();
  double sigma_step(double alpha_aff);
  void corrector(KktSystem& kkt, const Direction& affine, Step& step);
  void centrality_correctors(KktSystem& kkt, Step& step, Info& info);

  const ConeSet& cones_;
  const Settings& settings_;
  double tau_ = 1, kappa_ = 1, mu_ = 0;
  Vec e_, lambda_, lambda_sq_;
  Vec scaled_dx_, scaled_dz_, corr_;
  Vec ds_, ds_c_;            // the complementarity right-hand side d of the direction kept
  double kappa_rhs_ = 0;     // and its d_κ
  Direction affine_, trial_;
  Vec trial_s_, trial_z_, trial_v_;
  std::vector<double> blocking_;  // steps of the factors that block the affine step
};

}  // namespace rbla::conic::detail
