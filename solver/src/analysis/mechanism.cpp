#include "analysis/mechanism.hpp"

#include "analysis/limit_analysis.hpp"

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

Vec3 point_velocity(const model::Model& m, const std::vector<BlockMotion>& motions, int block, const Vec3& p) {
  const BlockMotion& motion = motions[block];
  return motion.translation + motion.rotation.cross(p - m.blocks[block].centroid);
}

double normalise(const model::Model& m, const Formulation& f, Normalisation normalisation, double target,
                 std::vector<BlockMotion>& motions) {
  std::vector<double> speed(m.blocks.size(), 0.0);
  double largest = 0.0;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    for (const Vec3& v : m.blocks[b].vertices) {
      speed[b] = std::max(speed[b], point_velocity(m, motions, static_cast<int>(b), v).norm());
    }
    if (!m.blocks[b].is_support()) largest = std::max(largest, speed[b]);
  }
  double reference = largest;
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
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    motions[b].translation *= factor;
    motions[b].rotation *= factor;
    motions[b].moving = speed[b] > kVelocityThreshold * largest && largest > 0.0;
  }
  return factor;
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

}  // namespace

void fill_interfaces(const model::Model& m, const Formulation& f, const std::vector<Vec3>& point_forces,
                     bool associative, Mechanism& mechanism) {
  mechanism.interfaces.assign(m.interfaces.size(), InterfaceResult{});
  mechanism.cracked_interfaces.clear();
  // Forces of the formulation points, shared among the corners they stand for.
  std::vector<std::vector<Vec3>> corner_forces(m.interfaces.size());
  for (std::size_t i = 0; i < m.interfaces.size(); ++i) {
    corner_forces[i].assign(m.interfaces[i].polygon.size(), Vec3::Zero());
  }
  for (std::size_t p = 0; p < f.points.size(); ++p) {
    const FormulationPoint& point = f.points[p];
    for (int k : point.corners) {
      corner_forces[point.interface_index][k] = point_forces[p] / static_cast<double>(point.corners.size());
    }
  }
  double largest = 0.0;
  std::vector<std::vector<Vec3>> relative(m.interfaces.size());
  for (std::size_t i = 0; i < m.interfaces.size(); ++i) {
    const model::ContactInterface& c = m.interfaces[i];
    for (const Vec3& p : c.polygon) {
      const Vec3 dv = point_velocity(m, mechanism.blocks, c.block_b, p) - point_velocity(m, mechanism.blocks, c.block_a, p);
      relative[i].emplace_back(dv.dot(c.normal), dv.dot(c.tangent1), dv.dot(c.tangent2));
      largest = std::max(largest, dv.norm());
    }
  }
  const double threshold = kVelocityThreshold * largest;
  for (std::size_t i = 0; i < m.interfaces.size(); ++i) {
    const model::ContactInterface& c = m.interfaces[i];
    InterfaceResult& result = mechanism.interfaces[i];
    bool any_closed = false, any_open = false, any_slide = false;
    Vec3 total = Vec3::Zero();
    for (std::size_t k = 0; k < c.polygon.size(); ++k) {
      PointResult point;
      point.position = c.polygon[k];
      const Vec3& force = corner_forces[i][k];
      point.normal_force = force.dot(c.normal);
      point.shear1 = force.dot(c.tangent1);
      point.shear2 = force.dot(c.tangent2);
      point.relative_velocity = relative[i][k];
      point.state = largest > 0.0 ? classify(relative[i][k], threshold, c.friction, associative) : ContactState::Closed;
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
