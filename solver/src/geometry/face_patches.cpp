#include "geometry/face_patches.hpp"

#include "geometry/polyhedron.hpp"
#include "model/angles.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <unordered_map>

namespace rbla::geometry {

using Vec3 = Eigen::Vector3d;

void fit_plane(const std::vector<Vec3>& vertices, const std::vector<int>& polygon, Vec3& normal, Vec3& point) {
  Vec3 area = Vec3::Zero();
  point = Vec3::Zero();
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& p = vertices[polygon[i]];
    const Vec3& q = vertices[polygon[(i + 1) % n]];
    area += (p - vertices[polygon[0]]).cross(q - vertices[polygon[0]]);
    point += p;
  }
  point /= static_cast<double>(std::max<std::size_t>(n, 1));
  const double length = area.norm();
  normal = length > 0.0 ? Vec3(area / length) : Vec3::UnitZ();
}

double polygon_diameter(const std::vector<Vec3>& vertices, const std::vector<int>& polygon) {
  double diameter = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    for (std::size_t j = i + 1; j < polygon.size(); ++j) {
      diameter = std::max(diameter, (vertices[polygon[i]] - vertices[polygon[j]]).norm());
    }
  }
  return diameter;
}

namespace {

struct BlockFaces {
  std::vector<std::vector<int>> faces;  // welded vertex indices, consecutive repeats removed
  std::vector<Vec3> area_vectors;
  std::vector<std::vector<int>> neighbours;
};

BlockFaces welded_faces(const model::Block& block) {
  // The closure check's welding (polyhedron.hpp): its own pairwise rule, smallest index of the
  // pair, split a corner whose copies were rounded apart and sorted out of index order.
  const double diagonal = model::bounding_box_of(block.vertices).diagonal();
  const std::vector<int> rep = merge_close_vertices(block.vertices, kVertexWeldRelative * diagonal);
  BlockFaces out;
  const int num_faces = static_cast<int>(block.faces.size());
  out.faces.resize(num_faces);
  out.area_vectors.resize(num_faces);
  out.neighbours.resize(num_faces);
  std::unordered_map<std::uint64_t, std::vector<int>> edge_faces;
  for (int f = 0; f < num_faces; ++f) {
    std::vector<int>& face = out.faces[f];
    for (const int v : block.faces[f]) {
      if (face.empty() || face.back() != rep[v]) face.push_back(rep[v]);
    }
    while (face.size() > 1 && face.front() == face.back()) face.pop_back();
    out.area_vectors[f] = face_geometry(block.vertices, block.faces[f]).area_vector;
    for (std::size_t k = 0; k < face.size(); ++k) {
      const auto u = static_cast<std::uint64_t>(std::min(face[k], face[(k + 1) % face.size()]));
      const auto v = static_cast<std::uint64_t>(std::max(face[k], face[(k + 1) % face.size()]));
      if (u != v) edge_faces[(u << 32) | v].push_back(f);
    }
  }
  for (const auto& entry : edge_faces) {
    for (const int f : entry.second) {
      for (const int g : entry.second) {
        if (f != g) out.neighbours[f].push_back(g);
      }
    }
  }
  for (auto& list : out.neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return out;
}

/// The boundary of the union of `members` as one loop of vertex indices, or empty when it is not
/// a single simple loop. Interior edges appear once in each direction and cancel.
std::vector<int> boundary_loop(const BlockFaces& bf, const std::vector<int>& members) {
  std::unordered_map<std::uint64_t, int> directed;
  auto key = [](int u, int v) { return (static_cast<std::uint64_t>(u) << 32) | static_cast<std::uint32_t>(v); };
  for (const int f : members) {
    const auto& face = bf.faces[f];
    for (std::size_t k = 0; k < face.size(); ++k) ++directed[key(face[k], face[(k + 1) % face.size()])];
  }
  std::unordered_map<int, int> next;
  std::size_t boundary_edges = 0;
  for (const auto& [k, count] : directed) {
    const int u = static_cast<int>(k >> 32), v = static_cast<int>(k & 0xffffffffu);
    const auto reverse = directed.find(key(v, u));
    const int remaining = count - (reverse == directed.end() ? 0 : reverse->second);
    if (remaining <= 0) continue;
    if (remaining > 1 || next.count(u)) return {};  // an edge used twice, or a pinched vertex
    next[u] = v;
    ++boundary_edges;
  }
  if (next.empty()) return {};
  int start = next.begin()->first;
  for (const auto& entry : next) start = std::min(start, entry.first);  // deterministic start
  std::vector<int> loop{start};
  for (int v = next[start]; v != start; v = next[v]) {
    if (!next.count(v) || loop.size() > boundary_edges) return {};
    loop.push_back(v);
  }
  return loop.size() == boundary_edges ? loop : std::vector<int>{};
}

/// Largest distance of a vertex of `members` from the plane (normal, point), and the diagonal of
/// their bounding box.
void flatness(const model::Block& block, const BlockFaces& bf, const std::vector<int>& members, const Vec3& normal,
              const Vec3& point, double& deviation, double& diagonal) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  deviation = 0.0;
  for (const int f : members) {
    for (const int v : bf.faces[f]) {
      deviation = std::max(deviation, std::abs(normal.dot(block.vertices[v] - point)));
      lo = lo.cwiseMin(block.vertices[v]);
      hi = hi.cwiseMax(block.vertices[v]);
    }
  }
  diagonal = (hi - lo).norm();
}

double flatness_limit(double fixed, double fraction, double size) { return fixed >= 0.0 ? fixed : fraction * size; }

/// A patch while it grows: its plane (normal of the summed area vectors, through the mean of the
/// members' corners), a bound on its members' distance from that plane, and their extent.
struct Growth {
  std::vector<int> members;
  Vec3 area = Vec3::Zero();
  Vec3 sum = Vec3::Zero();  // of the members' corners
  int count = 0;
  double deviation = 0.0;   // >= the largest distance of a member corner from the plane
  double radius = 0.0;      // >= the largest distance of a member corner from the mean
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  Vec3 normal() const { return area.normalized(); }
  Vec3 mean() const { return sum / count; }
};

/// Adds `face` to the growth when its corners stay within the flatness limit; false otherwise.
/// Old corners are bounded without visiting them: moving the plane from (n, c) to (n', c') moves
/// a corner v's distance by at most |n' - n| |v - c| + |c' - c|. Only when that bound is too
/// loose are all corners measured again, so a cap split into thousands of triangles stays linear.
bool try_add(const model::Block& block, const BlockFaces& bf, Growth& g, int face, double fixed, double fraction) {
  const Vec3 area = g.area + bf.area_vectors[face];
  Vec3 sum = g.sum, lo = g.lo, hi = g.hi;
  int count = g.count;
  for (const int v : bf.faces[face]) {
    sum += block.vertices[v];
    ++count;
    lo = lo.cwiseMin(block.vertices[v]);
    hi = hi.cwiseMax(block.vertices[v]);
  }
  const Vec3 n = area.normalized(), c = sum / count;
  const double shift = (c - g.mean()).norm();
  double deviation = g.deviation + (n - g.normal()).norm() * g.radius + shift;
  double radius = g.radius + shift;
  for (const int v : bf.faces[face]) {
    deviation = std::max(deviation, std::abs(n.dot(block.vertices[v] - c)));
    radius = std::max(radius, (block.vertices[v] - c).norm());
  }
  const double limit = flatness_limit(fixed, fraction, (hi - lo).norm());
  if (deviation > limit) {  // measure every corner against the new plane
    deviation = radius = 0.0;
    auto measure = [&](int f) {
      for (const int v : bf.faces[f]) {
        deviation = std::max(deviation, std::abs(n.dot(block.vertices[v] - c)));
        radius = std::max(radius, (block.vertices[v] - c).norm());
      }
    };
    for (const int f : g.members) measure(f);
    measure(face);
    if (deviation > limit) return false;
  }
  g.members.push_back(face);
  g.area = area;
  g.sum = sum;
  g.count = count;
  g.lo = lo;
  g.hi = hi;
  g.deviation = deviation;
  g.radius = radius;
  return true;
}

/// Grows a patch from `seed` over neighbours that keep it flat (see face_patches()).
std::vector<int> grow(const model::Block& block, const BlockFaces& bf, int seed, const std::vector<int>& assigned,
                      const PatchLimits& limits) {
  const double cos_limit = std::cos(model::radians(limits.angle_degrees));
  const double cos_pair_limit = std::cos(model::radians(limits.triangle_pair_angle_degrees));
  Growth growth;
  growth.members = {seed};
  growth.area = bf.area_vectors[seed];
  for (const int v : bf.faces[seed]) {
    growth.sum += block.vertices[v];
    ++growth.count;
    growth.lo = growth.lo.cwiseMin(block.vertices[v]);
    growth.hi = growth.hi.cwiseMax(block.vertices[v]);
  }
  double diagonal = 0.0;
  flatness(block, bf, growth.members, growth.normal(), growth.mean(), growth.deviation, diagonal);
  for (const int v : bf.faces[seed]) growth.radius = std::max(growth.radius, (block.vertices[v] - growth.mean()).norm());
  // A triangle's partner in a split quad is its most nearly coplanar neighbouring triangle: only
  // that one gets the triangle-pair limits (a small facet next to a split face must not).
  int partner = -1;
  if (bf.faces[seed].size() == 3) {
    double best = -2.0;
    for (const int f : bf.neighbours[seed]) {
      if (assigned[f] >= 0 || bf.faces[f].size() != 3 || bf.area_vectors[f].norm() <= 0.0) continue;
      const double c = bf.area_vectors[f].normalized().dot(growth.normal());
      if (c > best) best = c, partner = f;
    }
  }
  std::vector<char> taken(bf.faces.size(), 0);
  taken[seed] = 1;
  for (std::size_t i = 0; i < growth.members.size(); ++i) {
    for (const int f : bf.neighbours[growth.members[i]]) {
      if (taken[f] || assigned[f] >= 0 || bf.area_vectors[f].norm() <= 0.0) continue;
      const bool pair = growth.members.size() == 1 && f == partner;
      if (bf.area_vectors[f].normalized().dot(growth.normal()) < (pair ? cos_pair_limit : cos_limit)) continue;
      const bool added =
          pair ? try_add(block, bf, growth, f, limits.triangle_pair_flatness_fixed, limits.triangle_pair_flatness_fraction)
               : try_add(block, bf, growth, f, limits.flatness_fixed, limits.flatness_fraction);
      if (added) taken[f] = 1;
    }
  }
  return growth.members;
}

FacePatch make_patch(const model::Block& block, const BlockFaces& bf, std::vector<int> members,
                     std::vector<int> outline) {
  FacePatch patch;
  patch.faces = std::move(members);
  patch.outline = std::move(outline);
  fit_plane(block.vertices, patch.outline, patch.normal, patch.point);
  for (const int f : patch.faces) patch.area += bf.area_vectors[f].norm();
  double diagonal = 0.0;
  flatness(block, bf, patch.faces, patch.normal, patch.point, patch.max_plane_deviation, diagonal);
  patch.box_min = patch.box_max = block.vertices[patch.outline[0]];
  for (const int v : patch.outline) {
    patch.box_min = patch.box_min.cwiseMin(block.vertices[v]);
    patch.box_max = patch.box_max.cwiseMax(block.vertices[v]);
  }
  patch.size = polygon_diameter(block.vertices, patch.outline);
  return patch;
}

}  // namespace

std::vector<FacePatch> face_patches(const model::Block& block, const PatchLimits& limits) {
  std::vector<FacePatch> patches;
  if (block.vertices.empty()) return patches;
  const BlockFaces bf = welded_faces(block);
  const int num_faces = static_cast<int>(bf.faces.size());
  std::vector<int> order(num_faces);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return bf.area_vectors[a].norm() > bf.area_vectors[b].norm(); });
  std::vector<int> assigned(num_faces, -1);
  for (const int seed : order) {
    if (assigned[seed] >= 0 || bf.faces[seed].size() < 3 || bf.area_vectors[seed].norm() <= 0.0) continue;
    std::vector<int> members = grow(block, bf, seed, assigned, limits);
    std::vector<int> outline = members.size() > 1 ? boundary_loop(bf, members) : bf.faces[seed];
    if (outline.size() < 3) {  // not one simple loop: the seed stays a patch of its own
      members = {seed};
      outline = bf.faces[seed];
    }
    for (const int f : members) assigned[f] = static_cast<int>(patches.size());
    std::vector<FacePatch> parts;
    if (members.size() > 1) {
      for (const int f : members) parts.push_back(make_patch(block, bf, {f}, bf.faces[f]));
    }
    patches.push_back(make_patch(block, bf, std::move(members), std::move(outline)));
    patches.back().parts = std::move(parts);
  }
  return patches;
}

}  // namespace rbla::geometry
