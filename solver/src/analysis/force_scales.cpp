#include "analysis/force_scales.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace rbla::analysis {

namespace {

/// Joints whose plane is vertical still take this share (per unit area) of a block's load when
/// they lie below its centroid: a keystone wedged between two vertical faces is held by them.
constexpr double kVerticalJointWeight = 1e-2;

/// Exponent of the heavier scale in the weighted geometric mean given to a block beside another
/// (see force_scales). Measured on a light block beside a heavy one whose own sliding governs
/// (closed form 0.3) and on the arch sample with one light voussoir at the crown, carrying the
/// thrust (against the same arch with that voussoir weightless), contrasts 1e12 to 1e40: with
/// 0.5 the first went wrong from 1e13 and the second from 1e24; with 0.4 from 1e15 and 1e18;
/// with 0.35 from 1e18 and 1e17 (right up to 1e17 and 1e16).
constexpr double kLateralWeight = 0.35;

/// Own load of every free block: weight plus the magnitudes of its dead and live point loads.
std::vector<double> own_loads(const model::Model& m) {
  std::vector<double> load(m.blocks.size(), 0.0);
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    if (!m.blocks[b].is_support()) load[b] = m.blocks[b].weight();
  }
  for (const auto* loads : {&m.dead_loads, &m.live_loads}) {
    for (const model::PointLoad& point_load : *loads) load[point_load.block] += point_load.force.norm();
  }
  return load;
}

struct LoadPath {
  std::vector<double> carried;  ///< kN, per block: own load plus what the blocks above pass down
  std::vector<char> passes;     ///< per interface: a block passed load down through it
};

/// Passes each free block's load, from the highest down, to the interfaces below its centroid
/// (weighted by area, more for flatter joints) and through them to the lower free blocks.
LoadPath load_path(const model::Model& m) {
  LoadPath path{own_loads(m), std::vector<char>(m.interfaces.size(), 0)};
  const std::size_t n = m.blocks.size();
  std::vector<std::vector<int>> touching(n);
  for (std::size_t i = 0; i < m.interfaces.size(); ++i) {
    touching[m.interfaces[i].block_a].push_back(static_cast<int>(i));
    touching[m.interfaces[i].block_b].push_back(static_cast<int>(i));
  }
  auto height = [&](const model::Vec3& p) { return -m.gravity.dot(p); };
  std::vector<int> order;
  for (std::size_t b = 0; b < n; ++b) {
    if (!m.blocks[b].is_support()) order.push_back(static_cast<int>(b));
  }
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const double ha = height(m.blocks[a].centroid), hb = height(m.blocks[b].centroid);
    return ha > hb || (ha == hb && a < b);
  });
  std::vector<double> share;
  for (const int b : order) {
    const double top = height(m.blocks[b].centroid);
    share.assign(touching[b].size(), 0.0);
    double total = 0.0;
    for (std::size_t k = 0; k < touching[b].size(); ++k) {
      const model::ContactInterface& contact = m.interfaces[touching[b][k]];
      const int other = contact.block_a == b ? contact.block_b : contact.block_a;
      // Only to supports and strictly lower free blocks, which come later in the order: no load
      // goes round.
      if (height(contact.centroid) >= top) continue;
      if (!m.blocks[other].is_support() && !(height(m.blocks[other].centroid) < top)) continue;
      share[k] = contact.area * (std::abs(contact.normal.dot(m.gravity)) + kVerticalJointWeight);
      total += share[k];
    }
    if (!(total > 0.0)) continue;  // nothing below the centroid: the load stays with the block
    for (std::size_t k = 0; k < touching[b].size(); ++k) {
      if (!(share[k] > 0.0)) continue;
      const int i = touching[b][k];
      const int other = m.interfaces[i].block_a == b ? m.interfaces[i].block_b : m.interfaces[i].block_a;
      path.passes[i] = 1;
      if (!m.blocks[other].is_support()) path.carried[other] += path.carried[b] * share[k] / total;
    }
  }
  return path;
}

/// The scale of a carried load: the reference within the band, else the load to within the band.
double banded(double load, double reference) {
  const double ratio = load / reference;
  if (ratio > kForceScaleBand) return reference * (ratio / kForceScaleBand);
  if (ratio < 1.0 / kForceScaleBand) return reference * (ratio * kForceScaleBand);
  return reference;
}

}  // namespace

ForceScales force_scales(const model::Model& m, double reference, double lateral_limit) {
  ForceScales s;
  s.reference = reference;
  s.lateral_limit = lateral_limit;
  s.own = own_loads(m);
  const LoadPath path = load_path(m);
  s.carried = path.carried;
  std::vector<double>& carried = s.carried;
  // A weightless block that carries nothing takes the smallest load of a free neighbour (its
  // forces come from them), or the reference.
  std::vector<double> floor(m.blocks.size(), std::numeric_limits<double>::infinity());
  for (const auto& contact : m.interfaces) {
    for (const auto& [self, other] : {std::pair{contact.block_a, contact.block_b}, std::pair{contact.block_b, contact.block_a}}) {
      if (!m.blocks[other].is_support() && carried[other] > 0.0) floor[self] = std::min(floor[self], carried[other]);
    }
  }
  s.block.assign(m.blocks.size(), reference);
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    if (m.blocks[b].is_support()) continue;
    if (!(carried[b] > 0.0)) carried[b] = std::isfinite(floor[b]) ? floor[b] : reference;
    s.block[b] = banded(carried[b], reference);
  }
  // Whether a neighbour beside a block (no load passed between them) pushes through it is known
  // only after the solve: a light voussoir between heavy ones carries their thrust, a light block
  // standing beside a heavy one only its own weight. Its rows take a weighted geometric mean of
  // the two scales (light^0.65 heavy^0.35), which keeps either answer within reach.
  const std::vector<double> own_scale = s.block;
  for (std::size_t i = 0; i < m.interfaces.size(); ++i) {
    const model::ContactInterface& contact = m.interfaces[i];
    const int a = contact.block_a, b = contact.block_b;
    if (path.passes[i] || m.blocks[a].is_support() || m.blocks[b].is_support()) continue;
    if (own_scale[a] == own_scale[b]) continue;
    const double light = std::min(own_scale[a], own_scale[b]), heavy = std::max(own_scale[a], own_scale[b]);
    const double mean = std::pow(light, 1.0 - kLateralWeight) * std::pow(heavy, kLateralWeight);
    s.block[a] = std::max(s.block[a], mean);
    s.block[b] = std::max(s.block[b], mean);
    const double contrast = std::max(carried[a], carried[b]) / std::min(carried[a], carried[b]);
    if (contrast > s.lateral_contrast) {
      s.lateral_contrast = contrast;
      s.lateral_light = carried[a] < carried[b] ? a : b;
      s.lateral_heavy = carried[a] < carried[b] ? b : a;
    }
    if (contrast > lateral_limit) ++s.num_lateral_over_limit;
  }
  // An interface's forces act on both its blocks: the smaller of their scales.
  s.interface.resize(m.interfaces.size());
  s.interface_load.resize(m.interfaces.size());
  for (std::size_t i = 0; i < m.interfaces.size(); ++i) {
    const model::ContactInterface& contact = m.interfaces[i];
    double scale = std::numeric_limits<double>::infinity(), load = scale;
    for (const int b : {contact.block_a, contact.block_b}) {
      if (m.blocks[b].is_support()) continue;
      scale = std::min(scale, s.block[b]);
      load = std::min(load, carried[b]);
    }
    s.interface[i] = std::isfinite(scale) ? scale : reference;
    s.interface_load[i] = std::isfinite(load) && s.interface[i] != reference ? load : reference;
  }
  return s;
}

}  // namespace rbla::analysis
