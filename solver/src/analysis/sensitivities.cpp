#include "analysis/sensitivities.hpp"

#include <algorithm>
#include <cmath>

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

/// d alpha / d mu_k of one interface: sum over its points of N v_n / mu, over P.
double interface_friction_derivative(const model::ContactInterface& contact, const InterfaceResult& r, double live,
                                     const Floors& floors) {
  if (!(contact.friction > 0.0)) return 0.0;
  double sum = 0.0;
  for (const PointResult& point : r.points) {
    const double opening = point.relative_velocity.x();  // normal component of v_b - v_a
    if (point.normal_force > floors.force && opening > floors.opening) sum += point.normal_force * opening;
  }
  return sum / (contact.friction * live);
}

}  // namespace

std::optional<Sensitivities> load_multiplier_sensitivities(const model::Model& m, const AnalysisResult& r) {
  if (r.verdict != Verdict::Collapse || r.type != model::AnalysisType::LoadMultiplier ||
      r.friction_model != model::FrictionModel::Associative || !r.load_multiplier) {
    return std::nullopt;
  }
  const double live = r.work.live_work;
  if (!(live > 0.0) || r.mechanism.interfaces.size() != m.interfaces.size() ||
      r.mechanism.blocks.size() != m.blocks.size()) {
    return std::nullopt;
  }
  Sensitivities s;
  const Floors floors = round_off_floors(r.mechanism);
  for (std::size_t k = 0; k < m.interfaces.size(); ++k) {
    const double d = interface_friction_derivative(m.interfaces[k], r.mechanism.interfaces[k], live, floors);
    if (d == 0.0) continue;
    s.interface_friction.emplace_back(static_cast<int>(k), d);
    s.friction_factor += m.interfaces[k].friction * d;
  }
  const double alpha = *r.load_multiplier;
  const Vec3 d = m.analysis.seismic_direction.value_or(Vec3::Zero());
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    const model::Block& block = m.blocks[b];
    const Vec3& v = r.mechanism.blocks[b].translation;
    if (block.is_support() || !r.mechanism.blocks[b].moving || v.isZero()) continue;
    const double per_weight = -(m.gravity.dot(v) + alpha * d.dot(v)) / live;
    s.block_unit_weight.emplace_back(static_cast<int>(b), block.volume * per_weight);
  }
  return s;
}

}  // namespace rbla::analysis
