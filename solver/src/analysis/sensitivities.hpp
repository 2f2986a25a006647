// Derivatives of the load multiplier from the collapse state itself, without another solve
// (docs/sensitivities.md).
//
// Envelope theorem: at the optimum of  max alpha  s.t. equilibrium and the friction cones, the
// derivative of alpha with respect to a parameter is the derivative of the Lagrangian with the
// optimal forces and multipliers (the mechanism's velocities) held fixed.
// - Friction at a contact point p, cone |t| <= mu N: the multiplier of the cone is the slip rate,
//   and with associative flow the normal opening rate is v_n = mu |v_t|, so
//   d alpha / d mu_p = N_p v_n,p / (mu_p P), P the live load's work rate. Summed over an
//   interface's points: d alpha / d mu_k. The same holds for the pyramids (v_n = mu times the sum
//   of the facet multipliers).
// - Unit weight of block b, W_b = gamma_b V_b: with the mechanism fixed, alpha P + D = 0 (no
//   dissipation under associative friction), D = sum W_b g.v_b + ..., P = sum W_b d.v_b + ...
//   (seismic), so d alpha / d W_b = -(g.v_b + alpha d.v_b) / P.
// Where alpha has a kink (the mechanism changes with the parameter), this is the derivative
// along the mechanism found, one of the one-sided derivatives.
#pragma once

#include "analysis/analysis_result.hpp"
#include "model/model.hpp"

#include <optional>

namespace rbla::analysis {

/// Empty unless the result is a collapse of an associative load-multiplier analysis with a
/// positive live-load work rate.
std::optional<Sensitivities> load_multiplier_sensitivities(const model::Model& model, const AnalysisResult& result);

}  // namespace rbla::analysis
