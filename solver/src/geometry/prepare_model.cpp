#include "geometry/prepare_model.hpp"

#include "geometry/face_patches.hpp"
#include "geometry/overlap.hpp"
#include "geometry/polyhedron.hpp"
#include "geometry/surface_distance.hpp"
#include "geometry/warped_faces.hpp"

#include <chrono>
#include <cmath>
#include <set>
#include <sstream>

namespace rbla::geometry {

using model::InputIssue;
using model::Vec3;

namespace {

/// The model's distance tolerance grows with its extent (1e-4 of its bounding box): one block
/// kilometres away, a survey marker in a georeferenced export, made it 0.4 m and silenced the
/// checks of every block's warped faces, overlaps and CAD centroids. The checks of a block use
/// at most this fraction of its own size (of the median block's, between blocks), which leaves
/// models up to about a hundred blocks across as they were.
constexpr double kBlockToleranceCap = 0.01;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string format(double value) {
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

/// Lengths in messages are given back in the user's unit, to 6 digits.
std::string length6(double metres, const model::Units& units) { return model::length_text(metres, units, 6); }

/// First pair of non-adjacent edges of the polygon `corners` (in order) that cross each other
/// properly, seen along `normal`: -1 in `first` when none. A pentagram or a bow tie crosses; edges
/// that only touch or overlap (T-junctions, repeated vertices from mesh exports) do not count.
/// O(n^2) in the polygon's corners.
void first_crossing(const std::vector<Vec3>& corners, const Vec3& normal, int& first, int& second) {
  first = second = -1;
  const int n = static_cast<int>(corners.size());
  if (n < 4) return;
  // 2-D coordinates in the polygon's plane.
  Vec3 u = normal.unitOrthogonal(), v = normal.cross(u);
  std::vector<Eigen::Vector2d> p(n);
  for (int i = 0; i < n; ++i) p[i] = Eigen::Vector2d(corners[i].dot(u), corners[i].dot(v));
  auto orient = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    const double d = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    // Relative to the edge lengths, so that nearly collinear corners count as collinear.
    const double scale = (b - a).norm() * (c - a).norm();
    return d > 1e-12 * scale ? 1 : d < -1e-12 * scale ? -1 : 0;
  };
  for (int i = 0; i < n; ++i) {
    const int i1 = (i + 1) % n;
    for (int j = i + 2; j < n; ++j) {
      const int j1 = (j + 1) % n;
      if (j1 == i) continue;  // adjacent through the closing edge
      const int o1 = orient(p[i], p[i1], p[j]), o2 = orient(p[i], p[i1], p[j1]);
      const int o3 = orient(p[j], p[j1], p[i]), o4 = orient(p[j], p[j1], p[i1]);
      if (o1 * o2 < 0 && o3 * o4 < 0) {
        first = i;
        second = j;
        return;
      }
    }
  }
}

/// What the checks of one block report to, and the sizes they are relative to.
struct BlockChecks {
  std::size_t index;
  std::string pointer;          // "/blocks/i"
  std::string name;             // "block 'id'"
  double diagonal;              // m, of the block's bounding box
  double model_tolerance;       // m: the model's distance tolerance, capped at this block's scale
  std::vector<InputIssue>& errors;
  std::vector<model::Warning>& warnings;
};

/// Every face has three distinct vertices, an area, no crossing edges; warped faces are collected.
bool faces_sound(const model::Block& block, const BlockChecks& c, std::vector<WarpedFace>& warped) {
  bool faces_ok = true;
  for (std::size_t f = 0; f < block.faces.size(); ++f) {
    const std::string face_pointer = c.pointer + "/faces/" + std::to_string(f);
    std::set<int> distinct(block.faces[f].begin(), block.faces[f].end());
    if (distinct.size() < 3) {
      c.errors.push_back({face_pointer, c.name + ": face " + std::to_string(f) + " has fewer than 3 distinct vertices"});
      faces_ok = false;
      continue;
    }
    const FaceGeometry face = face_geometry(block.vertices, block.faces[f]);
    if (face.area <= 1e-10 * c.diagonal * c.diagonal) {
      c.errors.push_back({face_pointer, c.name + ": face " + std::to_string(f) + " has zero area"});
      faces_ok = false;
      continue;
    }
    std::vector<Vec3> corners;
    for (const int k : block.faces[f]) corners.push_back(block.vertices[k]);
    int e1 = -1, e2 = -1;
    first_crossing(corners, face.normal, e1, e2);
    if (e1 >= 0) {
      c.errors.push_back({face_pointer, c.name + ": face " + std::to_string(f) + " is self-intersecting (its edges " +
                                            std::to_string(e1) + " and " + std::to_string(e2) + " cross)"});
      faces_ok = false;
      continue;
    }
    if (face.max_plane_deviation > std::max(c.model_tolerance, 1e-6 * c.diagonal)) {
      warped.push_back({static_cast<int>(c.index), static_cast<int>(f), face.max_plane_deviation,
                        polygon_diameter(block.vertices, block.faces[f])});
    }
  }
  return faces_ok;
}

/// The faces close a volume and are consistently oriented (T-junctions accepted, with a warning).
bool closed(const model::Block& block, const BlockChecks& c) {
  // Vertices closer than this are the same vertex; relative to the block so that a 1 mm wedge in
  // a 100 m model is still checked at its own scale.
  const double merge_tol = std::min(c.model_tolerance, kVertexWeldRelative * c.diagonal);
  const ClosureCheck closure = check_closure(block.vertices, block.faces, merge_tol);
  if (!closure.consistent) {
    c.errors.push_back({c.pointer + "/faces", c.name + " has inconsistently oriented faces: " + closure.detail});
    return false;
  }
  if (!closure.closed) {
    c.errors.push_back({c.pointer + "/faces", c.name + " is open (its faces do not close a volume): " + closure.detail});
    return false;
  }
  if (closure.needed_t_junction_split) {
    c.warnings.push_back({"t_junctions", c.name + " has vertices lying on edges of other faces (T-junctions); "
                                                  "accepted as closed",
                          c.pointer + "/faces"});
  }
  return true;
}

/// Sets the block's volume and centroid, unless the volume is zero or negative (inverted faces).
bool set_mass_properties(model::Block& block, const BlockChecks& c) {
  const MassProperties mass = mass_properties(block.vertices, block.faces);
  if (std::abs(mass.volume) <= 1e-9 * c.diagonal * c.diagonal * c.diagonal) {
    c.errors.push_back({c.pointer, c.name + " has zero volume (flat or collapsed)"});
    return false;
  }
  if (mass.volume < 0.0) {
    c.errors.push_back({c.pointer + "/faces", c.name + " is inverted: its faces are ordered clockwise seen from "
                                                       "outside (inward normals); reverse every face"});
    return false;
  }
  block.volume = mass.volume;
  block.centroid = mass.centroid;
  return true;
}

/// Warnings where the CAD's own volume or centroid disagrees with the computed ones.
void compare_with_cad(const model::Block& block, const BlockChecks& c, const model::Units& units) {
  if (block.cad_volume && std::abs(*block.cad_volume - block.volume) > kCadVolumeTolerance * block.volume) {
    const double l3 = std::pow(units.length_to_m, 3);
    c.warnings.push_back({"cad_volume_mismatch",
                          c.name + ": the CAD volume " + format(*block.cad_volume / l3) + " differs from the volume " +
                              format(block.volume / l3) + " computed from its faces; the computed one is used",
                          c.pointer + "/volume", std::abs(*block.cad_volume - block.volume) / block.volume});
  }
  if (block.cad_centroid &&
      (*block.cad_centroid - block.centroid).norm() > std::max(kCadCentroidTolerance * c.diagonal, c.model_tolerance)) {
    c.warnings.push_back({"cad_centroid_mismatch",
                          c.name + ": the CAD centroid is " +
                              length6((*block.cad_centroid - block.centroid).norm(), units) +
                              " from the centroid computed from its faces; the computed one is used",
                          c.pointer + "/centroid", (*block.cad_centroid - block.centroid).norm()});
  }
}

void prepare_block(model::Block& block, std::size_t index, double model_tolerance, const model::Units& units,
                   std::vector<InputIssue>& errors, std::vector<model::Warning>& warnings,
                   std::vector<WarpedFace>& warped) {
  const double diagonal = model::bounding_box_of(block.vertices).diagonal();
  const BlockChecks checks{index,    "/blocks/" + std::to_string(index),
                           "block '" + block.id + "'",
                           diagonal, std::min(model_tolerance, kBlockToleranceCap * diagonal),
                           errors,   warnings};
  if (checks.diagonal == 0.0) {
    errors.push_back({checks.pointer + "/vertices", checks.name + " is degenerate: all its vertices coincide"});
    return;
  }
  if (!faces_sound(block, checks, warped) || !closed(block, checks) || !set_mass_properties(block, checks)) return;
  compare_with_cad(block, checks, units);
}

/// Where a given interface is in the model file: the reader drops repeated interfaces, so its
/// position in the model's list may be smaller.
std::string interface_pointer(const model::ContactInterface& contact, std::size_t index) {
  return "/interfaces/" + std::to_string(contact.source_index >= 0 ? static_cast<std::size_t>(contact.source_index) : index);
}

void prepare_given_interface(model::ContactInterface& contact, std::size_t index, const model::Model& m,
                             double tolerance, std::vector<InputIssue>& errors) {
  const std::string pointer = interface_pointer(contact, index);
  std::vector<int> all(contact.polygon.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  const FaceGeometry face = face_geometry(contact.polygon, all);
  double size = 0.0;
  for (const Vec3& p : contact.polygon) size = std::max(size, (p - contact.polygon[0]).norm());
  if (face.area <= 1e-10 * size * size || size == 0.0) {
    errors.push_back({pointer + "/polygon", "interface '" + contact.id + "' has a polygon of zero area"});
    return;
  }
  int e1 = -1, e2 = -1;
  first_crossing(contact.polygon, face.normal, e1, e2);
  if (e1 >= 0) {
    errors.push_back({pointer + "/polygon", "interface '" + contact.id + "' has a self-intersecting polygon (its edges " +
                                                std::to_string(e1) + " and " + std::to_string(e2) + " cross)"});
    return;
  }
  if (face.max_plane_deviation > tolerance) {
    errors.push_back({pointer + "/polygon", "interface '" + contact.id + "' is not planar: a corner is " +
                                                length6(face.max_plane_deviation, m.units) +
                                                " from the polygon's plane"});
    return;
  }
  // The schema says the normal points from blocks[0] into blocks[1].
  contact.normal = given_interface_normal(m, contact.block_a, contact.block_b, face.normal, face.centroid, tolerance);
  local_frame(contact.normal, contact.tangent1, contact.tangent2);
  contact.area = face.area;
  contact.centroid = face.centroid;
}

/// A given interface must lie on a face of each of its two blocks: every corner, and its
/// centroid (which catches a polygon across a block whose corners lie on its edges), within the
/// distance tolerance of both surfaces. A contact elsewhere puts forces where no block is.
void check_given_interface_on_blocks(const model::ContactInterface& contact, std::size_t index, const model::Model& m,
                                     double tolerance, std::vector<InputIssue>& errors) {
  std::vector<Vec3> points = contact.polygon;
  points.push_back(contact.centroid);
  for (const int b : {contact.block_a, contact.block_b}) {
    double worst = 0.0;
    std::size_t worst_point = 0;
    for (std::size_t k = 0; k < points.size(); ++k) {
      const double d = distance_to_surface(m.blocks[b], points[k]);
      if (d > worst) {
        worst = d;
        worst_point = k;
      }
    }
    if (worst <= tolerance) continue;
    const std::string where = worst_point + 1 == points.size() ? "its centroid" : "its corner " + std::to_string(worst_point);
    errors.push_back({"/interfaces/" + std::to_string(index) + "/polygon",
                      "interface '" + contact.id + "' does not lie on block '" + m.blocks[b].id + "': " + where + " is " +
                          length6(worst, m.units) + " from the block's nearest face (the distance tolerance is " +
                          length6(tolerance, m.units) + ")"});
  }
}

std::string volume_text(double cubic_metres, const model::Units& units) {
  return format(cubic_metres / std::pow(units.length_to_m, 3)) + " " + units.length_name + "3";
}

/// The deepest overlap of blocks a and b taken for drawing slack at a joint between them (m): a
/// tenth of the thinner block's thickness, at most 10 mm.
double shallow_overlap_limit(const model::Block& a, const model::Block& b) {
  return std::min(kShallowOverlapCap, kShallowOverlapFraction * std::min(thinnest_width(a), thinnest_width(b)));
}

/// Blocks occupying the same space: an error above kOverlapVolumeFraction of the smaller block
/// unless the overlap is shallow (shallow_overlap_limit; its depth is an upper bound of how far
/// one block must move to free the other, convex or not); other overlaps deeper than the
/// tolerance are one warning (the first pair and a count).
void check_overlaps(const model::Model& m, double tolerance, std::vector<InputIssue>& errors,
                    std::vector<model::Warning>& warnings) {
  int small = 0;
  std::string first_small;
  for (const BlockOverlap& o : find_overlaps(m, tolerance)) {
    const model::Block& a = m.blocks[o.block_a];
    const model::Block& b = m.blocks[o.block_b];
    if (std::isnan(o.volume) && o.centroid_inside) {
      errors.push_back({"/blocks/" + std::to_string(o.block_b),
                        "blocks '" + a.id + "' and '" + b.id + "' overlap: the centroid of one lies inside the other "
                        "(their common volume was not computed: non-convex, " + std::to_string(a.faces.size()) + " and " +
                            std::to_string(b.faces.size()) + " faces); blocks may touch but not share volume"});
      continue;
    }
    if (std::isnan(o.volume)) {
      warnings.push_back({"blocks_overlap_not_measured",
                          "blocks '" + a.id + "' and '" + b.id + "' (non-convex, " + std::to_string(a.faces.size()) +
                              " and " + std::to_string(b.faces.size()) +
                              " faces) may overlap: their convex hulls do, and their common volume was not computed "
                              "(too many faces); check them",
                          "/blocks/" + std::to_string(o.block_b)});
      continue;
    }
    const double fraction = o.volume / std::min(a.volume, b.volume);
    const std::string what = "blocks '" + a.id + "' and '" + b.id + "' overlap: " + volume_text(o.volume, m.units) +
                             " in common (" + format(100.0 * fraction) + " % of the smaller" +
                             ", up to " + length6(o.depth, m.units) + " deep)";
    const double shallow = shallow_overlap_limit(a, b);
    if (fraction > kOverlapVolumeFraction && !(o.depth <= shallow)) {
      errors.push_back({"/blocks/" + std::to_string(o.block_b),
                        what + ", more than " + format(100.0 * kOverlapVolumeFraction) +
                            " % of the smaller and deeper than " + length6(shallow, m.units) +
                            " (drawing slack at a joint: a tenth of the thinner block, at most 10 mm); "
                            "blocks may touch but not share volume (check for duplicated or misplaced blocks)"});
    } else if (small++ == 0) {
      first_small = what;
    }
  }
  if (small > 0) {
    warnings.push_back({"blocks_overlap",
                        first_small + (small > 1 ? " (and " + std::to_string(small - 1) + " more pairs)" : "") +
                            ": more than the distance tolerance (" + length6(tolerance, m.units) +
                            ") accepts at a joint but under " + format(100.0 * kOverlapVolumeFraction) +
                            " % of a block or no deeper than a tenth of the thinner block, accepted as a CAD "
                            "imperfection; a contact across it may be missed",
                        ""});
  }
}

/// A distance tolerance as large as the model merges everything (the schema caps the relative
/// one at 0.1 of the diagonal; the absolute one has no cap there): refuse it rather than answer.
void check_distance_tolerance(const model::Model& m) {
  if (m.detection.distance_tolerance && *m.detection.distance_tolerance > 0.1 * m.bounding_box().diagonal()) {
    throw model::ModelError("/detection/distance_tolerance",
                            "is " + length6(*m.detection.distance_tolerance, m.units) +
                                ", more than a tenth of the model's size (" +
                                length6(m.bounding_box().diagonal(), m.units) + " across)");
  }
}

/// Loads given without a point act at the centroid, known only once the blocks are prepared.
void place_loads_without_point(model::Model& m) {
  for (auto* loads : {&m.dead_loads, &m.live_loads}) {
    for (model::PointLoad& load : *loads) {
      if (std::isnan(load.point.x())) load.point = m.blocks[load.block].centroid;
    }
  }
}

/// Interfaces the CAD gave: frames from their polygons, checked against their blocks' faces;
/// those between two supports are dropped with a warning.
void prepare_given_interfaces(model::Model& m, double tolerance, std::vector<InputIssue>& errors) {
  std::vector<model::ContactInterface> kept;
  for (std::size_t i = 0; i < m.interfaces.size(); ++i) {
    model::ContactInterface& contact = m.interfaces[i];
    prepare_given_interface(contact, i, m, tolerance, errors);
    if (m.blocks[contact.block_a].is_support() && m.blocks[contact.block_b].is_support()) {
      m.warnings.push_back({"support_interface_ignored",
                            "interface '" + contact.id + "' joins two supports; it carries no unknowns and is ignored",
                            interface_pointer(contact, i)});
      continue;
    }
    if (!contact.polygon.empty() && contact.area > 0.0) check_given_interface_on_blocks(contact, i, m, tolerance, errors);
    kept.push_back(contact);
  }
  if (!errors.empty()) throw model::ModelError(errors);
  m.interfaces = std::move(kept);
}

/// Joints accepted across a gap near their tolerance are analysed as touching: a block drawn a
/// little clear of a wall is held by it. Said once, with the widest.
void warn_about_wide_gaps(model::Model& m) {
  const model::WideGaps& w = m.detection_summary.wide_gaps;
  if (w.joints == 0) return;
  const std::string share = std::to_string(static_cast<int>(std::lround(100.0 * w.widest / w.tolerance)));
  m.warnings.push_back(
      {"joints_closed_across_gaps",
       std::to_string(w.joints) +
           (w.joints == 1 ? " detected joint was accepted across a wide gap"
                          : " detected joints were accepted across wide gaps") +
           " (above half the joint's tolerance, or faces more than half the clearance limit apart where they come "
           "nearest), the widest " + model::length_text(w.widest, m.units) + " between blocks '" + m.blocks[w.block_a].id + "' and '" +
           m.blocks[w.block_b].id + "' (" + share + " % of its tolerance, " + model::length_text(w.nearest, m.units) +
           " at the nearest): such joints are analysed as touching. A gap that wide may be a real opening (a "
           "cavity, a movement joint, a block drawn clear of a wall would be held by it); check them, or lower "
           "detection.joint_tolerance",
       "/detection/joint_tolerance", w.widest});
}

/// Joints dropped because a third block lies between their faces: said once, with the first.
void warn_about_joints_through_blocks(model::Model& m) {
  const model::JointsThroughBlocks& t = m.detection_summary.through_blocks;
  if (t.joints == 0) return;
  m.warnings.push_back(
      {"joints_through_blocks",
       (t.joints == 1 ? std::string("a joint was") : std::to_string(t.joints) + " joints were") +
           " not formed because a third block lies between the two faces, touching both (blocks '" +
           m.blocks[t.block_a].id + "' and '" + m.blocks[t.block_b].id + "' are held apart by '" +
           m.blocks[t.between].id + "'): the gap between them is within the joint tolerance, but it is filled",
       "/blocks/" + std::to_string(t.between)});
}

/// Joints cut to the part where their faces bear (within kBearingBand of the nearest they come,
/// geometry/interface_detection.cpp): said once, with the first.
void warn_about_joints_touching_in_part(model::Model& m) {
  const model::JointsTouchingInPart& t = m.detection_summary.touching_in_part;
  if (t.joints == 0) return;
  m.warnings.push_back(
      {"joints_touching_in_part",
       (t.joints == 1 ? std::string("a detected joint touches") : std::to_string(t.joints) + " detected joints touch") +
           " over part of the faces' overlap only, where they are within " + model::length_text(t.band, m.units) +
           " of the nearest they come; elsewhere they are further apart, up to " +
           model::length_text(t.farthest, m.units) + " between blocks '" + m.blocks[t.block_a].id + "' and '" +
           m.blocks[t.block_b].id + "' (a face tilted onto its partner): only that part is a contact",
       "/detection/joint_tolerance", t.farthest});
}

/// Interface detection over the block pairs the CAD gave no interface for; the interfaces found
/// are appended with ids I0, I1, ... that no given interface uses.
void add_detected_interfaces(model::Model& m, PrepareReport& report) {
  const auto detect_start = std::chrono::steady_clock::now();
  std::vector<std::pair<int, int>> covered;
  for (const auto& contact : m.interfaces) {
    covered.emplace_back(std::min(contact.block_a, contact.block_b), std::max(contact.block_a, contact.block_b));
  }
  DetectionOutcome outcome = detect_interfaces(m, covered);
  std::vector<model::ContactInterface>& found = outcome.interfaces;
  m.near_misses = std::move(outcome.near_misses);
  m.detection_summary = outcome.summary;
  report.detection = outcome.summary;
  std::set<std::string> used_ids;
  for (const auto& contact : m.interfaces) used_ids.insert(contact.id);
  std::size_t next = 0;
  for (auto& contact : found) {
    do {
      contact.id = "I" + std::to_string(next++);
    } while (used_ids.count(contact.id));
    m.interfaces.push_back(std::move(contact));
  }
  report.detect_seconds = seconds_since(detect_start);
  report.detection_ran = true;
  warn_about_wide_gaps(m);
  warn_about_joints_touching_in_part(m);
  warn_about_joints_through_blocks(m);
}

/// A free block that touches nothing can only fall; say so now rather than leave the user to
/// puzzle over an infeasible analysis.
void warn_isolated_blocks(model::Model& m) {
  std::vector<int> contacts_per_block(m.blocks.size(), 0);
  for (const auto& contact : m.interfaces) {
    ++contacts_per_block[contact.block_a];
    ++contacts_per_block[contact.block_b];
  }
  for (std::size_t i = 0; i < m.blocks.size(); ++i) {
    if (!m.blocks[i].is_support() && contacts_per_block[i] == 0) {
      m.warnings.push_back({"isolated_block", "block '" + m.blocks[i].id + "' touches no other block",
                            "/blocks/" + std::to_string(i)});
    }
  }
}

/// A model kilometres or millimetres across was probably given in the wrong length unit.
void warn_suspicious_units(model::Model& m) {
  const double diagonal = m.bounding_box().diagonal();
  if (diagonal > 1e4) {
    m.warnings.push_back({"suspicious_units", "the model is " + format(diagonal) +
                                                  " m across: check /units/length", "/units/length"});
  } else if (diagonal < 1e-2) {
    m.warnings.push_back({"suspicious_units", "the model is only " + format(diagonal) +
                                                  " m across: check /units/length", "/units/length"});
  }
}

/// The model's distance tolerance for checks between blocks: at most kBlockToleranceCap of the
/// median block's size (the median: a ground slab or a marker must not set it).
double block_scale_tolerance(const model::Model& m) {
  const double tolerance = m.distance_tolerance();
  if (m.blocks.empty()) return tolerance;
  return std::min(tolerance, kBlockToleranceCap * m.median_block_size());
}

}  // namespace

PrepareReport prepare_model(model::Model& m) {
  PrepareReport report;
  const auto start = std::chrono::steady_clock::now();
  const double tolerance = m.distance_tolerance();
  check_distance_tolerance(m);

  std::vector<InputIssue> errors;
  std::vector<WarpedFace> warped;
  for (std::size_t i = 0; i < m.blocks.size(); ++i) {
    prepare_block(m.blocks[i], i, tolerance, m.units, errors, m.warnings, warped);
  }
  if (!errors.empty()) throw model::ModelError(errors);
  check_overlaps(m, block_scale_tolerance(m), errors, m.warnings);
  if (!errors.empty()) throw model::ModelError(errors);
  warn_warped_faces(warped, m);
  place_loads_without_point(m);
  prepare_given_interfaces(m, tolerance, errors);
  report.geometry_seconds = seconds_since(start);

  const bool detect = m.detection.mode == model::DetectionMode::Merge ||
                      (m.detection.mode == model::DetectionMode::Auto && m.interfaces.empty());
  if (detect) add_detected_interfaces(m, report);
  warn_isolated_blocks(m);
  warn_suspicious_units(m);
  return report;
}

}  // namespace rbla::geometry
