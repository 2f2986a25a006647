#include "geometry/polygon2d.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

// Design notes
// ------------
// Interface faces of stacked/running-bond masonry share edges and vertices exactly, which is the
// worst case for the classic boundary-walking clippers: Weiler-Atherton and Greiner-Hormann
// (ACM TOG 17(2), 1998) need "perturb the degenerate vertex" tricks that change the answer for
// touching faces. We instead
//   * take the convex fast path (Sutherland & Hodgman, "Reentrant polygon clipping",
//     CACM 17(1), 1974) with a three-way in/on/out classification, so vertices on a clip line
//     are neither duplicated nor turned into spurious crossings; and
//   * otherwise build a conforming arrangement of both boundaries (every edge split at every
//     vertex within tol and at every crossing, with vertices snapped to a tol-separated pool,
//     in the spirit of snap rounding, Hobby 1999 / Guibas & Marimont 1998), then classify each
//     arrangement edge by which side lies inside both inputs -- the edge-labelling step of the
//     map-overlay algorithm of de Berg et al., "Computational Geometry: Algorithms and
//     Applications", 3rd ed., §2.3. Overlapping collinear edges become the *same* arrangement
//     edge, so "same direction -> keep once, opposite direction -> drop" falls out of net
//     direction counts instead of special cases.

namespace rbla::geometry {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

double cross(const Point2& u, const Point2& v) { return u.x() * v.y() - u.y() * v.x(); }

// Twice the signed area of triangle abc; > 0 when c is left of a->b.
double orient(const Point2& a, const Point2& b, const Point2& c) { return cross(b - a, c - a); }

double point_segment_distance(const Point2& p, const Point2& a, const Point2& b) {
  const Point2 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * d)).norm();
}

// Smallest altitude of triangle abc (2 * area / longest side): its "thickness".
double min_altitude(const Point2& a, const Point2& b, const Point2& c) {
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  return longest > 0.0 ? std::abs(orient(a, b, c)) / longest : 0.0;
}

bool strictly_opposite(double s, double t) { return (s > 0.0 && t < 0.0) || (s < 0.0 && t > 0.0); }

bool segments_within(const Point2& p1, const Point2& p2, const Point2& q1, const Point2& q2, double tol) {
  if (strictly_opposite(orient(p1, p2, q1), orient(p1, p2, q2)) &&
      strictly_opposite(orient(q1, q2, p1), orient(q1, q2, p2))) {
    return true;
  }
  return std::min({point_segment_distance(p1, q1, q2), point_segment_distance(p2, q1, q2),
                   point_segment_distance(q1, p1, p2), point_segment_distance(q2, p1, p2)}) <= tol;
}

// Winding-number crossing rule of D. Sunday, "Inclusion of a point in a polygon" (2001): only
// orientation tests, no divisions, and half-open y-intervals so a ray through a vertex counts once.
int winding_step(const Point2& a, const Point2& b, const Point2& p) {
  if (a.y() <= p.y()) {
    if (b.y() > p.y() && orient(a, b, p) > 0.0) return 1;
  } else if (b.y() <= p.y() && orient(a, b, p) < 0.0) {
    return -1;
  }
  return 0;
}

int winding_number(const Polygon2& poly, const Point2& p) {
  int w = 0;
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) w += winding_step(poly[i], poly[(i + 1) % n], p);
  return w;
}

// Raised to a few ulps of the coordinate magnitude so that tol = 0 still snaps rounding noise of
// computed crossings; relative, so results stay scale invariant (mm vs m).
double effective_tol(const Polygon2& a, const Polygon2& b, double tol) {
  double scale = 0.0;
  for (const auto* poly : {&a, &b})
    for (const Point2& p : *poly) scale = std::max(scale, p.cwiseAbs().maxCoeff());
  return std::max(tol, 64.0 * std::numeric_limits<double>::epsilon() * scale);
}

// Simplified and counter-clockwise, or empty when degenerate.
Polygon2 prepare(const Polygon2& poly, double tol) {
  Polygon2 s = simplify(poly, tol);
  if (s.size() < 3) return {};
  const double area = signed_area(s);
  if (area == 0.0) return {};
  if (area < 0.0) std::reverse(s.begin(), s.end());
  return s;
}

// For an already simplified CCW polygon. Left turns everywhere is not enough (a pentagram turns
// left at every vertex); the total turning must also be exactly one revolution.
bool is_convex_ccw(const Polygon2& p) {
  const std::size_t n = p.size();
  if (n < 3) return false;
  double turning = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 e0 = p[i] - p[(i + n - 1) % n];
    const Point2 e1 = p[(i + 1) % n] - p[i];
    const double c = cross(e0, e1);
    if (!(c > 0.0)) return false;
    turning += std::atan2(c, e0.dot(e1));
  }
  return turning < 1.5 * kTwoPi;
}

struct Box {
  double x0, y0, x1, y1;
};

Box bounding_box(const Polygon2& p) {
  Box b{p[0].x(), p[0].y(), p[0].x(), p[0].y()};
  for (const Point2& q : p) {
    b.x0 = std::min(b.x0, q.x());
    b.y0 = std::min(b.y0, q.y());
    b.x1 = std::max(b.x1, q.x());
    b.y1 = std::max(b.y1, q.y());
  }
  return b;
}

// Boxes that are only within tol can at most touch, which yields no area anyway.
bool boxes_overlap(const Box& a, const Box& b, double tol) {
  return a.x0 < b.x1 - tol && b.x0 < a.x1 - tol && a.y0 < b.y1 - tol && b.y0 < a.y1 - tol;
}

std::vector<Polygon2> finish(std::vector<Polygon2> loops, double tol, double min_area) {
  std::vector<Polygon2> out;
  for (Polygon2& loop : loops) {
    Polygon2 s = simplify(loop, tol);
    if (s.size() < 3) continue;
    const double area = signed_area(s);
    // CW loops would be holes; the intersection of two simply connected regions has none, so
    // they can only be snapping artefacts.
    if (area <= 0.0 || area <= min_area) continue;
    out.push_back(std::move(s));
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Convex fast path: Sutherland-Hodgman. Vertices within tol of the clip line are "on" and kept
// without generating an intersection, so a shared edge or vertex yields a degenerate (zero-area)
// polygon that simplify() collapses, rather than a sliver or a duplicated point.
Polygon2 clip_convex(const Polygon2& subject, const Polygon2& clip, double tol) {
  Polygon2 out = subject;
  Polygon2 in;
  std::vector<double> d;
  const std::size_t m = clip.size();
  for (std::size_t j = 0; j < m; ++j) {
    const Point2& e0 = clip[j];
    const Point2& e1 = clip[(j + 1) % m];
    const double len = (e1 - e0).norm();
    if (len == 0.0) continue;
    in.swap(out);
    out.clear();
    const std::size_t n = in.size();
    d.resize(n);
    for (std::size_t k = 0; k < n; ++k) d[k] = orient(e0, e1, in[k]) / len;
    auto side = [tol](double dist) { return dist > tol ? 1 : (dist < -tol ? -1 : 0); };
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t k1 = (k + 1) % n;
      const int sp = side(d[k]);
      const int sq = side(d[k1]);
      if (sp >= 0) out.push_back(in[k]);
      if (sp * sq < 0) {
        const double t = d[k] / (d[k] - d[k1]);
        out.push_back(in[k] + t * (in[k1] - in[k]));
      }
    }
    if (out.size() < 3) return {};
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// General path.

struct Edge {
  int u, v;
  int owner;  // 0 = A, 1 = B
};

// Vertices closer than tol are one vertex, so pool points are pairwise > tol apart; this is what
// makes the later "split at vertices within tol" step produce identical index pairs for edges
// that overlap collinearly, whichever polygon they came from. First come wins, and A's
// vertices are added first, so A's coordinates survive in the result.
class VertexPool {
 public:
  explicit VertexPool(double tol) : tol2_(tol * tol) {}
  int add(const Point2& p) {
    for (std::size_t i = 0; i < pts_.size(); ++i)
      if ((pts_[i] - p).squaredNorm() <= tol2_) return static_cast<int>(i);
    pts_.push_back(p);
    return static_cast<int>(pts_.size()) - 1;
  }
  const Point2& operator[](int i) const { return pts_[static_cast<std::size_t>(i)]; }
  int size() const { return static_cast<int>(pts_.size()); }

 private:
  double tol2_;
  std::vector<Point2> pts_;
};

// Splits edge e at the pool vertices in `cuts` (ordered along the edge) and appends the pieces.
void emit_split(const Edge& e, std::vector<std::pair<double, int>>& cuts, std::vector<Edge>& out) {
  std::sort(cuts.begin(), cuts.end());
  int prev = e.u;
  for (const auto& c : cuts) {
    if (c.second == prev || c.second == e.v) continue;
    out.push_back({prev, c.second, e.owner});
    prev = c.second;
  }
  if (prev != e.v) out.push_back({prev, e.v, e.owner});
}

// Splits every edge at every pool vertex within tol of its interior.
std::vector<Edge> split_at_vertices(const std::vector<Edge>& edges, const VertexPool& pool, double tol) {
  std::vector<Edge> out;
  out.reserve(edges.size() * 2);
  std::vector<std::pair<double, int>> cuts;
  for (const Edge& e : edges) {
    const Point2& a = pool[e.u];
    const Point2& b = pool[e.v];
    const Point2 d = b - a;
    const double len2 = d.squaredNorm();
    const double x0 = std::min(a.x(), b.x()) - tol, x1 = std::max(a.x(), b.x()) + tol;
    const double y0 = std::min(a.y(), b.y()) - tol, y1 = std::max(a.y(), b.y()) + tol;
    cuts.clear();
    for (int k = 0; k < pool.size(); ++k) {
      if (k == e.u || k == e.v) continue;
      const Point2& p = pool[k];
      if (p.x() < x0 || p.x() > x1 || p.y() < y0 || p.y() > y1) continue;
      const double t = (p - a).dot(d) / len2;
      if (!(t > 0.0 && t < 1.0)) continue;
      if ((p - (a + t * d)).norm() <= tol) cuts.emplace_back(t, k);
    }
    if (cuts.empty()) {
      out.push_back(e);
    } else {
      emit_split(e, cuts, out);
    }
  }
  return out;
}

// Finds proper crossings between A- and B-edges (after split_at_vertices every touching pair
// already shares a pool vertex, so what remains are transversal crossings), snaps each crossing
// into the pool and splits both edges there. Returns false when there was nothing to do.
bool split_at_crossings(std::vector<Edge>& edges, VertexPool& pool) {
  std::vector<std::vector<int>> forced(edges.size());
  bool found = false;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (edges[i].owner != 0) continue;
    for (std::size_t j = 0; j < edges.size(); ++j) {
      if (edges[j].owner != 1) continue;
      const Edge& ea = edges[i];
      const Edge& eb = edges[j];
      if (ea.u == eb.u || ea.u == eb.v || ea.v == eb.u || ea.v == eb.v) continue;
      const Point2 &p1 = pool[ea.u], &p2 = pool[ea.v], &q1 = pool[eb.u], &q2 = pool[eb.v];
      if (std::max(p1.x(), p2.x()) < std::min(q1.x(), q2.x()) ||
          std::max(q1.x(), q2.x()) < std::min(p1.x(), p2.x()) ||
          std::max(p1.y(), p2.y()) < std::min(q1.y(), q2.y()) ||
          std::max(q1.y(), q2.y()) < std::min(p1.y(), p2.y())) {
        continue;
      }
      const double o1 = orient(q1, q2, p1);
      const double o2 = orient(q1, q2, p2);
      if (!strictly_opposite(o1, o2)) continue;
      if (!strictly_opposite(orient(p1, p2, q1), orient(p1, p2, q2))) continue;
      const double t = o1 / (o1 - o2);
      const int k = pool.add(p1 + t * (p2 - p1));
      if (k != ea.u && k != ea.v) forced[i].push_back(k);
      if (k != eb.u && k != eb.v) forced[j].push_back(k);
      found = true;
    }
  }
  if (!found) return false;
  std::vector<Edge> out;
  out.reserve(edges.size() + 8);
  std::vector<std::pair<double, int>> cuts;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const Edge& e = edges[i];
    if (forced[i].empty()) {
      out.push_back(e);
      continue;
    }
    const Point2& a = pool[e.u];
    const Point2 d = pool[e.v] - a;
    cuts.clear();
    for (int k : forced[i]) cuts.emplace_back((pool[k] - a).dot(d) / d.squaredNorm(), k);
    emit_split(e, cuts, out);
  }
  edges.swap(out);
  return true;
}

int winding_of_owner(const std::vector<Edge>& edges, int owner, const VertexPool& pool, const Point2& p) {
  int w = 0;
  for (const Edge& e : edges)
    if (e.owner == owner) w += winding_step(pool[e.u], pool[e.v], p);
  return w;
}

struct HalfEdge {
  int from, to;
  double angle;
};

}  // namespace

// -----------------------------------------------------------------------------------------------

double signed_area(const Polygon2& polygon) {
  const std::size_t n = polygon.size();
  if (n < 3) return 0.0;
  // Relative to the first vertex: same value, less cancellation far from the origin.
  const Point2& o = polygon[0];
  double twice = 0.0;
  for (std::size_t i = 1; i + 1 < n; ++i) twice += orient(o, polygon[i], polygon[i + 1]);
  return 0.5 * twice;
}

Polygon2 simplify(const Polygon2& polygon, double tol) {
  Polygon2 pts;
  pts.reserve(polygon.size());
  for (const Point2& p : polygon)
    if (pts.empty() || (p - pts.back()).norm() > tol) pts.push_back(p);
  while (pts.size() > 1 && (pts.back() - pts.front()).norm() <= tol) pts.pop_back();
  const std::size_t n = pts.size();
  if (n < 3) return {};

  std::vector<std::size_t> prev(n), next(n);
  std::vector<char> alive(n, 1), spike(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  std::size_t count = n;
  bool changed = true;
  while (changed && count >= 3) {
    changed = false;
    for (std::size_t i = 0; i < n && count >= 3; ++i) {
      if (!alive[i]) continue;
      const std::size_t pi = prev[i], ni = next[i];
      const Point2 &a = pts[pi], &b = pts[i], &c = pts[ni];
      // A fold-back thinner than tol is a zero-area spike: remove whatever its length.
      const bool is_spike = (b - a).dot(c - b) < 0.0 && min_altitude(a, b, c) <= tol;
      bool removable = is_spike;
      if (!removable) {
        // Check every original vertex the shortcut a-c would replace, not just b, so that a long
        // run of almost collinear vertices cannot drift by more than tol in total.
        removable = true;
        for (std::size_t k = (pi + 1) % n; k != ni; k = (k + 1) % n) {
          if (!spike[k] && point_segment_distance(pts[k], a, c) > tol) {
            removable = false;
            break;
          }
        }
      }
      if (!removable) continue;
      alive[i] = 0;
      spike[i] = is_spike ? 1 : 0;
      next[pi] = ni;
      prev[ni] = pi;
      --count;
      changed = true;
    }
  }
  if (count < 3) return {};
  Polygon2 out;
  out.reserve(count);
  for (std::size_t i = 0; i < n; ++i)
    if (alive[i]) out.push_back(pts[i]);
  return out;
}

bool is_simple(const Polygon2& polygon, double tol) {
  const std::size_t n = polygon.size();
  if (n < 3 || signed_area(polygon) == 0.0) return false;
  for (std::size_t i = 0; i < n; ++i)
    if ((polygon[(i + 1) % n] - polygon[i]).norm() <= tol) return false;
  for (std::size_t i = 0; i < n; ++i) {
    const Point2& p1 = polygon[i];
    const Point2& p2 = polygon[(i + 1) % n];
    // Adjacent edge (p1,p2)-(p2,p3): they share p2 legitimately but must not fold back.
    const Point2& p3 = polygon[(i + 2) % n];
    if (point_segment_distance(p3, p1, p2) <= tol || point_segment_distance(p1, p2, p3) <= tol) return false;
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
      if (segments_within(p1, p2, polygon[j], polygon[(j + 1) % n], tol)) return false;
    }
  }
  return true;
}

bool contains(const Polygon2& polygon, const Point2& p, double tol) {
  const std::size_t n = polygon.size();
  if (n == 0) return false;
  for (std::size_t i = 0; i < n; ++i)
    if (point_segment_distance(p, polygon[i], polygon[(i + 1) % n]) <= tol) return true;
  return winding_number(polygon, p) != 0;
}

bool is_convex(const Polygon2& polygon, double tol) {
  Polygon2 s = simplify(polygon, tol);
  if (s.size() < 3) return false;
  if (signed_area(s) < 0.0) std::reverse(s.begin(), s.end());
  return is_convex_ccw(s);
}

namespace {

// pa, pb: prepared (simplified, CCW) inputs; t: effective tolerance.
/// Step 1: all vertices snapped into one pool, and the directed (CCW) boundary edges of both.
std::vector<Edge> boundary_edges(const Polygon2& pa, const Polygon2& pb, VertexPool& pool) {
  std::vector<Edge> edges;
  edges.reserve(2 * (pa.size() + pb.size()));
  for (int owner = 0; owner < 2; ++owner) {
    const Polygon2& p = owner == 0 ? pa : pb;
    std::vector<int> idx(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) idx[i] = pool.add(p[i]);
    for (std::size_t i = 0; i < p.size(); ++i) {
      const int u = idx[i], v = idx[(i + 1) % p.size()];
      if (u != v) edges.push_back({u, v, owner});
    }
  }
  return edges;
}

/// Step 2: a conforming arrangement. Splitting at a snapped crossing bends edges by up to tol,
/// which can (rarely) create a new crossing or vertex-on-edge contact, hence the short fixed point.
void make_conforming(std::vector<Edge>& edges, VertexPool& pool, double t) {
  constexpr int kMaxRounds = 8;
  for (int round = 0;; ++round) {
    edges = split_at_vertices(edges, pool, t);
    if (round == kMaxRounds || !split_at_crossings(edges, pool)) break;
  }
}

/// Step 3: coincident arrangement edges merged, with the net direction count of each input. For
/// a simple input the count is +1/-1 on its boundary (interior on the left/right of u->v) and 0
/// elsewhere; a zero-width spike cancels to 0, as it should.
std::map<std::pair<int, int>, std::pair<int, int>> net_direction_counts(const std::vector<Edge>& edges) {
  std::map<std::pair<int, int>, std::pair<int, int>> merged;
  for (const Edge& e : edges) {
    if (e.u == e.v) continue;
    const int s = e.u < e.v ? 1 : -1;
    auto& w = merged[{std::min(e.u, e.v), std::max(e.u, e.v)}];
    (e.owner == 0 ? w.first : w.second) += s;
  }
  return merged;
}

/// Step 4: the directions with the overlap on the left and the outside on the right. This yields
/// A-edges inside B, B-edges inside A, and shared same-direction edges once; shared
/// opposite-direction edges (faces that only touch) have an outside on both sides.
std::vector<HalfEdge> overlap_boundary(const std::map<std::pair<int, int>, std::pair<int, int>>& merged,
                                       const std::vector<Edge>& edges, const VertexPool& pool) {
  std::vector<HalfEdge> half;
  for (const auto& [key, w] : merged) {
    const auto [u, v] = key;
    bool in_left[2], in_right[2];
    const int counts[2] = {w.first, w.second};
    for (int owner = 0; owner < 2; ++owner) {
      if (counts[owner] != 0) {
        in_left[owner] = counts[owner] > 0;
        in_right[owner] = counts[owner] < 0;
      } else {
        // Not on this input's boundary, and all crossings are split, so the whole edge is on one
        // side of it: the midpoint decides.
        const Point2 mid = 0.5 * (pool[u] + pool[v]);
        in_left[owner] = in_right[owner] = winding_of_owner(edges, owner, pool, mid) != 0;
      }
    }
    const bool left = in_left[0] && in_left[1];
    const bool right = in_right[0] && in_right[1];
    if (left == right) continue;
    const int from = left ? u : v;
    const int to = left ? v : u;
    const Point2 d = pool[to] - pool[from];
    half.push_back({from, to, std::atan2(d.y(), d.x())});
  }
  return half;
}

/// Step 5: the half-edges chained into loops. Where several result edges leave one vertex
/// (components pinched at a point), the next edge is the first outgoing one clockwise from the
/// reversed incoming edge: the DCEL "next" rule (de Berg et al. §2.2), which traces one face and
/// so splits pinched components into separate loops instead of a figure-eight.
std::vector<Polygon2> chain_loops(const std::vector<HalfEdge>& half, const VertexPool& pool) {
  std::vector<std::vector<int>> outgoing(static_cast<std::size_t>(pool.size()));
  for (std::size_t h = 0; h < half.size(); ++h)
    outgoing[static_cast<std::size_t>(half[h].from)].push_back(static_cast<int>(h));
  auto next_of = [&](int h) {
    const HalfEdge& e = half[static_cast<std::size_t>(h)];
    const auto& cand = outgoing[static_cast<std::size_t>(e.to)];
    if (cand.size() == 1) return cand[0];
    const Point2 back = pool[e.from] - pool[e.to];
    const double ref = std::atan2(back.y(), back.x());
    int best = -1;
    double best_delta = std::numeric_limits<double>::infinity();
    for (int g : cand) {
      double delta = std::fmod(ref - half[static_cast<std::size_t>(g)].angle, kTwoPi);
      if (delta <= 0.0) delta += kTwoPi;
      if (delta < best_delta) {
        best_delta = delta;
        best = g;
      }
    }
    return best;
  };

  std::vector<char> used(half.size(), 0);
  std::vector<Polygon2> loops;
  for (std::size_t h0 = 0; h0 < half.size(); ++h0) {
    if (used[h0]) continue;
    Polygon2 loop;
    int h = static_cast<int>(h0);
    bool closed = false;
    while (h >= 0 && !used[static_cast<std::size_t>(h)]) {
      used[static_cast<std::size_t>(h)] = 1;
      loop.push_back(pool[half[static_cast<std::size_t>(h)].from]);
      h = next_of(h);
      if (h == static_cast<int>(h0)) {
        closed = true;
        break;
      }
    }
    // An open chain means the classification was inconsistent (only possible when snapping has
    // folded the arrangement); its area would be meaningless, so it is dropped.
    if (closed) loops.push_back(std::move(loop));
  }
  return loops;
}

std::vector<Polygon2> general_prepared(const Polygon2& pa, const Polygon2& pb, double t, double min_area) {
  VertexPool pool(t);
  std::vector<Edge> edges = boundary_edges(pa, pb, pool);
  make_conforming(edges, pool, t);
  const std::vector<HalfEdge> half = overlap_boundary(net_direction_counts(edges), edges, pool);
  if (half.empty()) return {};
  return finish(chain_loops(half, pool), t, min_area);
}

std::vector<Polygon2> convex_prepared(const Polygon2& pa, const Polygon2& pb, double t, double min_area) {
  Polygon2 clipped = clip_convex(pa, pb, t);
  if (clipped.empty()) return {};
  std::vector<Polygon2> loops;
  loops.push_back(std::move(clipped));
  return finish(std::move(loops), t, min_area);
}

enum class Path { kAuto, kConvex, kGeneral };

std::vector<Polygon2> intersect_impl(const Polygon2& a, const Polygon2& b, double tol, double min_area,
                                     Path path) {
  const double t = effective_tol(a, b, tol);
  const Polygon2 pa = prepare(a, t);
  const Polygon2 pb = prepare(b, t);
  if (pa.empty() || pb.empty()) return {};
  if (!boxes_overlap(bounding_box(pa), bounding_box(pb), t)) return {};
  if (path != Path::kGeneral && is_convex_ccw(pa) && is_convex_ccw(pb))
    return convex_prepared(pa, pb, t, min_area);
  return general_prepared(pa, pb, t, min_area);
}

}  // namespace

std::vector<Polygon2> intersect(const Polygon2& a, const Polygon2& b, double tol, double min_area) {
  return intersect_impl(a, b, tol, min_area, Path::kAuto);
}

std::vector<Polygon2> intersect_convex(const Polygon2& a, const Polygon2& b, double tol, double min_area) {
  return intersect_impl(a, b, tol, min_area, Path::kConvex);
}

std::vector<Polygon2> intersect_general(const Polygon2& a, const Polygon2& b, double tol, double min_area) {
  return intersect_impl(a, b, tol, min_area, Path::kGeneral);
}

}  // namespace rbla::geometry
