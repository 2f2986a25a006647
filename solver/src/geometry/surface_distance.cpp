#include "geometry/surface_distance.hpp"

#include "geometry/polyhedron.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rbla::geometry {

namespace {

using model::Vec3;

double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

/// Crossing-number test of p's projection against the face polygon, in the face's plane.
bool projects_inside(const std::vector<Vec3>& vertices, const std::vector<int>& face, const Vec3& normal, const Vec3& p) {
  const Vec3 u = normal.unitOrthogonal(), v = normal.cross(u);
  const double px = p.dot(u), py = p.dot(v);
  bool inside = false;
  for (std::size_t i = 0, j = face.size() - 1; i < face.size(); j = i++) {
    const double xi = vertices[face[i]].dot(u), yi = vertices[face[i]].dot(v);
    const double xj = vertices[face[j]].dot(u), yj = vertices[face[j]].dot(v);
    if ((yi > py) != (yj > py) && px < xj + (py - yj) * (xi - xj) / (yi - yj)) inside = !inside;
  }
  return inside;
}

}  // namespace

double distance_to_surface(const model::Block& block, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& face : block.faces) {
    const FaceGeometry g = face_geometry(block.vertices, face);
    if (projects_inside(block.vertices, face, g.normal, p)) best = std::min(best, std::abs((p - g.centroid).dot(g.normal)));
    for (std::size_t i = 0; i < face.size(); ++i) {
      best = std::min(best, segment_distance(p, block.vertices[face[i]], block.vertices[face[(i + 1) % face.size()]]));
    }
  }
  return best;
}

}  // namespace rbla::geometry
