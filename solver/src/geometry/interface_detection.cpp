#include "geometry/interface_detection.hpp"

#include "geometry/joints_through_blocks.hpp"
#include "geometry/polygon2d.hpp"
#include "geometry/polyhedron.hpp"
#include "geometry/sweep.hpp"
#include "model/angles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <tuple>

namespace rbla::geometry {

using model::Vec3;

void local_frame(const Vec3& normal, Vec3& tangent1, Vec3& tangent2) {
  const Vec3 a = normal.cwiseAbs();
  Vec3 axis = Vec3::UnitX();
  if (a.y() < a.x() && a.y() <= a.z()) axis = Vec3::UnitY();
  else if (a.z() < a.x() && a.z() < a.y()) axis = Vec3::UnitZ();
  tangent1 = (axis - axis.dot(normal) * normal).normalized();
  tangent2 = normal.cross(tangent1);
}

double DetectionTolerances::distance(double size_a, double size_b) const {
  return per_joint ? joint_fraction * std::min(size_a, size_b) : fixed_distance;
}

PatchLimits DetectionTolerances::patch_limits() const {
  // Faces split by an export lie in one plane up to CAD noise, or crease along a diagonal by a
  // warp of a fraction of the joint tolerance; real facets of a curve meet at larger angles
  // (merging a 3.7 cm facet into its 9.5 degree neighbour moved a contact by 4 cm in the
  // 30000-block church). Hence a quarter of the angle and a third of the distance tolerance.
  PatchLimits limits;
  limits.angle_degrees = 0.25 * angle_degrees;
  limits.flatness_fraction = joint_fraction / 3.0;
  limits.flatness_fixed = per_joint ? -1.0 : fixed_distance / 3.0;
  limits.triangle_pair_angle_degrees = angle_degrees;
  limits.triangle_pair_flatness_fraction = joint_fraction;
  limits.triangle_pair_flatness_fixed = per_joint ? -1.0 : fixed_distance;
  return limits;
}

/// A joint's tolerance (3 % of the faces' diameter) allows for tilt and warp: a tilted face departs
/// from its neighbour's plane in proportion to its size. Faces that come nowhere near each other
/// are no joint however they are tilted: a drawn mortar layer or modelling slack is a few
/// millimetres to a couple of centimetres whatever the faces' size; more is a cavity or a movement
/// joint. So a joint's faces must also come within this many metres of each other somewhere (the
/// thickest mortar joint we expect drawn as a gap; its clearance). Without it two 8 x 3 m leaves of
/// a cavity wall 12 cm apart (tolerance 26 cm) were one wall, alpha 0.0545 against 0.0333 for each
/// leaf, without a warning, and so were leaves 5 cm apart at the foot and 11 cm at the top (the
/// review of the first version, which limited only gaps the same all over). Only with the
/// per-joint tolerance: a distance tolerance set in the model is kept; a joint_tolerance set in it
/// scales this limit too (at 0.1 instead of 0.03, 100 mm). Faces that overlap or cross anywhere
/// have no clearance (an overlap is the overlap check's).
constexpr double kClearanceLimit = 0.03;

DetectionTolerances DetectionTolerances::of(const model::Model& model) {
  DetectionTolerances t;
  const model::DetectionSettings& s = model.detection;
  t.per_joint = !s.distance_tolerance && !s.relative_tolerance;
  t.joint_fraction = s.joint_tolerance;
  t.fixed_distance = t.per_joint ? 0.0 : model.distance_tolerance();
  t.angle_degrees = s.angle_tolerance_degrees;
  t.clearance_limit = t.per_joint ? kClearanceLimit * s.joint_tolerance / model::DetectionSettings{}.joint_tolerance
                                  : std::numeric_limits<double>::infinity();
  return t;
}

model::Spread spread_of(std::vector<double>& values) {
  model::Spread s;
  s.count = values.size();
  if (values.empty()) return s;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  s.median = *middle;
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  s.min = *lo;
  s.max = *hi;
  return s;
}

Vec3 given_interface_normal(const model::Model& m, int a, int b, const Vec3& n, const Vec3& c, double tolerance) {
  const model::Block& block = m.blocks[a];
  const double cos_limit = std::cos(model::radians(10.0));
  double best = std::numeric_limits<double>::infinity();
  Vec3 normal = Vec3::Zero();
  for (const auto& face : block.faces) {
    const FaceGeometry g = face_geometry(block.vertices, face);
    const double distance = std::abs(g.normal.dot(c - g.centroid));
    if (std::abs(g.normal.dot(n)) < cos_limit || distance > tolerance || distance >= best) continue;
    Vec3 t1, t2;
    local_frame(g.normal, t1, t2);
    Polygon2 outline;
    for (const int i : face) outline.emplace_back(block.vertices[i].dot(t1), block.vertices[i].dot(t2));
    if (!contains(outline, Point2(c.dot(t1), c.dot(t2)), tolerance)) continue;
    best = distance;
    normal = g.normal.dot(n) > 0.0 ? n : Vec3(-n);
  }
  if (best < std::numeric_limits<double>::infinity()) return normal;
  return n.dot(m.blocks[b].centroid - block.centroid) < 0.0 ? Vec3(-n) : n;
}

namespace {

struct BlockPatches {
  std::vector<FacePatch> patches;
  Vec3 box_min = Vec3::Zero(), box_max = Vec3::Zero();
  double pad = 0.0;  // m: the largest near-miss range of its patches
};

bool boxes_overlap(const Vec3& a_min, const Vec3& a_max, const Vec3& b_min, const Vec3& b_max, double pad) {
  return (a_min.array() <= b_max.array() + pad).all() && (b_min.array() <= a_max.array() + pad).all();
}

std::vector<BlockPatches> all_patches(const model::Model& m, const DetectionTolerances& tol, std::size_t& merged) {
  std::vector<BlockPatches> out(m.blocks.size());
  const PatchLimits limits = tol.patch_limits();
  merged = 0;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    BlockPatches& bp = out[b];
    bp.patches = face_patches(m.blocks[b], limits);
    bp.box_min = bp.box_max = m.blocks[b].vertices[0];
    for (const Vec3& v : m.blocks[b].vertices) {
      bp.box_min = bp.box_min.cwiseMin(v);
      bp.box_max = bp.box_max.cwiseMax(v);
    }
    for (const FacePatch& p : bp.patches) {
      bp.pad = std::max(bp.pad, kNearMissFactor * tol.distance(p.size, p.size));
      merged += p.faces.size() - 1;
    }
  }
  return out;
}

/// Broad phase: block pairs (a < b, not two supports) whose boxes overlap once padded by the
/// smaller of their two pads (a joint's tolerance follows its smaller face, so a base slab's large
/// pad does not widen the search around every block on it), sorted.
std::vector<std::pair<int, int>> candidate_pairs(const model::Model& m, const std::vector<BlockPatches>& bp) {
  const int n = static_cast<int>(bp.size());
  const int axis = sweep_axis(m);
  const std::vector<int> order = sweep_order(n, [&](int i) { return bp[i].box_min[axis]; });
  std::vector<std::pair<int, int>> candidates;
  for (int i = 0; i < n; ++i) {
    const int a = order[i];
    for (int j = i + 1; j < n; ++j) {
      const int b = order[j];
      if (bp[b].box_min[axis] > bp[a].box_max[axis] + bp[a].pad) break;
      if (m.blocks[a].is_support() && m.blocks[b].is_support()) continue;
      if (!boxes_overlap(bp[a].box_min, bp[a].box_max, bp[b].box_min, bp[b].box_max, std::min(bp[a].pad, bp[b].pad))) {
        continue;
      }
      candidates.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(candidates.begin(), candidates.end());  // deterministic output order
  return candidates;
}

/// False when every corner of `p` is further than `range` from the plane of `q` on one side: the
/// overlap, inside p's outline, cannot come within range of q's plane either.
bool may_reach(const model::Block& block, const FacePatch& p, const FacePatch& q, double range) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const int v : p.outline) {
    const double d = q.normal.dot(block.vertices[v] - q.point);
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  const double margin = range + p.max_plane_deviation + q.max_plane_deviation;
  return lo <= margin && hi >= -margin;
}

/// One patch pair after its planes and projections have been compared.
struct PairGeometry {
  Vec3 normal;  // from a into b
  // The in-plane axes the outlines are projected on: local_frame of the normal oriented away from
  // the larger patch's block, so that the projections, and the snapping of intersect(), do not
  // depend on which block was listed first (`larger_first` tells which that was).
  Vec3 t1, t2;
  bool larger_first = true;  // pa is the larger patch (t1 x t2 = normal); else t1 x t2 = -normal
  double angle_degrees = 0.0;
  double tolerance = 0.0;
};

/// Height along `n` of the plane (normal, point) above the 2-D point (x, y) of the frame.
double plane_height(const FacePatch& patch, const PairGeometry& g, const Point2& p) {
  return (patch.normal.dot(patch.point) - patch.normal.dot(p.x() * g.t1 + p.y() * g.t2)) / patch.normal.dot(g.normal);
}

/// The block's thickness along n: the spread of its vertices' heights.
double extent_along(const model::Block& block, const Vec3& n) {
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (const Vec3& v : block.vertices) {
    low = std::min(low, v.dot(n));
    high = std::max(high, v.dot(n));
  }
  return high - low;
}

/// Two faces whose planes are within the tolerance may still face away from each other: the bottom
/// of one thin slab and the top of the slab above it, back to back across the first slab's
/// thickness. The faces of a joint face each other, up to a CAD overlap; one face lying behind the
/// other by more than this fraction of the thinner block's thickness is no joint.
constexpr double kBackToBackFraction = 0.5;

/// Whether a piece's clearance (the nearest its faces come, 0 where they overlap or cross) is too
/// wide for a joint. The limit holds up to round-off: 1.03 - 1.0 is 0.030000000000000027.
bool clearance_too_wide(const DetectionTolerances& tol, double clearance) {
  return clearance > tol.clearance_limit * (1.0 + 1e-9);
}

/// 2 area / perimeter: the width of a strip, the radius of a disc (a measure of how narrow a face is).
double width(const Polygon2& polygon) {
  double perimeter = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) perimeter += (polygon[(i + 1) % polygon.size()] - polygon[i]).norm();
  return perimeter > 0.0 ? 2.0 * std::abs(signed_area(polygon)) / perimeter : 0.0;
}

/// Outline vertices closer than this snap together when two faces are intersected, so that a
/// sliver left where two noisy edges nearly coincide vanishes: a quarter of the joint tolerance,
/// but at most kSnapWidthFraction of the narrower face's width. The tolerance follows the faces'
/// diameter, so on long faces a quarter of it filled a 45 mm recess along a 6 m wall (alpha 29 %
/// too high) and swallowed a 20 mm slab standing on its edge (the independent detection review).
constexpr double kSnapWidthFraction = 0.01;
double snap_distance(double tolerance, double narrower_face_width) {
  return std::min(0.25 * tolerance, kSnapWidthFraction * narrower_face_width);
}

/// A sliver where noisy edges of neighbouring joints cross, not a contact: a piece narrower than a
/// quarter of the tolerance that covers under 1 % of the smaller face (1 to 3 mm wide and 0.14 % of
/// the joint between diagonal voussoirs of a noisy vault, where they carried 17-24 kN and raised
/// alpha by 4-8 %; 0.4 % of the side of a 20 mm floor tile), or under 10 % of it and narrower than
/// 5 % of the narrower face's width too (between the split faces of a noisy dome). A narrow face's
/// own contact (a slab on its edge, a ridge) covers all of that face, and a bearing strip along a
/// long wall (4 cm, or tapering from 8 cm, along an 8 m wall 0.5 m thick; 8 % of its top; the
/// third review) is wider than 5 % of the wall's width: they stay.
bool is_sliver(const Polygon2& piece, double tolerance, double smaller_face_area, double narrower_face_width) {
  const double w = width(piece), share = std::abs(signed_area(piece)) / smaller_face_area;
  if (w >= 0.25 * tolerance) return false;
  return share < 0.01 || (share < 0.1 && w < 0.05 * narrower_face_width);
}

Polygon2 project(const model::Block& block, const FacePatch& patch, const PairGeometry& g) {
  Polygon2 polygon;
  polygon.reserve(patch.outline.size());
  for (const int i : patch.outline) polygon.emplace_back(block.vertices[i].dot(g.t1), block.vertices[i].dot(g.t2));
  return polygon;
}

Point2 area_centroid(const Polygon2& piece, double& area) {
  Point2 weighted = Point2::Zero();
  area = 0.0;
  for (std::size_t k = 1; k + 1 < piece.size(); ++k) {
    const Point2 e1 = piece[k] - piece[0], e2 = piece[k + 1] - piece[0];
    const double tri = 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
    weighted += tri * (piece[0] + piece[k] + piece[k + 1]) / 3.0;
    area += tri;
  }
  return area != 0.0 ? Point2(weighted / area) : piece[0];
}

model::ContactInterface make_interface(int a, int b, const FacePatch& pa, const FacePatch& pb, const PairGeometry& g,
                                       const Polygon2& piece, double friction) {
  model::ContactInterface contact;
  contact.block_a = a;
  contact.block_b = b;
  contact.normal = g.normal;
  contact.tangent1 = g.t1;
  contact.tangent2 = g.normal.cross(g.t1);  // right-handed with the normal whichever way t2 points
  contact.detected = true;
  contact.friction = friction;
  double area = 0.0;
  const Point2 c = area_centroid(piece, area);
  // One plane for the whole polygon (normal n), halfway between the fitted planes at its centroid.
  const double h = 0.5 * (plane_height(pa, g, c) + plane_height(pb, g, c));
  contact.polygon.reserve(piece.size());
  for (const Point2& p : piece) contact.polygon.push_back(h * g.normal + p.x() * g.t1 + p.y() * g.t2);
  // Counter-clockwise about the contact's normal, as the pieces are about t1 x t2.
  if (!g.larger_first) std::reverse(contact.polygon.begin(), contact.polygon.end());
  contact.area = std::abs(area);
  contact.centroid = h * g.normal + c.x() * g.t1 + c.y() * g.t2;
  return contact;
}

/// Everything detection collects while it runs.
struct Collector {
  std::vector<model::ContactInterface> interfaces;
  std::vector<model::NearMiss> near_misses;
  std::vector<double> gaps, angles, tolerances;
  std::vector<double> smallest_gaps;  ///< m, the nearest the two faces come over each joint
  double largest_gap_fraction = 0.0;
  model::WideGaps wide_gaps;
  model::JointsTouchingInPart touching_in_part;
  std::size_t face_pairs_tested = 0;
};

/// A joint accepted across a gap above this fraction of its tolerance is counted and the widest
/// reported (prepare_model warns): real CAD joints stay far below it (COMPAS assemblies at most
/// 13 %, a faceted generated dome 49.5 %), while a block drawn a few centimetres clear of a wall
/// is glued to it at 80 % and clamped there.
constexpr double kWideGapFraction = 0.5;

/// The farthest two faces are apart over a piece, either way, and the nearest (0 where they overlap
/// or cross): its gap and its clearance.
struct PieceGaps {
  double farthest = 0.0, clearance = 0.0;
  double ahead = 0.0, behind = 0.0;  ///< m, the widest gap and the deepest overlap
};
PieceGaps gaps_over(const Polygon2& piece, const FacePatch& pa, const FacePatch& pb, const PairGeometry& g) {
  PieceGaps out;
  double nearest = std::numeric_limits<double>::infinity();
  for (const Point2& p : piece) {
    const double gap = plane_height(pb, g, p) - plane_height(pa, g, p);  // > 0: b's face in front of a's
    out.farthest = std::max(out.farthest, std::abs(gap));
    nearest = std::min(nearest, gap);
    out.behind = std::max(out.behind, -gap);
    out.ahead = std::max(out.ahead, gap);
  }
  out.clearance = std::max(nearest, 0.0);
  return out;
}

/// The part of a piece where its faces are at most `limit` apart. The gap between two planes is
/// affine over the piece, so that part is the piece cut by one line: intersected with the
/// half-plane gap <= limit, drawn as a convex polygon around the piece's bounding box.
std::vector<Polygon2> within(const Polygon2& piece, const FacePatch& pa, const FacePatch& pb, const PairGeometry& g,
                             double limit, double snap, double min_area) {
  Point2 low = piece.front(), high = piece.front();
  for (const Point2& p : piece) low = low.cwiseMin(p), high = high.cwiseMax(p);
  const Point2 pad = (high - low) + Point2(1.0, 1.0) * 1e-3 * (high - low).norm();
  low -= pad;
  high += pad;
  const auto excess = [&](const Point2& p) { return plane_height(pb, g, p) - plane_height(pa, g, p) - limit; };
  const Polygon2 box{low, Point2(high.x(), low.y()), high, Point2(low.x(), high.y())};
  Polygon2 half;  // Sutherland-Hodgman against excess <= 0 (the box is convex)
  for (std::size_t i = 0; i < box.size(); ++i) {
    const Point2 &p = box[i], &q = box[(i + 1) % box.size()];
    const double ep = excess(p), eq = excess(q);
    if (ep <= 0.0) half.push_back(p);
    if ((ep < 0.0) != (eq < 0.0) && ep != eq) half.push_back(p + (q - p) * (ep / (ep - eq)));
  }
  if (half.size() < 3) return {};
  return intersect(piece, half, snap, min_area);
}

/// The two faces being compared.
struct FacePair {
  int a, b;
  const FacePatch &pa, &pb;
  const PairGeometry& g;
};

/// What decides how an accepted piece becomes contacts.
struct CutLimits {
  double bearing_band, snap, min_area;  ///< bearing_band: m, see kBearingBand
  double smaller_face_area, narrower_face_width;
};

/// How far beyond the nearest a tilted joint's faces still bear on each other, m: the default
/// clearance limit, whatever detection.joint_tolerance. The tolerance decides which faces form a
/// joint; scaled with it, the band let a block resting on its toe over a bed 0 to 50 mm bear on
/// its heel too, alpha rising 5-fold from joint_tolerance 0.03 to 0.05 (the third review).
constexpr double kBearingBand = kClearanceLimit;

/// Adds an accepted piece's contacts; false when nothing but slivers was left. A face tilted onto
/// its partner bears where the two are within kBearingBand of the nearest they come (the piece
/// cut along the line where the gap is clearance + kBearingBand), not all over: a leaf leaning onto
/// another, touching at its top edge and 12 cm clear at its foot, bore on its whole face (alpha
/// 0.0345 against 0.01377). Measured from the nearest, not from touching: a block on a drawn bed
/// 31 mm thick at its toe and 29 mm at its heel, cut at 30 mm, stood on its heel half (alpha 1e-4
/// against b/h = 0.5; the second review).
bool add_contacts(const model::Model& m, const FacePair& f, const Polygon2& piece, const PieceGaps& gaps,
                  const CutLimits& limits, Collector& out) {
  const double cut = gaps.clearance + limits.bearing_band;
  const bool cutting = gaps.ahead > cut;
  const std::vector<Polygon2> parts = cutting ? within(piece, f.pa, f.pb, f.g, cut, limits.snap, limits.min_area)
                                              : std::vector<Polygon2>{piece};
  double kept = 0.0;
  for (const Polygon2& part : parts) {
    if (cutting && is_sliver(part, f.g.tolerance, limits.smaller_face_area, limits.narrower_face_width)) continue;
    const PieceGaps part_gaps = cutting ? gaps_over(part, f.pa, f.pb, f.g) : gaps;
    out.interfaces.push_back(make_interface(f.a, f.b, f.pa, f.pb, f.g, part, m.default_friction));
    out.gaps.push_back(part_gaps.farthest);
    out.smallest_gaps.push_back(part_gaps.clearance);
    out.angles.push_back(f.g.angle_degrees);
    out.tolerances.push_back(f.g.tolerance);
    kept += std::abs(signed_area(part));
  }
  // Counted only when the cut took something off (a vertex a hair beyond the line snaps back).
  if (kept > 0.0 && kept < (1.0 - 1e-6) * std::abs(signed_area(piece)) && out.touching_in_part.joints++ == 0) {
    out.touching_in_part = {1, gaps.ahead, f.a, f.b, limits.bearing_band};
  }
  return kept > 0.0;
}

/// What comparing two patches gave: accepted pieces go straight to the collector.
struct PairOutcome {
  bool overlapping = false;  // some overlap came within the near-miss range
  bool accepted = false;
  model::NearMiss closest;   // the rejected piece closest to the tolerances
};

/// Compares patch pa of block a with patch pb of block b.
PairOutcome compare(const model::Model& m, int a, int b, const FacePatch& pa, const FacePatch& pb,
                    const DetectionTolerances& tol, Collector& out) {
  PairOutcome result;
  result.closest.distance = std::numeric_limits<double>::infinity();
  PairGeometry g;
  g.angle_degrees = model::degrees(std::acos(std::clamp(-pa.normal.dot(pb.normal), -1.0, 1.0)));
  if (g.angle_degrees > kNearMissFactor * tol.angle_degrees) return result;
  g.tolerance = tol.distance(pa.size, pb.size);
  const double range = kNearMissFactor * g.tolerance;
  if (!boxes_overlap(pa.box_min, pa.box_max, pb.box_min, pb.box_max, range)) return result;
  if (!may_reach(m.blocks[a], pa, pb, range) || !may_reach(m.blocks[b], pb, pa, range)) return result;
  ++out.face_pairs_tested;
  g.normal = (pa.normal - pb.normal).normalized();
  g.larger_first = !(pb.area > pa.area);
  local_frame(g.larger_first ? g.normal : Vec3(-g.normal), g.t1, g.t2);
  const double min_area = m.detection.min_area_fraction * std::min(pa.area, pb.area);
  // Vertices within a quarter of the joint tolerance snap together, so a sliver left where two
  // noisy edges nearly coincide vanishes rather than becoming a contact. Snapping keeps the
  // vertices of the polygon given first, so the larger face goes first whatever the blocks'
  // order: listed the other way round, an imperfect vault's contact points moved by up to 1.4 mm
  // and its alpha by 5e-5 (the search review).
  const Polygon2 qa = project(m.blocks[a], pa, g), qb = project(m.blocks[b], pb, g);
  const double narrower = std::min(width(qa), width(qb));
  const double snap = snap_distance(g.tolerance, narrower);
  const std::vector<Polygon2> pieces = g.larger_first ? intersect(qa, qb, snap, min_area)
                                                      : intersect(qb, qa, snap, min_area);
  const double thinner = std::min(extent_along(m.blocks[a], g.normal), extent_along(m.blocks[b], g.normal));
  for (const Polygon2& piece : pieces) {
    if (is_sliver(piece, g.tolerance, std::min(pa.area, pb.area), narrower)) continue;
    const PieceGaps gaps = gaps_over(piece, pa, pb, g);
    const double distance = gaps.farthest, clearance = gaps.clearance;
    if (distance > range || gaps.behind > kBackToBackFraction * thinner) continue;
    result.overlapping = true;
    const bool too_wide = clearance_too_wide(tol, clearance);
    const bool fits = g.angle_degrees <= tol.angle_degrees && distance <= g.tolerance && !too_wide;
    const CutLimits limits{tol.per_joint ? kBearingBand : std::numeric_limits<double>::infinity(), snap, min_area,
                           std::min(pa.area, pb.area), narrower};
    if (fits && add_contacts(m, {a, b, pa, pb, g}, piece, gaps, limits, out)) {
      result.accepted = true;
      // A piece that fits but is all slivers once cut is a near miss, so that it is named.
    } else if (distance < result.closest.distance) {
      model::NearMiss& miss = result.closest;
      miss.block_a = a;
      miss.block_b = b;
      miss.face_a = pa.faces.front();
      miss.face_b = pb.faces.front();
      // The farther of the two limits from accepting the pair is reported: a joint tolerance raised
      // to the farthest distance does not close a clearance over the limit.
      const bool by_clearance = too_wide && clearance * g.tolerance >= distance * tol.clearance_limit;
      miss.distance = by_clearance ? clearance : distance;
      miss.angle_degrees = g.angle_degrees;
      miss.overlap_area = std::abs(signed_area(piece));
      miss.distance_tolerance = by_clearance ? tol.clearance_limit : g.tolerance;
    }
  }
  return result;
}

/// How far outside its tolerances a near miss is (1 = at the tolerance).
double excess(const model::NearMiss& miss, double angle_tolerance) {
  const double d = miss.distance_tolerance > 0.0 ? miss.distance / miss.distance_tolerance : 0.0;
  return std::max(d, angle_tolerance > 0.0 ? miss.angle_degrees / angle_tolerance : 0.0);
}

/// Compares two patches; when a merged patch does not fit, compares its faces one by one (a
/// face of a finely faceted curve merged with its neighbours may fit where the merged plane
/// does not). Records the closest rejected pair as a near miss when nothing was accepted.
void match_patches(const model::Model& m, int a, int b, const FacePatch& pa, const FacePatch& pb,
                   const DetectionTolerances& tol, Collector& out) {
  PairOutcome best = compare(m, a, b, pa, pb, tol, out);
  if (best.accepted) return;
  if (!pa.parts.empty() || !pb.parts.empty()) {
    const std::vector<FacePatch> only_a{pa}, only_b{pb};
    for (const FacePatch& qa : pa.parts.empty() ? only_a : pa.parts) {
      for (const FacePatch& qb : pb.parts.empty() ? only_b : pb.parts) {
        const PairOutcome part = compare(m, a, b, qa, qb, tol, out);
        best.accepted = best.accepted || part.accepted;
        if (part.overlapping && (!best.overlapping || excess(part.closest, tol.angle_degrees) <
                                                          excess(best.closest, tol.angle_degrees))) {
          best.closest = part.closest;
          best.overlapping = true;
        }
      }
    }
  }
  if (!best.accepted && best.overlapping && std::isfinite(best.closest.distance)) out.near_misses.push_back(best.closest);
}

/// A joint's faces are apart everywhere when the nearest they come is more than this fraction of the
/// farthest: a shim or a layer between parallel faces, give or take CAD noise.
constexpr double kApartFraction = 0.5;

/// Drops the joints through a third block (geometry/joints_through_blocks.hpp) with their gaps,
/// angles and tolerances, and records the first.
void drop_joints_through_blocks(const model::Model& m, const DetectionTolerances& tol, Collector& c,
                                model::JointsThroughBlocks& through) {
  // Only faces apart everywhere can be held apart by a block: a block that touches the base along
  // one edge and rests on a pinning stone at the other keeps its joint (the second review: dropping
  // it left the block "cannot stand").
  std::vector<bool> apart(c.interfaces.size());
  // Gaps of round-off size (a block drawn at 0.1 + 0.2 on supports at 0.3) are no gap at all.
  for (std::size_t k = 0; k < apart.size(); ++k) {
    apart[k] = c.smallest_gaps[k] > kApartFraction * c.gaps[k] && c.gaps[k] > 1e-3 * c.tolerances[k];
  }
  const std::vector<int> between = blocks_between(m, c.interfaces, apart, c.gaps, tol.angle_degrees);
  std::size_t kept = 0;
  for (std::size_t k = 0; k < between.size(); ++k) {
    if (between[k] >= 0) {
      if (through.joints++ == 0) through = {1, c.interfaces[k].block_a, c.interfaces[k].block_b, between[k]};
      continue;
    }
    if (kept != k) {  // a vector moved onto itself may be left empty
      c.interfaces[kept] = std::move(c.interfaces[k]);
      c.gaps[kept] = c.gaps[k];
      c.angles[kept] = c.angles[k];
      c.tolerances[kept] = c.tolerances[k];
      c.smallest_gaps[kept] = c.smallest_gaps[k];
    }
    ++kept;
  }
  c.interfaces.resize(kept);
  c.gaps.resize(kept);
  c.angles.resize(kept);
  c.tolerances.resize(kept);
  c.smallest_gaps.resize(kept);
}

/// The largest gap over its tolerance, and the joints accepted across a wide gap: more than
/// kWideGapFraction of the tolerance, or a clearance (the nearest the faces come) of more than
/// kWideGapFraction of its limit (15 mm at the defaults: a 25 mm gap beside a wall, a narrow
/// cavity, or a thick mortar joint drawn as a gap; the review of the clearance limit).
void tally_gaps(Collector& c, const DetectionTolerances& tol) {
  model::WideGaps& wide = c.wide_gaps;
  for (std::size_t k = 0; k < c.interfaces.size(); ++k) {
    const double gap = c.gaps[k], tolerance = c.tolerances[k], nearest = c.smallest_gaps[k];
    if (tolerance > 0.0) c.largest_gap_fraction = std::max(c.largest_gap_fraction, gap / tolerance);
    if (gap > kWideGapFraction * tolerance || nearest > kWideGapFraction * tol.clearance_limit) {
      ++wide.joints;
      if (gap > wide.widest) {
        wide = {wide.joints, gap, tolerance, nearest, c.interfaces[k].block_a, c.interfaces[k].block_b};
      }
    }
  }
}

model::DetectionSummary summarise(Collector& c, const DetectionTolerances& tol, std::size_t candidates,
                                  std::size_t merged) {
  model::DetectionSummary s;
  s.ran = true;
  s.per_joint = tol.per_joint;
  s.joint_tolerance = tol.joint_fraction;
  s.clearance_limit = tol.clearance_limit;
  s.fixed_distance = tol.fixed_distance;
  s.angle_tolerance_degrees = tol.angle_degrees;
  s.distance_tolerances = spread_of(c.tolerances);
  s.gaps = spread_of(c.gaps);
  s.angles = spread_of(c.angles);
  s.largest_gap_fraction = c.largest_gap_fraction;
  s.wide_gaps = c.wide_gaps;
  s.touching_in_part = c.touching_in_part;
  s.candidate_block_pairs = candidates;
  s.face_pairs_tested = c.face_pairs_tested;
  s.merged_faces = merged;
  s.interfaces_found = c.interfaces.size();
  s.near_misses_total = c.near_misses.size();
  return s;
}

}  // namespace

DetectionOutcome detect_interfaces(const model::Model& m, const std::vector<std::pair<int, int>>& skip_pairs) {
  const DetectionTolerances tol = DetectionTolerances::of(m);
  std::size_t merged = 0;
  const std::vector<BlockPatches> bp = all_patches(m, tol, merged);
  const std::vector<std::pair<int, int>> candidates = candidate_pairs(m, bp);
  const std::set<std::pair<int, int>> skip(skip_pairs.begin(), skip_pairs.end());
  // Merged patches' parts may be nearer opposite than the merged normal: keep the pre-test loose.
  const double cos_near = std::cos(model::radians(std::min(2.0 * kNearMissFactor * tol.angle_degrees, 90.0)));
  Collector collected;
  for (const auto& [a, b] : candidates) {
    if (skip.count({a, b})) continue;
    for (const FacePatch& pa : bp[a].patches) {
      for (const FacePatch& pb : bp[b].patches) {
        if (-pa.normal.dot(pb.normal) < cos_near) continue;
        match_patches(m, a, b, pa, pb, tol, collected);
      }
    }
  }
  model::JointsThroughBlocks through;
  drop_joints_through_blocks(m, tol, collected, through);
  tally_gaps(collected, tol);
  DetectionOutcome outcome;
  outcome.summary = summarise(collected, tol, candidates.size(), merged);
  outcome.summary.through_blocks = through;
  auto& misses = collected.near_misses;
  const std::size_t keep = std::min(misses.size(), static_cast<std::size_t>(std::max(m.detection.max_near_misses, 0)));
  auto closer = [&](const model::NearMiss& x, const model::NearMiss& y) {
    return std::make_tuple(excess(x, tol.angle_degrees), x.block_a, x.block_b, x.face_a, x.face_b) <
           std::make_tuple(excess(y, tol.angle_degrees), y.block_a, y.block_b, y.face_a, y.face_b);
  };
  std::partial_sort(misses.begin(), misses.begin() + static_cast<std::ptrdiff_t>(keep), misses.end(), closer);
  misses.resize(keep);
  outcome.near_misses = std::move(misses);
  outcome.interfaces = std::move(collected.interfaces);
  return outcome;
}

}  // namespace rbla::geometry
