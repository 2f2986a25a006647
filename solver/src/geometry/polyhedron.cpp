#include "geometry/polyhedron.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>
#include <utility>

namespace rbla::geometry {

FaceGeometry face_geometry(const std::vector<Vec3>& vertices, const std::vector<int>& face) {
  FaceGeometry result;
  const std::size_t n = face.size();
  if (n < 3) return result;
  const Vec3& origin = vertices[face[0]];
  Vec3 area2 = Vec3::Zero();
  for (std::size_t i = 1; i + 1 < n; ++i) {
    area2 += (vertices[face[i]] - origin).cross(vertices[face[i + 1]] - origin);
  }
  result.area_vector = 0.5 * area2;
  result.area = result.area_vector.norm();
  if (result.area > 0.0) result.normal = result.area_vector / result.area;

  Vec3 weighted = Vec3::Zero();
  double total = 0.0;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const Vec3& b = vertices[face[i]];
    const Vec3& c = vertices[face[i + 1]];
    const double signed_area = 0.5 * (b - origin).cross(c - origin).dot(result.normal);
    weighted += signed_area * (origin + b + c) / 3.0;
    total += signed_area;
  }
  if (total != 0.0) {
    result.centroid = weighted / total;
  } else {
    result.centroid = Vec3::Zero();
    for (int index : face) result.centroid += vertices[index];
    result.centroid /= static_cast<double>(n);
  }
  for (int index : face) {
    result.max_plane_deviation = std::max(
        result.max_plane_deviation, std::abs(result.normal.dot(vertices[index] - result.centroid)));
  }
  return result;
}

MassProperties mass_properties(const std::vector<Vec3>& vertices, const FaceList& faces) {
  MassProperties result;
  if (vertices.empty()) return result;
  Vec3 lo = vertices[0], hi = vertices[0];
  for (const Vec3& v : vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Vec3 reference = 0.5 * (lo + hi);
  double volume6 = 0.0;
  Vec3 moment24 = Vec3::Zero();  // sum of 6 V_t * 4 * (centroid_t - r)
  for (const auto& face : faces) {
    if (face.size() < 3) continue;
    const Vec3 a = vertices[face[0]] - reference;
    for (std::size_t i = 1; i + 1 < face.size(); ++i) {
      const Vec3 b = vertices[face[i]] - reference;
      const Vec3 c = vertices[face[i + 1]] - reference;
      const double v6 = a.dot(b.cross(c));
      volume6 += v6;
      moment24 += v6 * (a + b + c);
    }
    result.surface_area += face_geometry(vertices, face).area;
  }
  result.volume = volume6 / 6.0;
  result.centroid = volume6 != 0.0 ? Vec3(reference + moment24 / (4.0 * volume6)) : reference;
  return result;
}

namespace {

/// Maps every vertex to the smallest index of a vertex within `tol` of it (sweep along x).
std::vector<int> merge_close_vertices(const std::vector<Vec3>& vertices, double tol) {
  const int n = static_cast<int>(vertices.size());
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return vertices[a].x() < vertices[b].x(); });
  std::vector<int> canonical(n);
  std::iota(canonical.begin(), canonical.end(), 0);
  for (int i = 0; i < n; ++i) {
    const int a = order[i];
    for (int j = i + 1; j < n && vertices[order[j]].x() - vertices[a].x() <= tol; ++j) {
      const int b = order[j];
      if ((vertices[a] - vertices[b]).norm() <= tol) {
        const int root = std::min(canonical[a], canonical[b]);
        canonical[a] = canonical[b] = root;
      }
    }
  }
  // Resolve chains so each vertex points at its class's representative.
  for (int i = 0; i < n; ++i) {
    int root = canonical[i];
    while (canonical[root] != root) root = canonical[root];
    canonical[i] = root;
  }
  return canonical;
}

using Edge = std::pair<int, int>;

std::map<Edge, int> count_directed_edges(const std::vector<std::vector<int>>& faces) {
  std::map<Edge, int> count;
  for (const auto& face : faces) {
    for (std::size_t i = 0; i < face.size(); ++i) {
      const int u = face[i];
      const int v = face[(i + 1) % face.size()];
      if (u != v) ++count[{u, v}];
    }
  }
  return count;
}

ClosureCheck judge(const std::map<Edge, int>& count) {
  ClosureCheck check;
  for (const auto& [edge, n] : count) {
    if (n > 1) {
      const auto reverse = count.find({edge.second, edge.first});
      const int m = reverse == count.end() ? 0 : reverse->second;
      if (m != n) {
        check.consistent = false;
        std::ostringstream out;
        out << "edge " << edge.first << "->" << edge.second << " is used " << n
            << " times in the same direction (faces oriented inconsistently)";
        check.detail = out.str();
        return check;
      }
    }
  }
  for (const auto& [edge, n] : count) {
    const auto reverse = count.find({edge.second, edge.first});
    const int m = reverse == count.end() ? 0 : reverse->second;
    if (m != n) {
      check.closed = false;
      std::ostringstream out;
      out << "edge " << edge.first << "->" << edge.second << " has no matching opposite edge";
      check.detail = out.str();
      return check;
    }
  }
  return check;
}

}  // namespace

ClosureCheck check_closure(const std::vector<Vec3>& vertices, const FaceList& faces, double tol) {
  const std::vector<int> canonical = merge_close_vertices(vertices, tol);
  std::vector<std::vector<int>> merged;
  merged.reserve(faces.size());
  for (const auto& face : faces) {
    std::vector<int> loop;
    for (int index : face) {
      const int c = canonical[index];
      if (loop.empty() || loop.back() != c) loop.push_back(c);
    }
    while (loop.size() > 1 && loop.front() == loop.back()) loop.pop_back();
    merged.push_back(std::move(loop));
  }
  ClosureCheck check = judge(count_directed_edges(merged));
  if (check.closed && check.consistent) return check;

  // T-junctions: split every edge at the (distinct) vertices lying on it, then judge again.
  std::vector<int> representatives;
  for (int i = 0; i < static_cast<int>(vertices.size()); ++i) {
    if (canonical[i] == i) representatives.push_back(i);
  }
  std::vector<std::vector<int>> split;
  split.reserve(merged.size());
  for (const auto& loop : merged) {
    std::vector<int> refined;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int u = loop[i];
      const int v = loop[(i + 1) % loop.size()];
      refined.push_back(u);
      const Vec3 p = vertices[u];
      const Vec3 d = vertices[v] - p;
      const double length2 = d.squaredNorm();
      if (length2 <= tol * tol) continue;
      std::vector<std::pair<double, int>> on_edge;
      for (int w : representatives) {
        if (w == u || w == v) continue;
        const double t = (vertices[w] - p).dot(d) / length2;
        if (t <= 0.0 || t >= 1.0) continue;
        if ((p + t * d - vertices[w]).norm() <= tol) on_edge.emplace_back(t, w);
      }
      std::sort(on_edge.begin(), on_edge.end());
      for (const auto& [t, w] : on_edge) refined.push_back(w);
    }
    split.push_back(std::move(refined));
  }
  ClosureCheck refined_check = judge(count_directed_edges(split));
  refined_check.needed_t_junction_split = refined_check.closed && refined_check.consistent;
  if (!(refined_check.closed && refined_check.consistent)) return check;  // report the plain failure
  return refined_check;
}

}  // namespace rbla::geometry
