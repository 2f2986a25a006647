#include "analysis/initial_reaction.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

namespace rbla::analysis {
namespace {

using model::Vec3;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// One interface between the rigid body and the ground. The spring pressure at x is
// p(x) = g(x)ᵀ s with g(x) = [n; (x − o) × n] (n: unit normal from the support into the body,
// o: the body's reference point) and s the body's generalised displacement times the stiffness;
// the pressure pushes the body along n.
struct BaseFace {
  std::vector<Vec3> polygon;  // the whole interface
  std::vector<Vec3> contact;  // the part in compression (the whole polygon at first)
  Vec3 normal = Vec3::UnitZ();
  bool moving = false;
};

Vec6 g_of(const Vec3& x, const Vec3& n, const Vec3& o) {
  Vec6 g;
  g.head<3>() = n;
  g.tail<3>() = (x - o).cross(n);
  return g;
}

// Calls f(weight, point) for a quadrature over the polygon that is exact for polynomials of
// degree 2 (the edge midpoints of each triangle of a fan, weight area/3). Areas are signed along
// n, so a non-convex polygon given in order is still integrated exactly.
template <class F>
void integrate_quadratic(const std::vector<Vec3>& polygon, const Vec3& n, F&& f) {
  if (polygon.size() < 3) return;
  double sign = 0;
  for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
    sign += (polygon[k] - polygon[0]).cross(polygon[k + 1] - polygon[0]).dot(n);
  sign = sign < 0 ? -1.0 : 1.0;
  for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
    const Vec3 &a = polygon[0], &b = polygon[k], &c = polygon[k + 1];
    const double area = 0.5 * sign * (b - a).cross(c - a).dot(n);
    f(area / 3.0, 0.5 * (a + b));
    f(area / 3.0, 0.5 * (b + c));
    f(area / 3.0, 0.5 * (c + a));
  }
}

// The part of `polygon` where the affine pressure p = g(x)ᵀ s is ≥ 0 (Sutherland–Hodgman
// against one half-space; p is affine on the plane, so crossings are found exactly).
std::vector<Vec3> compressed_part(const std::vector<Vec3>& polygon, const Vec3& n, const Vec3& o, const Vec6& s) {
  std::vector<Vec3> out;
  const std::size_t count = polygon.size();
  for (std::size_t k = 0; k < count; ++k) {
    const Vec3& a = polygon[k];
    const Vec3& b = polygon[(k + 1) % count];
    const double pa = g_of(a, n, o).dot(s), pb = g_of(b, n, o).dot(s);
    if (pa >= 0) out.push_back(a);
    if ((pa >= 0) != (pb >= 0)) out.push_back(a + (pa / (pa - pb)) * (b - a));
  }
  return out;
}

double contact_area(const std::vector<Vec3>& polygon, const Vec3& n) {
  double area = 0;
  integrate_quadratic(polygon, n, [&](double w, const Vec3&) { area += w; });
  return area;
}

/// Groups of free blocks joined by free-free interfaces, with their members, support interfaces
/// and dead loads gathered once (a scene of many loose blocks has as many groups), each under the
/// index of its root block.
struct Groups {
  std::vector<int> root;  // per block (supports: themselves)
  std::vector<std::vector<int>> members, base_faces, dead_loads;
};

Groups group_free_blocks(const model::Model& m) {
  const std::size_t num_blocks = m.blocks.size();
  // Union-find with path halving.
  std::vector<int> parent(num_blocks);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int b) {
    while (parent[b] != b) b = parent[b] = parent[parent[b]];
    return b;
  };
  for (const auto& face : m.interfaces) {
    if (!m.blocks[face.block_a].is_support() && !m.blocks[face.block_b].is_support())
      parent[find(face.block_a)] = find(face.block_b);
  }
  Groups groups;
  groups.root.resize(num_blocks);
  for (std::size_t b = 0; b < num_blocks; ++b) groups.root[b] = find(static_cast<int>(b));
  groups.members.resize(num_blocks);
  groups.base_faces.resize(num_blocks);
  groups.dead_loads.resize(num_blocks);
  for (std::size_t b = 0; b < num_blocks; ++b)
    if (!m.blocks[b].is_support()) groups.members[groups.root[b]].push_back(static_cast<int>(b));
  for (std::size_t i = 0; i < m.interfaces.size(); ++i) {
    const auto& face = m.interfaces[i];
    const bool a_support = m.blocks[face.block_a].is_support();
    if (a_support != m.blocks[face.block_b].is_support())
      groups.base_faces[groups.root[a_support ? face.block_b : face.block_a]].push_back(static_cast<int>(i));
  }
  for (std::size_t i = 0; i < m.dead_loads.size(); ++i)
    groups.dead_loads[groups.root[m.dead_loads[i].block]].push_back(static_cast<int>(i));
  return groups;
}

/// A group's interfaces with the supports, normals from the support into the body; `base_area`
/// and `o`, the base's area centroid (which keeps K well scaled), are set from them.
std::vector<BaseFace> base_of(const model::Model& m, const std::vector<int>& base_faces, double& base_area, Vec3& o) {
  std::vector<BaseFace> base;
  base_area = 0;
  o = Vec3::Zero();
  for (int index : base_faces) {
    const auto& face = m.interfaces[index];
    const bool a_support = m.blocks[face.block_a].is_support();
    const int ground = a_support ? face.block_a : face.block_b;
    BaseFace f;
    f.polygon = face.polygon;
    f.contact = face.polygon;
    f.normal = a_support ? face.normal : Vec3(-face.normal);
    f.moving = m.blocks[ground].role == model::BlockRole::MovingSupport;
    base.push_back(std::move(f));
    base_area += face.area;
    o += face.area * face.centroid;
  }
  return base;
}

/// The dead loads of a group (self-weight and fixed loads) as a wrench about o.
Vec6 dead_wrench(const model::Model& m, const Groups& groups, int root, const Vec3& o) {
  Vec6 load = Vec6::Zero();
  auto add = [&](const Vec3& force, const Vec3& point, const Vec3& moment) {
    load.head<3>() += force;
    load.tail<3>() += (point - o).cross(force) + moment;
  };
  for (int b : groups.members[root]) add(m.blocks[b].weight() * m.gravity, m.blocks[b].centroid, Vec3::Zero());
  for (int i : groups.dead_loads[root]) add(m.dead_loads[i].force, m.dead_loads[i].point, m.dead_loads[i].moment);
  return load;
}

// Normal springs give no stiffness to some motions of the body (sliding on a flat base, turning
// about its normal), and next to none when the base is flat but for CAD imprecision: faces a
// fraction of a degree apart give those motions a stiffness of the order of the angle squared.
// Solving with it would let a load of the order of the angle drive the body far along such a
// motion and turn the pressure around (measured: R0 of a settling wall fell from 36.1 to 12.1 kN
// with 0.5 mm noise and 0.2 % warp on its faces). Motions stiffer than kStiffMotion times the
// stiffest are kept; along the others the body does not move, and the part of the load they
// would carry (at most about the angle, here about sqrt(kStiffMotion) = 3 %) is left to friction
// at the base. A larger part is a genuine horizontal load: R0 is then not defined.
constexpr double kStiffMotion = 1e-3;
constexpr double kUncarriedFraction = 0.05;

/// s with K s = -load on the motions stiffer than kStiffMotion times the stiffest, 0 on the others.
Vec6 stiff_motion(const Mat6& K, const Vec6& load) {
  const Eigen::SelfAdjointEigenSolver<Mat6> eigen(K);
  const Vec6& values = eigen.eigenvalues();
  const double largest = values.cwiseAbs().maxCoeff();
  Vec6 s = Vec6::Zero();
  for (int k = 0; k < 6; ++k) {
    if (!(values[k] > kStiffMotion * largest)) continue;
    const auto mode = eigen.eigenvectors().col(k);
    s -= (mode.dot(load) / values[k]) * mode;
  }
  return s;
}

/// The no-tension base pressure of one rigid body: solve on the part in contact, lift where the
/// pressure pulls, repeat. Settled when a pass changes neither the contact area nor s: s was then
/// solved on the very contact it leaves in place (comparing areas alone would miss a neutral axis
/// that turns). Returns s, or empty with `why_not` (completed by `group`, the body's name).
std::optional<Vec6> settle_base_pressure(std::vector<BaseFace>& base, const Vec3& o, double base_area,
                                         const Vec6& load, const std::string& group, std::string& why_not,
                                         int& passes) {
  // Forces and moments mix units: with l = sqrt(base area), D = diag(1, 1, 1, 1/l, 1/l, 1/l)
  // brings the moment rows and rotation columns to force units, so that the rank decision and
  // the acceptance test below depend neither on the length unit nor on the size of the base.
  const double ell = std::sqrt(base_area);
  Vec6 D;
  D << 1.0, 1.0, 1.0, 1.0 / ell, 1.0 / ell, 1.0 / ell;
  const Vec6 scaled_load = D.cwiseProduct(load);
  constexpr int kMaxPasses = 100;
  Vec6 s = Vec6::Zero();
  bool settled = false;
  int pass = 0;
  for (; pass < kMaxPasses && !settled; ++pass) {
    Mat6 K = Mat6::Zero();
    for (const BaseFace& f : base) {
      integrate_quadratic(f.contact, f.normal, [&](double w, const Vec3& x) {
        const Vec6 g = g_of(x, f.normal, o);
        K.noalias() += w * g * g.transpose();
      });
    }
    const Mat6 scaled_K = D.asDiagonal() * K * D.asDiagonal();
    const Vec6 scaled_s = stiff_motion(scaled_K, scaled_load);
    const double imbalance = (scaled_K * scaled_s + scaled_load).norm();
    if (!(imbalance <= kUncarriedFraction * scaled_load.norm())) {
      why_not = "the dead loads on " + group +
                " have a part that normal base pressure cannot carry (for example a horizontal load on a "
                "flat base)";
      return std::nullopt;
    }
    const Vec6 previous_scaled_s = D.cwiseInverse().cwiseProduct(s);
    s = D.cwiseProduct(scaled_s);
    double changed = 0, contact = 0;
    for (BaseFace& f : base) {
      std::vector<Vec3> next = compressed_part(f.polygon, f.normal, o, s);
      const double before = contact_area(f.contact, f.normal);
      const double after = contact_area(next, f.normal);
      changed += std::abs(after - before);
      contact += after;
      f.contact = std::move(next);
    }
    if (!(contact > 1e-12 * base_area)) {
      why_not = "the base of " + group + " lifts everywhere (its dead loads would need tension in the ground)";
      return std::nullopt;
    }
    settled = pass > 0 && changed <= 1e-12 * base_area && (scaled_s - previous_scaled_s).norm() <= 1e-10 * scaled_s.norm();
  }
  if (!settled) {
    why_not = "the no-tension base pressure under " + group + " did not settle in " + std::to_string(kMaxPasses) +
              " passes";
    return std::nullopt;
  }
  passes = pass;
  return s;
}

/// Adds what the moving supports under a settled base hold along d to `total` (point by point,
/// in the order of the groups and faces), and says whether part of the base lifts.
void add_moving_support_reaction(const std::vector<BaseFace>& base, const Vec3& o, const Vec6& s, const Vec3& d,
                                 double& total, bool& base_lifts) {
  for (const BaseFace& f : base) {
    if (contact_area(f.contact, f.normal) < contact_area(f.polygon, f.normal) * (1.0 - 1e-12)) base_lifts = true;
    if (!f.moving) continue;
    // Force of the body on the support: −p n; its component along d is what the ground holds.
    double pressure_resultant = 0;
    integrate_quadratic(f.contact, f.normal,
                        [&](double w, const Vec3& x) { pressure_resultant += w * g_of(x, f.normal, o).dot(s); });
    total += pressure_resultant * (-f.normal.dot(d));
  }
}

}  // namespace

InitialReaction initial_base_reaction(const model::Model& m, const Vec3& d) {
  InitialReaction out;
  const Groups groups = group_free_blocks(m);
  double total = 0;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    const int root = static_cast<int>(b);
    if (m.blocks[b].is_support() || groups.root[b] != root) continue;  // one pass per group, at its root
    double base_area = 0;
    Vec3 o;
    std::vector<BaseFace> base = base_of(m, groups.base_faces[root], base_area, o);
    // Messages name one block of the group, so that the user can find it.
    const std::string group = "the group of free blocks with block '" + m.blocks[b].id + "'";
    if (base.empty() || !(base_area > 0)) {
      out.why_not = group + " touches no support";
      return out;
    }
    o /= base_area;
    int passes = 0;
    const std::optional<Vec6> s =
        settle_base_pressure(base, o, base_area, dead_wrench(m, groups, root, o), group, out.why_not, passes);
    if (!s) return out;
    out.iterations = std::max(out.iterations, passes);
    add_moving_support_reaction(base, o, *s, d, total, out.base_lifts);
  }
  out.value = total;
  return out;
}

}  // namespace rbla::analysis
