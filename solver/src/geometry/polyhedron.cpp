#include "geometry/polyhedron.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>
#include <utility>

namespace rbla::geometry {

namespace {
Vec3 corner_mean(const std::vector<Vec3>& vertices, const std::vector<int>& face) {
  Vec3 sum = Vec3::Zero();
  for (int index : face) sum += vertices[index];
  return sum / static_cast<double>(face.size());
}
}  // namespace

FaceGeometry face_geometry(const std::vector<Vec3>& vertices, const std::vector<int>& face) {
  FaceGeometry result;
  const std::size_t n = face.size();
  if (n < 3) return result;
  const Vec3 origin = corner_mean(vertices, face);
  Vec3 area2 = Vec3::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    area2 += (vertices[face[i]] - origin).cross(vertices[face[(i + 1) % n]] - origin);
  }
  result.area_vector = 0.5 * area2;
  result.area = result.area_vector.norm();
  if (result.area > 0.0) result.normal = result.area_vector / result.area;

  Vec3 weighted = Vec3::Zero();
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& b = vertices[face[i]];
    const Vec3& c = vertices[face[(i + 1) % n]];
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
    const std::size_t n = face.size();
    if (n < 3) continue;
    const Vec3 a = corner_mean(vertices, face) - reference;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 b = vertices[face[i]] - reference;
      const Vec3 c = vertices[face[(i + 1) % n]] - reference;
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

/// Classes of vertices under union; each class is represented by its smallest index.
class VertexClasses {
 public:
  explicit VertexClasses(int n) : parent_(static_cast<std::size_t>(n)) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int a) {
    while (parent_[a] != a) a = parent_[a] = parent_[parent_[a]];
    return a;
  }
  void unite(int a, int b) {
    a = find(a), b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<int> parent_;
};

using CellKey = std::array<std::int64_t, 3>;

/// The vertices of one grid cell: positions [begin, end) of the sorted list.
struct Cell {
  CellKey key;
  std::size_t begin, end;
};

}  // namespace

std::vector<int> merge_close_vertices(const std::vector<Vec3>& vertices, double tol) {
  const int n = static_cast<int>(vertices.size());
  VertexClasses classes(n);
  if (n == 0) return {};
  Vec3 lo = vertices[0], hi = vertices[0];
  for (const Vec3& v : vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  const double extent = (hi - lo).maxCoeff();
  double h = std::max(tol, 0.0) / 1.75;
  const bool cell_is_close = h > 0.0 && extent / h <= std::ldexp(1.0, 50);
  if (!cell_is_close) h = std::max(extent * std::ldexp(1.0, -50), std::numeric_limits<double>::min());
  std::vector<std::pair<CellKey, int>> sorted(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const Vec3 c = ((vertices[i] - lo) / h).array().floor();
    sorted[i] = {{static_cast<std::int64_t>(c.x()), static_cast<std::int64_t>(c.y()), static_cast<std::int64_t>(c.z())}, i};
  }
  std::sort(sorted.begin(), sorted.end());
  std::vector<Cell> cells;
  for (std::size_t k = 0; k < sorted.size(); ++k) {
    if (cells.empty() || cells.back().key != sorted[k].first) cells.push_back({sorted[k].first, k, k});
    cells.back().end = k + 1;
  }
  // Joins the classes of cells a and b (a == b: within one cell) where a pair is within tol.
  auto connect = [&](const Cell& a, const Cell& b) {
    for (std::size_t i = a.begin; i < a.end; ++i) {
      for (std::size_t j = (&a == &b ? i + 1 : b.begin); j < b.end; ++j) {
        if (cell_is_close && classes.find(sorted[i].second) == classes.find(sorted[j].second)) return;
        if ((vertices[sorted[i].second] - vertices[sorted[j].second]).norm() <= tol) {
          classes.unite(sorted[i].second, sorted[j].second);
          if (cell_is_close) return;
        }
      }
    }
  };
  for (const Cell& cell : cells) {
    if (cell_is_close) {
      for (std::size_t k = cell.begin + 1; k < cell.end; ++k) classes.unite(sorted[cell.begin].second, sorted[k].second);
    } else {
      connect(cell, cell);
    }
    for (std::int64_t dx = 0; dx <= 2; ++dx) {
      for (std::int64_t dy = dx == 0 ? 0 : -2; dy <= 2; ++dy) {
        for (std::int64_t dz = (dx == 0 && dy == 0) ? 1 : -2; dz <= 2; ++dz) {
          const CellKey key{cell.key[0] + dx, cell.key[1] + dy, cell.key[2] + dz};
          const auto other = std::lower_bound(cells.begin(), cells.end(), key,
                                              [](const Cell& c, const CellKey& k) { return c.key < k; });
          if (other != cells.end() && other->key == key) connect(cell, *other);
        }
      }
    }
  }
  std::vector<int> canonical(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) canonical[i] = classes.find(i);
  return canonical;
}

namespace {

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

/// T-junctions (a vertex of one face lying on an edge of another): each edge left unmatched is
/// split at the vertices lying on it, so that its pieces can meet the edges through that vertex.
/// Only unmatched edges need it (a matched pair would be split alike on both sides), and only at
/// ends of unmatched edges (the pieces' partners are unmatched too), found by a sort along the
/// edge's longest axis: O((E + U) log U) for E edges and U unmatched ones, where testing every
/// edge against every vertex was O(E V).
std::vector<std::vector<int>> split_at_t_junctions(const std::vector<Vec3>& vertices,
                                                   const std::vector<std::vector<int>>& loops,
                                                   const std::map<Edge, int>& count, double tol) {
  auto times = [&](int u, int v) {
    const auto found = count.find({u, v});
    return found == count.end() ? 0 : found->second;
  };
  std::vector<int> ends;
  for (const auto& [edge, n] : count) {
    if (times(edge.second, edge.first) != n) ends.insert(ends.end(), {edge.first, edge.second});
  }
  std::sort(ends.begin(), ends.end());
  ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
  std::array<std::vector<int>, 3> by_axis;
  for (int a = 0; a < 3; ++a) {
    by_axis[a] = ends;
    std::sort(by_axis[a].begin(), by_axis[a].end(), [&](int p, int q) { return vertices[p][a] < vertices[q][a]; });
  }
  std::vector<std::vector<int>> split;
  split.reserve(loops.size());
  for (const auto& loop : loops) {
    std::vector<int> refined;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int u = loop[i];
      const int v = loop[(i + 1) % loop.size()];
      refined.push_back(u);
      const Vec3 p = vertices[u];
      const Vec3 d = vertices[v] - p;
      const double length2 = d.squaredNorm();
      if (length2 <= tol * tol || times(v, u) == times(u, v)) continue;
      int axis = 0;
      d.cwiseAbs().maxCoeff(&axis);
      const auto& sorted = by_axis[axis];
      const double from = std::min(p[axis], vertices[v][axis]) - tol, to = std::max(p[axis], vertices[v][axis]) + tol;
      auto it = std::lower_bound(sorted.begin(), sorted.end(), from,
                                 [&](int w, double x) { return vertices[w][axis] < x; });
      std::vector<std::pair<double, int>> on_edge;
      for (; it != sorted.end() && vertices[*it][axis] <= to; ++it) {
        const int w = *it;
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
  return split;
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
  const std::map<Edge, int> count = count_directed_edges(merged);
  ClosureCheck check = judge(count);
  if (check.closed && check.consistent) return check;
  std::vector<std::vector<int>> split = split_at_t_junctions(vertices, merged, count, tol);
  ClosureCheck refined_check = judge(count_directed_edges(split));
  refined_check.needed_t_junction_split = refined_check.closed && refined_check.consistent;
  if (!(refined_check.closed && refined_check.consistent)) return check;  // report the plain failure
  return refined_check;
}

}  // namespace rbla::geometry
