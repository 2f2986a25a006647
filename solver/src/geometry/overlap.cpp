#include "geometry/overlap.hpp"

#include "geometry/polyhedron.hpp"
#include "geometry/sweep.hpp"
#include "model/angles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace rbla::geometry {

namespace {

using model::Vec3;
using Polygon3 = std::vector<Vec3>;
/// A convex polyhedron as its faces, each counter-clockwise seen from outside.
using Convex = std::vector<Polygon3>;

struct Plane {
  Vec3 normal;    // outward
  double offset;  // inside: normal . x <= offset
};

struct Box {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());
  void add(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  bool overlaps(const Box& o, double margin) const {
    return ((min.array() + margin) < o.max.array()).all() && ((o.min.array() + margin) < max.array()).all();
  }
};

/// A tetrahedron of a block's signed decomposition: the indicator of the block is the sum of
/// sign times the indicator of each (winding numbers of the closed surface).
struct SignedTet {
  Convex faces;
  std::vector<Plane> planes;
  Box box;
  double sign = 1.0;
};

/// Tetrahedron pairs clipped at most for one pair of non-convex blocks, which bounds the exact
/// volume's cost to seconds (a clip costs microseconds). Blocks that only touch at a joint need
/// few pairs, since only tetrahedra whose boxes meet are clipped; two 4000-triangle blocks in one
/// place would need 16 M pairs, and then the centroid test decides instead.
constexpr std::size_t kMaxTetClips = 1000000;

/// What the overlap test needs of one block.
struct BlockShape {
  Box box;
  std::vector<Plane> planes;  // one per face: normal and offset through the face centroid
  bool convex = true;
  std::vector<SignedTet> tets;  // filled only for non-convex blocks, when first needed
};

double volume(const Convex& faces) {
  if (faces.empty()) return 0.0;
  const Vec3 r = faces.front().front();
  double six_v = 0.0;
  for (const Polygon3& f : faces) {
    for (std::size_t k = 1; k + 1 < f.size(); ++k) six_v += (f[0] - r).dot((f[k] - r).cross(f[k + 1] - r));
  }
  return six_v / 6.0;
}

/// The part of `body` with normal . x <= offset (Sutherland-Hodgman per face, plus the cap).
/// A plane that supports the body (every vertex within eps on one side) keeps it whole or
/// leaves nothing: a face lying in the plane must not come back a second time as the cap.
Convex clip(const Convex& body, const Plane& plane, double eps) {
  bool inside = true, outside = true;
  for (const Polygon3& face : body) {
    for (const Vec3& p : face) {
      const double d = plane.normal.dot(p) - plane.offset;
      inside = inside && d <= eps;
      outside = outside && d >= -eps;
    }
  }
  if (inside) return body;
  if (outside) return {};
  Convex out;
  Polygon3 cut;
  for (const Polygon3& face : body) {
    Polygon3 kept;
    for (std::size_t i = 0; i < face.size(); ++i) {
      const Vec3& a = face[i];
      const Vec3& b = face[(i + 1) % face.size()];
      const double da = plane.normal.dot(a) - plane.offset, db = plane.normal.dot(b) - plane.offset;
      if (da <= eps) kept.push_back(a);
      if (std::abs(da) <= eps) cut.push_back(a);
      if ((da < -eps && db > eps) || (da > eps && db < -eps)) {
        const Vec3 p = a + (b - a) * (da / (da - db));
        kept.push_back(p);
        cut.push_back(p);
      }
    }
    if (kept.size() >= 3) out.push_back(std::move(kept));
  }
  if (cut.size() >= 3) {
    // The cap: the cut points in counter-clockwise order seen along the outward normal.
    Vec3 centre = Vec3::Zero();
    for (const Vec3& p : cut) centre += p;
    centre /= static_cast<double>(cut.size());
    const Vec3 u = plane.normal.unitOrthogonal(), v = plane.normal.cross(u);
    std::sort(cut.begin(), cut.end(), [&](const Vec3& p, const Vec3& q) {
      return std::atan2((p - centre).dot(v), (p - centre).dot(u)) < std::atan2((q - centre).dot(v), (q - centre).dot(u));
    });
    Polygon3 cap;
    for (const Vec3& p : cut) {
      if (cap.empty() || (p - cap.back()).norm() > eps) cap.push_back(p);
    }
    if (cap.size() >= 3 && (cap.front() - cap.back()).norm() <= eps) cap.pop_back();
    if (cap.size() >= 3) out.push_back(std::move(cap));
  }
  return out;
}

double clipped_volume(Convex body, const std::vector<Plane>& planes, double eps) {
  for (const Plane& plane : planes) {
    body = clip(body, plane, eps);
    if (body.size() < 4) return 0.0;
  }
  return std::max(0.0, volume(body));
}

Convex faces_of(const model::Block& block) {
  Convex faces;
  for (const auto& face : block.faces) {
    Polygon3 polygon;
    for (const int k : face) polygon.push_back(block.vertices[k]);
    faces.push_back(std::move(polygon));
  }
  return faces;
}

BlockShape shape_of(const model::Block& block, double eps) {
  BlockShape s;
  for (const Vec3& v : block.vertices) s.box.add(v);
  for (const auto& face : block.faces) {
    const FaceGeometry g = face_geometry(block.vertices, face);
    s.planes.push_back({g.normal, g.normal.dot(g.centroid)});
  }
  for (const Plane& plane : s.planes) {
    for (const Vec3& v : block.vertices) s.convex = s.convex && plane.normal.dot(v) <= plane.offset + eps;
  }
  return s;
}

/// The signed tetrahedra (centroid, fan triangle) of a block; flat ones are left out.
std::vector<SignedTet> signed_tets(const model::Block& block) {
  std::vector<SignedTet> tets;
  const Vec3 r = block.centroid;
  for (const auto& face : block.faces) {
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      const Vec3 &a = block.vertices[face[0]], &b = block.vertices[face[k]], &c = block.vertices[face[k + 1]];
      const double six_v = (a - r).dot((b - r).cross(c - r));
      if (!(std::abs(six_v) > 1e-12 * block.volume)) continue;
      SignedTet t;
      t.sign = six_v > 0.0 ? 1.0 : -1.0;
      // Faces counter-clockwise seen from outside for the positively oriented (r, p, q, s).
      const Vec3 p = a, q = six_v > 0.0 ? b : c, s = six_v > 0.0 ? c : b;
      t.faces = {{r, q, p}, {r, p, s}, {p, q, s}, {r, s, q}};
      for (const Polygon3& f : t.faces) {
        const Vec3 n = (f[1] - f[0]).cross(f[2] - f[0]).normalized();
        t.planes.push_back({n, n.dot(f[0])});
      }
      for (const Vec3& v : {r, p, q, s}) t.box.add(v);
      tets.push_back(std::move(t));
    }
  }
  return tets;
}

/// Smallest overlap of the two vertex sets' projections over the face normals of both.
double projection_depth(const model::Block& a, const model::Block& b, const BlockShape& sa, const BlockShape& sb) {
  double depth = std::numeric_limits<double>::infinity();
  for (const auto* planes : {&sa.planes, &sb.planes}) {
    for (const Plane& plane : *planes) {
      double lo_a = std::numeric_limits<double>::infinity(), hi_a = -lo_a, lo_b = lo_a, hi_b = -lo_a;
      for (const Vec3& v : a.vertices) {
        lo_a = std::min(lo_a, plane.normal.dot(v));
        hi_a = std::max(hi_a, plane.normal.dot(v));
      }
      for (const Vec3& v : b.vertices) {
        lo_b = std::min(lo_b, plane.normal.dot(v));
        hi_b = std::max(hi_b, plane.normal.dot(v));
      }
      depth = std::min(depth, std::min(hi_a, hi_b) - std::max(lo_a, lo_b));
    }
  }
  return depth;
}

/// V(A n B), exact for planar faces (see find_overlaps); NaN when two non-convex blocks would
/// need more than kMaxTetClips clips (the signed sum cannot stop early).
double common_volume(const model::Block& a, const model::Block& b, BlockShape& sa, BlockShape& sb, double eps) {
  if (sa.convex && sb.convex) return clipped_volume(faces_of(a), sb.planes, eps);
  if (!sa.convex && sa.tets.empty()) sa.tets = signed_tets(a);
  if (!sb.convex && sb.tets.empty()) sb.tets = signed_tets(b);
  double total = 0.0;
  if (sa.convex || sb.convex) {
    const BlockShape& convex = sa.convex ? sa : sb;
    const BlockShape& other = sa.convex ? sb : sa;
    for (const SignedTet& t : other.tets) {
      if (t.box.overlaps(convex.box, 0.0)) total += t.sign * clipped_volume(t.faces, convex.planes, eps);
    }
    return std::max(0.0, total);
  }
  std::vector<std::pair<const SignedTet*, const SignedTet*>> pairs;
  for (const SignedTet& ta : sa.tets) {
    if (!ta.box.overlaps(sb.box, 0.0)) continue;
    for (const SignedTet& tb : sb.tets) {
      if (!ta.box.overlaps(tb.box, 0.0)) continue;
      if (pairs.size() == kMaxTetClips) return std::numeric_limits<double>::quiet_NaN();
      pairs.emplace_back(&ta, &tb);
    }
  }
  for (const auto& [ta, tb] : pairs) total += ta->sign * tb->sign * clipped_volume(ta->faces, tb->planes, eps);
  return std::max(0.0, total);
}

/// Winding number of the block's closed surface around p (1 inside, 0 outside): the solid
/// angles of its fan triangles (Van Oosterom & Strackee 1983) over 4 pi.
double winding_number(const model::Block& block, const Vec3& p) {
  double total = 0.0;
  for (const auto& face : block.faces) {
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      const Vec3 a = block.vertices[face[0]] - p, b = block.vertices[face[k]] - p, c = block.vertices[face[k + 1]] - p;
      const double la = a.norm(), lb = b.norm(), lc = c.norm();
      const double numerator = a.dot(b.cross(c));
      const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
      total += 2.0 * std::atan2(numerator, denominator);
    }
  }
  return total / (4.0 * model::kPi);
}

}  // namespace

std::vector<BlockOverlap> find_overlaps(const model::Model& m, double tolerance) {
  const int n = static_cast<int>(m.blocks.size());
  const double eps = 1e-12 * std::max(m.bounding_box().diagonal(), 1e-300);
  std::vector<BlockShape> shapes;
  shapes.reserve(m.blocks.size());
  // Faces of CAD blocks are planar to about the tolerance: a block is convex to a thousandth of it.
  for (const model::Block& block : m.blocks) shapes.push_back(shape_of(block, std::max(eps, 1e-3 * tolerance)));

  // Sweep and prune (geometry/sweep.hpp): boxes that overlap by more than the tolerance on every
  // axis.
  const int axis = sweep_axis(m);
  const std::vector<int> order = sweep_order(n, [&](int i) { return shapes[i].box.min[axis]; });
  std::vector<BlockOverlap> found;
  for (int i = 0; i < n; ++i) {
    const int a = order[i];
    for (int j = i + 1; j < n; ++j) {
      const int b = order[j];
      if (shapes[b].box.min[axis] + tolerance >= shapes[a].box.max[axis]) break;
      if (m.blocks[a].is_support() && m.blocks[b].is_support()) continue;
      if (!shapes[a].box.overlaps(shapes[b].box, tolerance)) continue;
      const double depth = projection_depth(m.blocks[a], m.blocks[b], shapes[a], shapes[b]);
      if (depth <= tolerance) continue;
      const double common = common_volume(m.blocks[a], m.blocks[b], shapes[a], shapes[b], eps);
      const double smaller = std::min(m.blocks[a].volume, m.blocks[b].volume);
      if (!std::isnan(common) && !(common > tolerance * std::cbrt(smaller * smaller))) continue;
      BlockOverlap overlap{std::min(a, b), std::max(a, b), common, depth, shapes[a].convex && shapes[b].convex};
      if (std::isnan(common)) {
        overlap.centroid_inside = winding_number(m.blocks[a], m.blocks[b].centroid) > 0.5 ||
                                  winding_number(m.blocks[b], m.blocks[a].centroid) > 0.5;
      }
      found.push_back(overlap);
    }
  }
  std::sort(found.begin(), found.end(), [](const BlockOverlap& x, const BlockOverlap& y) {
    return x.block_a < y.block_a || (x.block_a == y.block_a && x.block_b < y.block_b);
  });
  return found;
}

double thinnest_width(const model::Block& block) {
  double thinnest = std::numeric_limits<double>::infinity();
  for (const std::vector<int>& face : block.faces) {
    const Vec3 area = face_geometry(block.vertices, face).area_vector;
    if (!(area.norm() > 0.0)) continue;
    const Vec3 n = area.normalized();
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (const Vec3& v : block.vertices) {
      low = std::min(low, v.dot(n));
      high = std::max(high, v.dot(n));
    }
    thinnest = std::min(thinnest, high - low);
  }
  return thinnest;
}

}  // namespace rbla::geometry
