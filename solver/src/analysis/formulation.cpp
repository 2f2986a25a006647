#include "analysis/formulation.hpp"

#include "analysis/force_scales.hpp"
#include "analysis/solve_steps.hpp"
#include "geometry/polyhedron.hpp"
#include "model/errors.hpp"
#include "model/angles.hpp"

#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rbla::analysis {

namespace {

constexpr double kParallelTolerance = 1e-9;  // |cos| or |sin| below which directions count as exact

Vec3 axis_vector(int axis) {
  Vec3 e = Vec3::Zero();
  e[axis] = 1.0;
  return e;
}

/// The planar reduction (3 rows per block, the corners of an interface summed at its two ends)
/// is exact when the 3-D problem is symmetric about the mid-plane normal to the axis and
/// invariant along it: then a symmetric optimum exists (average any optimum with its mirror
/// image), its out-of-plane forces and moments cancel, and any planar solution lifts back with
/// each end force split between its two corners. That needs the whole arrangement to be an
/// extrusion, not only each block: every free block a right prism over the same depth, every
/// interface spanning that depth, and every load in the mid-plane. An interface that covers only
/// part of the depth (a block overhanging the edge of its support along the axis) carries a
/// moment about the in-plane axes that the planar rows drop.

struct Scales {
  double length = 1.0;
  double force = 1.0;
};

/// Mean block size and mean free-block weight: O(1) coefficients whatever the user's units.
Scales choose_scales(const model::Model& m) {
  Scales s;
  double size_sum = 0.0, weight_sum = 0.0;
  int count = 0, weighted = 0;
  for (const model::Block& block : m.blocks) {
    if (block.is_support()) continue;
    size_sum += model::bounding_box_of(block.vertices).diagonal();
    ++count;
    if (block.weight() > 0.0) {
      weight_sum += block.weight();
      ++weighted;
    }
  }
  if (count > 0 && size_sum > 0.0) s.length = size_sum / count;
  if (weighted > 0) {
    s.force = weight_sum / weighted;
  } else {
    double load_sum = 0.0;
    for (const auto& load : m.live_loads) load_sum += load.force.norm();
    if (load_sum > 0.0) s.force = load_sum / static_cast<double>(m.live_loads.size());
  }
  return s;
}

/// Length below which two coordinates count as one in the extrusion tests and in the planar
/// corner groups: 1e-4 (kModelRelativeTolerance) of the mean free block's size, or the model's
/// distance tolerance when that is smaller. Not that tolerance alone: it grows with the model's
/// extent and with a gap tolerance set for detection, neither of which says whether the blocks
/// form an extrusion (a fixed block 3 km away let a cap stone overhanging its pier by 0.3 m pass
/// as planar, and the planar LP reported a collapse at 0.38 for a block that cannot stand). A
/// smaller tolerance can only send a model to the 3-D formulation, which is exact for every model.
double extrusion_tolerance(const model::Model& m) {
  return std::min(m.distance_tolerance(), model::kModelRelativeTolerance * choose_scales(m).length);
}

/// Why the free blocks are not right prisms along `axis` over one depth [lo, hi]; empty when they are.
std::string prism_obstacle(const model::Model& m, int axis, double& lo, double& hi) {
  const Vec3 e = axis_vector(axis);
  const std::string name = std::string(1, static_cast<char>('x' + axis));
  const double tol = extrusion_tolerance(m);
  const model::Block* first = nullptr;
  for (const model::Block& block : m.blocks) {
    // A support enters the problem only through its interfaces, which are checked apart.
    if (block.is_support()) continue;
    double block_lo = std::numeric_limits<double>::infinity(), block_hi = -block_lo;
    for (const Vec3& v : block.vertices) {
      block_lo = std::min(block_lo, v[axis]);
      block_hi = std::max(block_hi, v[axis]);
    }
    if (!first) {
      first = &block;
      lo = block_lo;
      hi = block_hi;
    } else if (std::abs(block_lo - lo) > tol || std::abs(block_hi - hi) > tol) {
      return "blocks '" + first->id + "' and '" + block.id + "' do not span the same depth along " + name;
    }
    for (const auto& face : block.faces) {
      const double c = std::abs(geometry::face_geometry(block.vertices, face).normal.dot(e));
      if (c > 1e-9 && c < 1.0 - 1e-9) return "block '" + block.id + "' is not a prism along " + name;
    }
    // Faces only parallel or normal to the axis still allow steps (a block narrower along the
    // axis in its upper part): a right prism has every vertex on one of its two end planes.
    for (const Vec3& v : block.vertices) {
      if (std::abs(v[axis] - lo) > tol && std::abs(v[axis] - hi) > tol) {
        return "block '" + block.id + "' is not a prism along " + name + " (a vertex lies between its end faces)";
      }
    }
  }
  return "";
}

/// Why an interface does not span the whole depth [lo, hi] along `axis` as a rectangle; empty
/// when every one does. The polygon lies in a plane containing the axis, inside the rectangle
/// [lo, hi] x [its in-plane extent]; it is that rectangle when its area fills it.
std::string interface_obstacle(const model::Model& m, int axis, double lo, double hi) {
  const Vec3 e = axis_vector(axis);
  const std::string name = std::string(1, static_cast<char>('x' + axis));
  const double tol = extrusion_tolerance(m);
  for (const auto& contact : m.interfaces) {
    if (std::abs(contact.normal.dot(e)) > 1e-9) return "interface '" + contact.id + "' is not parallel to " + name;
    const Vec3 t = e.cross(contact.normal).normalized();
    double a_lo = std::numeric_limits<double>::infinity(), a_hi = -a_lo, s_lo = a_lo, s_hi = -a_lo;
    for (const Vec3& p : contact.polygon) {
      a_lo = std::min(a_lo, p[axis]);
      a_hi = std::max(a_hi, p[axis]);
      s_lo = std::min(s_lo, p.dot(t));
      s_hi = std::max(s_hi, p.dot(t));
    }
    const double depth = hi - lo, width = s_hi - s_lo;
    if (a_lo > lo + tol || a_hi < hi - tol || contact.area < depth * width - 2.0 * tol * (depth + width)) {
      return "interface '" + contact.id + "' does not span the blocks' whole depth along " + name;
    }
  }
  return "";
}

/// Why the loads are not all in the mid-plane normal to `axis`; empty when they are.
std::string load_obstacle(const model::Model& m, int axis, double mid) {
  const Vec3 e = axis_vector(axis);
  const std::string name = std::string(1, static_cast<char>('x' + axis));
  const double tol = extrusion_tolerance(m);
  const model::AnalysisRequest& a = m.analysis;
  if (a.seismic_direction && std::abs(a.seismic_direction->dot(e)) > kParallelTolerance) {
    return "the seismic direction has a component along " + name;
  }
  if (a.type == model::AnalysisType::Settlement && std::abs(a.settlement_direction.dot(e)) > kParallelTolerance) {
    return "the settlement direction has a component along " + name;
  }
  for (const auto* loads : {&m.dead_loads, &m.live_loads}) {
    for (const model::PointLoad& load : *loads) {
      if (std::abs(load.force.dot(e)) > kParallelTolerance * load.force.norm() ||
          (load.moment - load.moment.dot(e) * e).norm() > kParallelTolerance * load.moment.norm() ||
          (load.force.norm() > 0.0 && std::abs(load.point[axis] - mid) > tol)) {
        return "a load on block '" + m.blocks[load.block].id + "' acts out of the plane normal to " + name;
      }
    }
  }
  return "";
}

/// Why `axis` is not a planar extrusion axis of the model; empty when it is.
std::string planar_obstacle(const model::Model& m, int axis, double& depth) {
  if (std::abs(axis_vector(axis).dot(m.gravity)) > kParallelTolerance) {
    return std::string("gravity is along ") + static_cast<char>('x' + axis);
  }
  double lo = 0.0, hi = 0.0;
  std::string obstacle = prism_obstacle(m, axis, lo, hi);
  if (obstacle.empty()) obstacle = interface_obstacle(m, axis, lo, hi);
  if (obstacle.empty()) obstacle = load_obstacle(m, axis, 0.5 * (lo + hi));
  depth = hi - lo;
  return obstacle;
}

/// One variable of a contact point before indices are assigned.
struct VariableSpec {
  Vec3 force = Vec3::Zero();  // force on block_b per unit of the variable (force-scale units)
  bool in_radius_row = false;
};

struct PointSpec {
  std::vector<VariableSpec> orthant;  // nonnegative variables
  std::vector<VariableSpec> cone;     // one second-order cone (empty when none)
  bool has_radius_row = false;
};

PointSpec friction_variables(const FormulationOptions& options, double mu, const Vec3& n, const Vec3& t1,
                             const Vec3& t2) {
  PointSpec spec;
  const bool pyramid = options.cone != model::ConeKind::Exact;
  const int m = options.pyramid_faces;
  // Circumscribed pyramid: its faces touch the cone, so its edges are 1/cos(pi/m) further out.
  const double edge_factor = options.cone == model::ConeKind::PyramidCircumscribed ? 1.0 / std::cos(model::kPi / m) : 1.0;
  auto edge = [&](int j) { return std::cos(2.0 * model::kPi * j / m) * t1 + std::sin(2.0 * model::kPi * j / m) * t2; };

  if (options.friction_set == FrictionSet::Cone) {
    if (options.planar) {
      // |T| <= mu N in the plane: the two edges of the 2-D cone, n +- mu t.
      spec.orthant.push_back({n + mu * t1, false});
      spec.orthant.push_back({n - mu * t1, false});
    } else if (pyramid) {
      for (int j = 0; j < m; ++j) spec.orthant.push_back({n + mu * edge_factor * edge(j), false});
    } else {
      // (N, tau1, tau2) in Q^3 with T = mu tau: ||T|| <= mu N.
      spec.cone = {{n, false}, {mu * t1, false}, {mu * t2, false}};
    }
    return spec;
  }
  // Cylinder of the non-associative scheme: N >= 0 free of the shear, ||T|| <= r.
  spec.has_radius_row = true;
  spec.orthant.push_back({n, false});
  if (options.planar) {
    // (rho, T) in Q^2, i.e. |T| <= rho, with rho = r fixed by the radius row: a row with one
    // entry, which the conic solver eliminates before factoring (T+ - T- with a slack would
    // make it a row of three).
    spec.cone = {{Vec3::Zero(), true}, {t1, false}};
  } else if (pyramid) {
    for (int j = 0; j < m; ++j) spec.orthant.push_back({edge_factor * edge(j), true});
    spec.orthant.push_back({Vec3::Zero(), true});
  } else {
    // (rho, T1, T2) in Q^3 with rho = r fixed by the radius row.
    spec.cone = {{Vec3::Zero(), true}, {t1, false}, {t2, false}};
  }
  return spec;
}

/// Blocks side by side whose loads differ beyond what one scaling of the problem resolves.
model::Warning lateral_contrast_warning(const model::Model& m, const ForceScales& loads) {
  const model::Block& light = m.blocks[loads.lateral_light];
  const model::Block& heavy = m.blocks[loads.lateral_heavy];
  const double kN = m.units.force_to_kN;
  std::string message = "blocks '" + light.id + "' and '" + heavy.id + "' touch side by side and carry loads " +
                        format(loads.lateral_contrast, 3) + " times apart (" +
                        format(loads.carried[loads.lateral_light] / kN, 3) + " and " +
                        format(loads.carried[loads.lateral_heavy] / kN, 3) + " " + m.units.force_name +
                        "): whether '" + heavy.id + "' pushes through '" + light.id +
                        "' is known only after the solve, and beyond a contrast of " +
                        format(loads.lateral_limit, 3) +
                        (m.analysis.friction_model == model::FrictionModel::NonAssociative ? " (non-associative)" : "") +
                        " the conic problem cannot be scaled to resolve both; the answer may be wrong";
  if (loads.num_lateral_over_limit > 1) {
    message += " (" + std::to_string(loads.num_lateral_over_limit) + " such pairs)";
  }
  return {"weight_contrast", message, "/blocks/" + std::to_string(loads.lateral_light)};
}

/// The per-block and per-interface force scales (analysis/force_scales.hpp) into `f` (block
/// scales, rhs_resolution, the warning); returned for the points' scales.
ForceScales apply_force_scales(const model::Model& m, Formulation& f) {
  const bool associative = m.analysis.friction_model != model::FrictionModel::NonAssociative;
  ForceScales loads =
      force_scales(m, f.force_scale, associative ? kLateralContrastLimit : kLateralContrastLimitNonAssociative);
  f.block_scale = loads.block;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    if (!m.blocks[b].is_support() && loads.block[b] != f.force_scale && loads.own[b] > 0.0) {
      f.rhs_resolution = std::min(f.rhs_resolution, loads.own[b] / loads.block[b]);
    }
  }
  if (loads.num_lateral_over_limit > 0) f.warnings.push_back(lateral_contrast_warning(m, loads));
  return loads;
}

}  // namespace

PlanarFrame detect_planar(const model::Model& m) {
  PlanarFrame frame;
  double best_depth = std::numeric_limits<double>::infinity();
  std::string reasons;
  for (int axis = 0; axis < 3; ++axis) {
    double depth = 0.0;
    const std::string obstacle = planar_obstacle(m, axis, depth);
    if (!obstacle.empty()) {
      reasons += (reasons.empty() ? "" : "; ") + obstacle;
      continue;
    }
    if (depth < best_depth) {
      best_depth = depth;
      frame.planar = true;
      frame.axis = axis;
    }
  }
  if (!frame.planar) {
    frame.reason = reasons;
    return frame;
  }
  frame.normal = axis_vector(frame.axis);
  frame.e1 = axis_vector((frame.axis + 1) % 3);
  frame.e2 = axis_vector((frame.axis + 2) % 3);
  return frame;
}

namespace {

/// Equilibrium rows: every free block; under settlement, the moving supports settle together by
/// the same amount along d, so they share one row: the sum of their loads along d equals R.
/// Fills f.block_row; returns the number of rows and sets `settlement_row` (-1 when none).
int assign_equilibrium_rows(const model::Model& m, Formulation& f, int& settlement_row) {
  int num_rows = 0;
  settlement_row = -1;
  f.block_row.assign(m.blocks.size(), -1);
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    const model::Block& block = m.blocks[b];
    if (!block.is_support()) {
      f.block_row[b] = num_rows;
      num_rows += f.rows_per_block;
    } else if (block.role == model::BlockRole::MovingSupport && f.settlement) {
      if (settlement_row < 0) settlement_row = num_rows++;
      f.block_row[b] = settlement_row;
    }
  }
  return num_rows;
}

/// The corners of one interface that make up each of its formulation points: every corner on its
/// own in 3-D; in the planar reduction the two ends of the segment along the in-plane tangent
/// t1 = e x n (and t2 = n x t1), which replace the interface's own tangents.
std::vector<std::vector<int>> corner_groups(const model::ContactInterface& contact, const FormulationOptions& options,
                                            double tol, Vec3& t1, Vec3& t2) {
  std::vector<std::vector<int>> groups;
  if (!options.planar) {
    for (int k = 0; k < static_cast<int>(contact.polygon.size()); ++k) groups.push_back({k});
    return groups;
  }
  // The interface is a rectangle extruded along e: its corners project onto two points of
  // the segment along the in-plane tangent t = e x n. Corners strictly between carry nothing
  // a corner could not (no-tension forces at interior points are convex combinations).
  t1 = options.frame.normal.cross(contact.normal).normalized();
  t2 = contact.normal.cross(t1);
  double s_min = std::numeric_limits<double>::infinity(), s_max = -s_min;
  for (const Vec3& p : contact.polygon) {
    s_min = std::min(s_min, p.dot(t1));
    s_max = std::max(s_max, p.dot(t1));
  }
  // Corners within the distance tolerance of an end belong to it; for a strip narrower
  // than the tolerance (a 1e-4 m knife edge in a 1 m model) a quarter of its width decides,
  // else both ends would merge into one point and the strip would lose its lever arm.
  const double width = s_max - s_min;
  const double group_tol = width > 0.0 ? std::min(tol, 0.25 * width) : tol;
  std::vector<int> low, high;
  for (int k = 0; k < static_cast<int>(contact.polygon.size()); ++k) {
    const double s = contact.polygon[k].dot(t1);
    if (s - s_min <= group_tol) low.push_back(k);
    else if (s_max - s <= group_tol) high.push_back(k);
  }
  groups.push_back(low);
  if (!high.empty()) groups.push_back(high);
  return groups;
}

/// The contact points of every interface (into f.points) and the friction variables of each.
std::vector<PointSpec> contact_points(const model::Model& m, const FormulationOptions& options,
                                      const ForceScales& loads, Formulation& f) {
  const double tol = extrusion_tolerance(m);
  std::vector<PointSpec> specs;
  for (std::size_t i = 0; i < m.interfaces.size(); ++i) {
    const model::ContactInterface& contact = m.interfaces[i];
    Vec3 t1 = contact.tangent1, t2 = contact.tangent2;
    for (auto& corners : corner_groups(contact, options, tol, t1, t2)) {
      FormulationPoint point;
      point.interface_index = static_cast<int>(i);
      point.friction = contact.friction;
      point.force_scale = loads.interface[i];
      point.load = loads.interface_load[i];
      for (int k : corners) point.position += contact.polygon[k];
      point.position /= static_cast<double>(corners.size());
      point.corners = std::move(corners);
      specs.push_back(friction_variables(options, contact.friction, contact.normal, t1, t2));
      f.points.push_back(std::move(point));
    }
  }
  return specs;
}

/// The load multiplier's copies, one per free block, and the pairs of copies tied equal.
struct MultiplierCopies {
  std::vector<int> variable;                // per model block: the variable of its copy
  std::vector<std::pair<int, int>> ties;    // (copy, copy) pairs of variables forced equal
  int count = 1;                            // variables 0 .. count-1
};

/// Free blocks that a live load (seismic or a point load) acts on.
int num_live_loaded_blocks(const model::Model& m) {
  int loaded_blocks = 0;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    if (m.blocks[b].is_support()) continue;
    const bool seismic = m.analysis.seismic_direction && m.blocks[b].weight() > 0.0;
    bool point_load = false;
    for (const auto& load : m.live_loads) point_load |= load.block == static_cast<int>(b);
    loaded_blocks += (seismic || point_load) ? 1 : 0;
  }
  return loaded_blocks;
}

/// A live load on every block (seismic) would make the multiplier's column dense, and with it
/// A W^2 A^T; keeping it out of the factor by a bordered solve loses accuracy near the optimum.
/// Instead each free block gets its own copy alpha_b of the multiplier, in its own rows only,
/// and equalities alpha_parent = alpha_child along a spanning tree of the contact graph tie the
/// copies together: each such row couples two blocks that already touch, so the normal matrix
/// keeps the block pattern of the structure. Variable 0 is the copy the objective sees.
MultiplierCopies multiplier_copies(const model::Model& m, const Formulation& f) {
  MultiplierCopies copies;
  copies.variable.assign(m.blocks.size(), f.multiplier_variable);
  if (f.settlement || num_live_loaded_blocks(m) <= 1) return copies;
  const std::vector<std::vector<int>> neighbours = m.neighbours(/*through_supports=*/false);
  std::vector<bool> seen(m.blocks.size(), false);
  int root_variable = -1;
  for (std::size_t start = 0; start < m.blocks.size(); ++start) {
    if (m.blocks[start].is_support() || seen[start]) continue;
    // Breadth-first over one connected group of free blocks; groups are tied to the first.
    std::vector<int> queue{static_cast<int>(start)};
    seen[start] = true;
    copies.variable[start] = root_variable < 0 ? f.multiplier_variable : copies.count++;
    if (root_variable < 0) root_variable = f.multiplier_variable;
    else copies.ties.emplace_back(root_variable, copies.variable[start]);
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const int block = queue[head];
      for (int next : neighbours[block]) {
        if (seen[next]) continue;
        seen[next] = true;
        copies.variable[next] = copies.count++;
        copies.ties.emplace_back(copies.variable[block], copies.variable[next]);
        queue.push_back(next);
      }
    }
  }
  return copies;
}

/// The entries of A for the contact forces: each variable's unit force on the two blocks of its
/// interface, as rows of force and moment about each block's centroid.
class ContactColumns {
 public:
  ContactColumns(const model::Model& m, const FormulationOptions& options, Formulation& f,
                 std::vector<Eigen::Triplet<double>>& triplets)
      : m_(m), options_(options), f_(f), triplets_(triplets) {}

  /// Places every point's variables: the multiplier copies first, then every orthant variable,
  /// then the cones (the conic layer's order); radius rows from `num_rows` on. Returns the number
  /// of variables and fills the second-order cones' sizes.
  int place(const std::vector<PointSpec>& specs, int num_alpha, int& num_rows, int& num_orthant,
            std::vector<Eigen::Index>& soc_dims) {
    num_orthant = num_alpha;
    for (const PointSpec& spec : specs) num_orthant += static_cast<int>(spec.orthant.size());
    int next_orthant = num_alpha;
    int next_cone = num_orthant;
    for (std::size_t p = 0; p < f_.points.size(); ++p) {
      FormulationPoint& point = f_.points[p];
      const PointSpec& spec = specs[p];
      if (spec.has_radius_row) point.radius_row = num_rows++;
      for (const VariableSpec& variable : spec.orthant) place_variable(point, variable, next_orthant++);
      if (!spec.cone.empty()) {
        for (const VariableSpec& variable : spec.cone) place_variable(point, variable, next_cone++);
        soc_dims.push_back(static_cast<Eigen::Index>(spec.cone.size()));
      }
    }
    return next_cone;
  }

 private:
  void place_variable(FormulationPoint& point, const VariableSpec& variable, int index) {
    const model::ContactInterface& contact = m_.interfaces[point.interface_index];
    point.generators.push_back({index, variable.force});
    add_block_entries(contact.block_b, +1.0, index, variable.force, point.force_scale, point.position);
    add_block_entries(contact.block_a, -1.0, index, variable.force, point.force_scale, point.position);
    if (variable.in_radius_row) triplets_.emplace_back(point.radius_row, index, 1.0);
  }

  /// `unit_force` is the force of one unit of the variable, in units of its point's scale; the
  /// rows are in units of the block's scale (the moving supports' row in the reference scale).
  void add_block_entries(int block, double sign, int variable, const Vec3& unit_force, double point_scale,
                         const Vec3& position) {
    const int row = f_.block_row[block];
    if (row < 0 || unit_force.isZero(0.0)) return;
    const model::Block& target = m_.blocks[block];
    if (target.role == model::BlockRole::MovingSupport) {
      triplets_.emplace_back(row, variable,
                             sign * unit_force.dot(f_.settlement_direction) * (point_scale / f_.force_scale));
      return;
    }
    const Vec3 force = unit_force * (point_scale / f_.block_scale[block]);
    const Vec3 moment = (position - target.centroid).cross(force) / f_.length_scale;
    if (options_.planar) {
      triplets_.emplace_back(row, variable, sign * force.dot(options_.frame.e1));
      triplets_.emplace_back(row + 1, variable, sign * force.dot(options_.frame.e2));
      triplets_.emplace_back(row + 2, variable, sign * moment.dot(options_.frame.normal));
    } else {
      for (int k = 0; k < 3; ++k) {
        if (force[k] != 0.0) triplets_.emplace_back(row + k, variable, sign * force[k]);
        if (moment[k] != 0.0) triplets_.emplace_back(row + 3 + k, variable, sign * moment[k]);
      }
    }
  }

  const model::Model& m_;
  const FormulationOptions& options_;
  Formulation& f_;
  std::vector<Eigen::Triplet<double>>& triplets_;
};

/// Adds a load on a free block, as its wrench about the centroid, to the block's rows of `target`.
void add_wrench(const model::Model& m, const FormulationOptions& options, const Formulation& f,
                Eigen::VectorXd& target, int block, const Vec3& force, const Vec3& moment_about_centroid) {
  const int row = f.block_row[block];
  if (row < 0 || m.blocks[block].is_support()) return;
  const Vec3 fs = force / f.block_scale[block];
  const Vec3 ms = moment_about_centroid / (f.block_scale[block] * f.length_scale);
  if (options.planar) {
    target[row] += fs.dot(options.frame.e1);
    target[row + 1] += fs.dot(options.frame.e2);
    target[row + 2] += ms.dot(options.frame.normal);
  } else {
    target.segment<3>(row) += fs;
    target.segment<3>(row + 3) += ms;
  }
}

/// The loads in the equilibrium rows: dead (self-weight and dead point loads) into `dead`, live
/// (seismic, live point loads; under settlement the ground's reaction -R d on the moving
/// supports, Portioli & Cascini 2016) into `live`, the multiplier's column.
void load_vectors(const model::Model& m, const FormulationOptions& options, const Formulation& f, int settlement_row,
                  Eigen::VectorXd& dead, Eigen::VectorXd& live) {
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    const model::Block& block = m.blocks[b];
    if (block.is_support()) continue;
    add_wrench(m, options, f, dead, static_cast<int>(b), block.weight() * m.gravity, Vec3::Zero());
    if (!f.settlement && m.analysis.seismic_direction) {
      add_wrench(m, options, f, live, static_cast<int>(b), block.weight() * *m.analysis.seismic_direction,
                 Vec3::Zero());
    }
  }
  auto moment_of = [&](const model::PointLoad& load) -> Vec3 {
    return (load.point - m.blocks[load.block].centroid).cross(load.force) + load.moment;
  };
  for (const model::PointLoad& load : m.dead_loads) add_wrench(m, options, f, dead, load.block, load.force, moment_of(load));
  if (!f.settlement) {
    for (const model::PointLoad& load : m.live_loads) {
      add_wrench(m, options, f, live, load.block, load.force, moment_of(load));
    }
  } else if (settlement_row >= 0) {
    live[settlement_row] = -1.0;
  }
}

/// The live load's entries, each row in the column of its block's copy of the multiplier (the
/// moving supports' row in the multiplier's own). With FormulationOptions::pattern_for_every_direction
/// every row of a block the seismic load acts on is kept, zero or not: a component that vanishes
/// along one direction (the y force at 0 degrees) does not along the next.
void add_live_column(const model::Model& m, const Formulation& f, const MultiplierCopies& copies,
                     const Eigen::VectorXd& live, std::vector<Eigen::Triplet<double>>& triplets) {
  const auto num_rows = static_cast<int>(live.size());
  std::vector<int> row_owner(num_rows, -1);  // the block whose equilibrium a row states
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    if (f.block_row[b] < 0 || m.blocks[b].is_support()) continue;
    for (int k = 0; k < f.rows_per_block; ++k) row_owner[f.block_row[b] + k] = static_cast<int>(b);
  }
  const bool seismic =
      f.options.pattern_for_every_direction && !f.settlement && m.analysis.seismic_direction.has_value();
  auto seismic_row = [&](int row) { return seismic && row_owner[row] >= 0 && m.blocks[row_owner[row]].weight() > 0.0; };
  for (int row = 0; row < num_rows; ++row) {
    if (live[row] == 0.0 && !seismic_row(row)) continue;
    const int variable = row_owner[row] >= 0 ? copies.variable[row_owner[row]] : f.multiplier_variable;
    triplets.emplace_back(row, variable, live[row]);
  }
}

}  // namespace

Formulation build_formulation(const model::Model& m, const FormulationOptions& options) {
  Formulation f;
  f.options = options;
  const Scales scales = choose_scales(m);
  f.length_scale = scales.length;
  f.force_scale = scales.force;
  const ForceScales loads = apply_force_scales(m, f);
  f.settlement = m.analysis.type == model::AnalysisType::Settlement;
  f.settlement_direction = m.analysis.settlement_direction;
  f.rows_per_block = options.planar ? 3 : 6;

  int settlement_row = -1;
  int num_rows = assign_equilibrium_rows(m, f, settlement_row);
  const std::vector<PointSpec> specs = contact_points(m, options, loads, f);
  const MultiplierCopies copies = multiplier_copies(m, f);

  // Rows: equilibrium, then one radius row per point that has one, then the multiplier's ties.
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<Eigen::Index> soc_dims;
  int num_orthant = 0;
  f.first_radius_row = num_rows;
  const int num_variables =
      ContactColumns(m, options, f, triplets).place(specs, copies.count, num_rows, num_orthant, soc_dims);
  f.num_radius_rows = num_rows - f.first_radius_row;

  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(num_rows);
  Eigen::VectorXd live = Eigen::VectorXd::Zero(num_rows);
  load_vectors(m, options, f, settlement_row, rhs, live);
  add_live_column(m, f, copies, live, triplets);
  for (const auto& [first, second] : copies.ties) {
    triplets.emplace_back(num_rows, first, 1.0);
    triplets.emplace_back(num_rows, second, -1.0);
    ++num_rows;
  }
  rhs.conservativeResize(num_rows);
  rhs.tail(copies.ties.size()).setZero();
  f.num_tie_rows = static_cast<int>(copies.ties.size());

  f.problem.A.resize(num_rows, num_variables);
  f.problem.A.setFromTriplets(triplets.begin(), triplets.end());
  f.problem.A.makeCompressed();
  f.problem.b = -rhs;
  f.problem.c = Eigen::VectorXd::Zero(num_variables);
  f.problem.c[f.multiplier_variable] = f.settlement ? 1.0 : -1.0;  // min R, or max alpha
  f.problem.cones.num_nonneg = num_orthant;
  f.problem.cones.soc_dims = std::move(soc_dims);
  return f;
}

std::vector<Vec3> Formulation::point_forces(const Eigen::VectorXd& x) const {
  std::vector<Vec3> forces(points.size(), Vec3::Zero());
  for (std::size_t p = 0; p < points.size(); ++p) {
    for (const Generator& g : points[p].generators) forces[p] += x[g.variable] * g.force;
    forces[p] *= points[p].force_scale;
  }
  return forces;
}

Eigen::VectorXd Formulation::rhs_with_radii(const std::vector<double>& radii_kN) const {
  Eigen::VectorXd b = problem.b;
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (points[p].radius_row >= 0) b[points[p].radius_row] = radii_kN[p] / points[p].force_scale;
  }
  return b;
}

}  // namespace rbla::analysis
