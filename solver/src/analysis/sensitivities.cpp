#include "analysis/sensitivities.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace rbla::analysis {
namespace {

/// Openings and normal forces below this fraction of the largest are the solver's round-off
/// (complementarity holds to its tolerance: a closed point opens by ~1e-9, an open one keeps
/// ~1e-9 of force).
constexpr double kRoundOff = 1e-6;

struct Floors {
  double opening = 0.0, force = 0.0;
};

Floors round_off_floors(const Mechanism& mechanism) {
  Floors largest;
  for (const InterfaceResult& r : mechanism.interfaces) {
    for (const PointResult& point : r.points) {
      largest.opening = std::max(largest.opening, point.relative_velocity.x());
      largest.force = std::max(largest.force, point.normal_force);
    }
  }
  return {kRoundOff * largest.opening, kRoundOff * largest.force};
}

/// d value / d mu_k of one interface: sum over its points of N v_n / mu, over P.
double interface_friction_derivative(const model::ContactInterface& contact, const InterfaceResult& r, double power,
                                     const Floors& floors) {
  if (!(contact.friction > 0.0)) return 0.0;
  double sum = 0.0;
  for (const PointResult& point : r.points) {
    const double opening = point.relative_velocity.x();  // normal component of v_b - v_a
    if (point.normal_force > floors.force && opening > floors.opening) sum += point.normal_force * opening;
  }
  return sum / (contact.friction * power);
}

/// Work rate of the value's own load per unit value, P: the live load's for alpha; under
/// settlement the ground's reaction -d on the settling supports, P = -v_s. NaN when there is none.
double value_power(const model::Model& m, const AnalysisResult& r) {
  if (r.type == model::AnalysisType::LoadMultiplier) return r.work.live_work;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    if (m.blocks[b].role == model::BlockRole::MovingSupport) {
      return -r.mechanism.blocks[b].translation.dot(r.settlement_direction);
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

bool has_sensitivities(const AnalysisResult& r) {
  const bool value = r.type == model::AnalysisType::LoadMultiplier ? r.load_multiplier.has_value()
                                                                    : r.base_reaction.has_value();
  return r.verdict == Verdict::Collapse && r.friction_model == model::FrictionModel::Associative && value;
}

}  // namespace

std::optional<Sensitivities> collapse_sensitivities(const model::Model& m, const AnalysisResult& r) {
  if (!has_sensitivities(r) || r.mechanism.interfaces.size() != m.interfaces.size() ||
      r.mechanism.blocks.size() != m.blocks.size()) {
    return std::nullopt;
  }
  const bool settlement = r.type == model::AnalysisType::Settlement;
  const double power = value_power(m, r);
  // A load multiplier needs the live load to work on the mechanism; a settlement, the supports
  // to settle (P = -v_s < 0).
  if (!(settlement ? power < 0.0 : power > 0.0)) return std::nullopt;
  Sensitivities s;
  s.quantity = settlement ? SensitivityOf::BaseReaction : SensitivityOf::LoadMultiplier;
  const Floors floors = round_off_floors(r.mechanism);
  for (std::size_t k = 0; k < m.interfaces.size(); ++k) {
    const double d = interface_friction_derivative(m.interfaces[k], r.mechanism.interfaces[k], power, floors);
    if (d == 0.0) continue;
    s.interface_friction.emplace_back(static_cast<int>(k), d);
    s.friction_factor += m.interfaces[k].friction * d;
  }
  // d value / d W_b = -(g.v_b + alpha d.v_b) / P; no live load turns with the weights under settlement.
  const double alpha = settlement ? 0.0 : *r.load_multiplier;
  const Vec3 d = settlement ? Vec3::Zero() : m.analysis.seismic_direction.value_or(Vec3::Zero());
  // Every block with a velocity counts, not only those the picture calls moving: a part
  // drifting at 2 % of the largest speed still works against its weight.
  std::vector<std::pair<int, double>> blocks;
  double largest = 0.0;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    const model::Block& block = m.blocks[b];
    const Vec3& v = r.mechanism.blocks[b].translation;
    if (block.is_support() || v.isZero()) continue;
    const double per_weight = -(m.gravity.dot(v) + alpha * d.dot(v)) / power;
    blocks.emplace_back(static_cast<int>(b), block.volume * per_weight);
    largest = std::max(largest, std::abs(blocks.back().second));
  }
  for (const auto& entry : blocks) {
    if (std::abs(entry.second) > kRoundOff * largest) s.block_unit_weight.push_back(entry);
  }
  return s;
}

}  // namespace rbla::analysis
