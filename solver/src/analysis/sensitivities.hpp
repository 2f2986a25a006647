// Derivatives of the load multiplier (or, under settlement, of the base reaction R) from the
// collapse state itself, without another solve (docs/sensitivities.md).
//
// Envelope theorem: at the optimum of  max alpha (min R)  s.t. equilibrium and the friction
// cones, the derivative of the optimum with respect to a parameter is the derivative of the
// Lagrangian with the optimal forces and multipliers (the mechanism's velocities) held fixed.
// Both read  d value = (d of the contact and dead power) / (-P), P the work rate of the value's
// own load column per unit value: the live load for alpha, -d on the settling supports for R
// (P = -v_s, v_s the supports' settlement rate along d).
// - Friction at a contact point p, cone |t| <= mu N: the multiplier of the cone is the slip rate,
//   and with associative flow the normal opening rate is v_n = mu |v_t|, so
//   d alpha / d mu_p = N_p v_n,p / (mu_p P), P the live load's work rate. Summed over an
//   interface's points: d alpha / d mu_k. The same holds for the pyramids (v_n = mu times the sum
//   of the facet multipliers).
// - Unit weight of block b, W_b = gamma_b V_b: with the mechanism fixed, alpha P + D = 0 (no
//   dissipation under associative friction), D = sum W_b g.v_b + ..., P = sum W_b d.v_b + ...
//   (seismic), so d alpha / d W_b = -(g.v_b + alpha d.v_b) / P. Under settlement
//   -R v_s + D = 0, so d R / d W_b = g.v_b / v_s, and d R / d mu_p = -N_p v_n,p / (mu_p v_s).
// Where alpha has a kink (the mechanism changes with the parameter), this is the derivative
// along the mechanism found, one of the one-sided derivatives.
#pragma once

#include "analysis/analysis_result.hpp"
#include "model/model.hpp"

#include <optional>

namespace rbla::analysis {

/// Empty unless the result is a collapse of an associative analysis: a load multiplier with a
/// positive live-load work rate, or a settlement with the supports settling.
std::optional<Sensitivities> collapse_sensitivities(const model::Model& model, const AnalysisResult& result);

}  // namespace rbla::analysis
