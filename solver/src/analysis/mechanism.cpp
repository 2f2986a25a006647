#include "analysis/mechanism.hpp"

#include <algorithm>
#include <cmath>

namespace rbla::analysis {

std::vector<BlockMotion> block_velocities(const model::Model& m, const Formulation& f, const Eigen::VectorXd& y) {
  std::vector<BlockMotion> motions(m.blocks.size());
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    const int row = f.block_row[b];
    if (row < 0) continue;
    BlockMotion& motion = motions[b];
    // Rows divided by the block's scale have multipliers multiplied by it: back to common units.
    const double unscale = f.force_scale / f.block_scale[b];
    if (m.blocks[b].role == model::BlockRole::MovingSupport) {
      motion.translation = -y[row] * f.settlement_direction;
    } else if (f.options.planar) {
      motion.translation = -unscale * (y[row] * f.options.frame.e1 + y[row + 1] * f.options.frame.e2);
      motion.rotation = -unscale * y[row + 2] / f.length_scale * f.options.frame.normal;
    } else {
      motion.translation = -unscale * y.segment<3>(row);
      motion.rotation = -unscale * y.segment<3>(row + 3) / f.length_scale;
    }
  }
  return motions;
}

void set_block_multipliers(const Formulation& f, int block, const BlockMotion& motion, Eigen::VectorXd& y) {
  const int row = f.block_row[block];
  const double scale = f.block_scale[block] / f.force_scale;  // 1 / block_velocities' unscale
  if (f.options.planar) {
    y[row] = -scale * motion.translation.dot(f.options.frame.e1);
    y[row + 1] = -scale * motion.translation.dot(f.options.frame.e2);
    y[row + 2] = -scale * f.length_scale * motion.rotation.dot(f.options.frame.normal);
  } else {
    y.segment<3>(row) = -scale * motion.translation;
    y.segment<3>(row + 3) = -scale * f.length_scale * motion.rotation;
  }
}

Vec3 point_velocity(const model::Model& m, const std::vector<BlockMotion>& motions, int block, const Vec3& p) {
  const BlockMotion& motion = motions[block];
  return motion.translation + motion.rotation.cross(p - m.blocks[block].centroid);
}

std::vector<Vec3> formulation_point_velocities(const model::Model& m, const Formulation& f, const Eigen::VectorXd& y) {
  const std::vector<BlockMotion> motions = block_velocities(m, f, y);
  std::vector<Vec3> d(f.points.size());
  for (std::size_t p = 0; p < f.points.size(); ++p) {
    const FormulationPoint& point = f.points[p];
    const model::ContactInterface& c = m.interfaces[point.interface_index];
    d[p] = point_velocity(m, motions, c.block_b, point.position) - point_velocity(m, motions, c.block_a, point.position);
  }
  return d;
}

double block_speed(const model::Block& block, const BlockMotion& motion) {
  double largest = 0.0;
  for (const Vec3& v : block.vertices) {
    largest = std::max(largest, (motion.translation + motion.rotation.cross(v - block.centroid)).norm());
  }
  return largest;
}

std::vector<double> block_speeds(const model::Model& m, const std::vector<BlockMotion>& motions) {
  std::vector<double> speed(m.blocks.size(), 0.0);
  for (std::size_t b = 0; b < m.blocks.size(); ++b) speed[b] = block_speed(m.blocks[b], motions[b]);
  return speed;
}

double normalise(const model::Model& m, const Formulation& f, Normalisation normalisation, double target,
                 std::vector<BlockMotion>& motions) {
  const std::vector<double> speed = block_speeds(m, motions);
  double reference = 0.0;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    if (!m.blocks[b].is_support()) reference = std::max(reference, speed[b]);
  }
  if (normalisation == Normalisation::UnitSettlement) {
    reference = 0.0;
    for (std::size_t b = 0; b < m.blocks.size(); ++b) {
      if (m.blocks[b].role == model::BlockRole::MovingSupport && f.block_row[b] >= 0) {
        reference = motions[b].translation.dot(f.settlement_direction);
        break;
      }
    }
  }
  if (!(std::abs(reference) > 0.0)) return 0.0;
  const double factor = target / reference;
  for (BlockMotion& motion : motions) {
    motion.translation *= factor;
    motion.rotation *= factor;
  }
  return factor;
}

std::vector<std::vector<Vec3>> corner_forces(const model::Model& m, const Formulation& f,
                                             const std::vector<Vec3>& point_forces) {
  std::vector<std::vector<Vec3>> forces(m.interfaces.size());
  for (std::size_t i = 0; i < m.interfaces.size(); ++i) forces[i].assign(m.interfaces[i].polygon.size(), Vec3::Zero());
  for (std::size_t p = 0; p < f.points.size(); ++p) {
    const FormulationPoint& point = f.points[p];
    for (int k : point.corners) {
      forces[point.interface_index][k] = point_forces[p] / static_cast<double>(point.corners.size());
    }
  }
  return forces;
}

namespace {

ContactState classify(const Vec3& relative, double threshold, double mu, bool associative) {
  const double opening = relative[0];
  const double slip = std::hypot(relative[1], relative[2]);
  if (std::abs(opening) <= threshold && slip <= threshold) return ContactState::Closed;
  if (slip <= threshold) return ContactState::Opening;
  // Associative sliding dilates by mu times the slip (normality): that is still sliding.
  const double dilatancy = associative ? mu * slip : 0.0;
  return opening <= dilatancy + threshold ? ContactState::Sliding : ContactState::OpeningSliding;
}

/// Relative velocity of block_b against block_a at each corner of each interface, in the
/// interface frame (normal, t1, t2).
std::vector<std::vector<Vec3>> relative_velocities(const model::Model& m, const std::vector<BlockMotion>& motions) {
  std::vector<std::vector<Vec3>> relative(m.interfaces.size());
  for (std::size_t i = 0; i < m.interfaces.size(); ++i) {
    const model::ContactInterface& c = m.interfaces[i];
    for (const Vec3& p : c.polygon) {
      const Vec3 dv = point_velocity(m, motions, c.block_b, p) - point_velocity(m, motions, c.block_a, p);
      relative[i].emplace_back(dv.dot(c.normal), dv.dot(c.tangent1), dv.dot(c.tangent2));
    }
  }
  return relative;
}

/// The crack threshold of each interface (kCrackFraction of the larger speed of its blocks), and
/// whether it stays closed (its two blocks move as one there).
void crack_thresholds(const model::Model& m, const std::vector<double>& speed,
                      const std::vector<std::vector<Vec3>>& relative, std::vector<double>& threshold,
                      std::vector<bool>& closed) {
  threshold.assign(m.interfaces.size(), 0.0);
  closed.assign(m.interfaces.size(), true);
  for (std::size_t i = 0; i < m.interfaces.size(); ++i) {
    const model::ContactInterface& c = m.interfaces[i];
    threshold[i] = kCrackFraction * std::max(speed[c.block_a], speed[c.block_b]);
    double largest = 0.0;
    for (const Vec3& dv : relative[i]) largest = std::max(largest, dv.norm());
    closed[i] = !(threshold[i] > 0.0) || largest < threshold[i];
  }
}

/// Virtual power of the dead loads (self-weight, dead point loads) on each block.
std::vector<double> dead_load_power(const model::Model& m, const std::vector<BlockMotion>& motions) {
  std::vector<double> power(m.blocks.size(), 0.0);
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    if (!m.blocks[b].is_support()) power[b] = m.blocks[b].weight() * m.gravity.dot(motions[b].translation);
  }
  for (const model::PointLoad& load : m.dead_loads) {
    power[load.block] += load.force.dot(point_velocity(m, motions, load.block, load.point)) +
                         load.moment.dot(motions[load.block].rotation);
  }
  return power;
}

/// Blocks moving by at least kMovingFraction of the largest speed (in a certificate, only those
/// going down), and those joined to them through closed interfaces (breadth-first). Fixed
/// supports never move.
std::vector<bool> moving_blocks(const model::Model& m, const std::vector<double>& speed,
                                const std::vector<bool>& closed, const std::vector<double>* dead_power) {
  std::vector<bool> moving(m.blocks.size(), false);
  const double largest = speed.empty() ? 0.0 : *std::max_element(speed.begin(), speed.end());
  if (!(largest > 0.0)) return moving;
  std::vector<std::vector<int>> joints(m.blocks.size());
  for (std::size_t i = 0; i < m.interfaces.size(); ++i) {
    if (!closed[i]) continue;
    joints[m.interfaces[i].block_a].push_back(static_cast<int>(i));
    joints[m.interfaces[i].block_b].push_back(static_cast<int>(i));
  }
  std::vector<int> queue;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    const bool goes_down = !dead_power || (*dead_power)[b] > 0.0;
    if (m.blocks[b].role != model::BlockRole::Fixed && speed[b] >= kMovingFraction * largest && goes_down) {
      moving[b] = true;
      queue.push_back(static_cast<int>(b));
    }
  }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    for (int i : joints[queue[head]]) {
      const model::ContactInterface& c = m.interfaces[i];
      const int other = c.block_a == queue[head] ? c.block_b : c.block_a;
      if (moving[other] || m.blocks[other].role == model::BlockRole::Fixed) continue;
      moving[other] = true;
      queue.push_back(other);
    }
  }
  return moving;
}

}  // namespace

void fill_interfaces(const model::Model& m, const std::vector<std::vector<Vec3>>& corner_forces, bool associative,
                     Mechanism& mechanism, MotionKind kind) {
  mechanism.interfaces.assign(m.interfaces.size(), InterfaceResult{});
  mechanism.cracked_interfaces.clear();
  const std::vector<double> speed = block_speeds(m, mechanism.blocks);
  const std::vector<std::vector<Vec3>> relative = relative_velocities(m, mechanism.blocks);
  std::vector<double> threshold;
  std::vector<bool> closed;
  crack_thresholds(m, speed, relative, threshold, closed);
  const std::vector<double> dead_power =
      kind == MotionKind::Certificate ? dead_load_power(m, mechanism.blocks) : std::vector<double>{};
  const std::vector<bool> moving =
      moving_blocks(m, speed, closed, kind == MotionKind::Certificate ? &dead_power : nullptr);
  for (std::size_t b = 0; b < m.blocks.size(); ++b) mechanism.blocks[b].moving = moving[b];

  for (std::size_t i = 0; i < m.interfaces.size(); ++i) {
    const model::ContactInterface& c = m.interfaces[i];
    InterfaceResult& result = mechanism.interfaces[i];
    const bool in_mechanism = !closed[i] && (moving[c.block_a] || moving[c.block_b]);
    bool any_closed = false, any_open = false, any_slide = false;
    Vec3 total = Vec3::Zero();
    for (std::size_t k = 0; k < c.polygon.size(); ++k) {
      PointResult point;
      point.position = c.polygon[k];
      const Vec3 force = corner_forces.empty() ? Vec3::Zero() : corner_forces[i][k];
      point.normal_force = force.dot(c.normal);
      point.shear1 = force.dot(c.tangent1);
      point.shear2 = force.dot(c.tangent2);
      point.relative_velocity = relative[i][k];
      point.state = in_mechanism ? classify(relative[i][k], threshold[i], c.friction, associative) : ContactState::Closed;
      any_closed |= point.state == ContactState::Closed;
      any_open |= point.state == ContactState::Opening || point.state == ContactState::OpeningSliding;
      any_slide |= point.state == ContactState::Sliding || point.state == ContactState::OpeningSliding;
      total += force;
      result.points.push_back(point);
    }
    result.normal_force = total.dot(c.normal);
    result.shear_force = std::hypot(total.dot(c.tangent1), total.dot(c.tangent2));
    if (any_slide) result.state = any_open ? InterfaceState::OpeningSliding : InterfaceState::Sliding;
    else if (any_open) result.state = any_closed ? InterfaceState::Hinge : InterfaceState::Opening;
    else result.state = InterfaceState::Closed;
    result.cracked = result.state != InterfaceState::Closed;
    if (result.cracked) mechanism.cracked_interfaces.push_back(static_cast<int>(i));
  }
}

}  // namespace rbla::analysis
