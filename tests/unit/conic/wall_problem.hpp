#pragma once
// Synthetic problems with exactly the structure of rigid-block limit analysis, generated here
// independently of rbla's analysis layer (shared by tests/unit/conic and bench/conic).
//
// Wall: ny courses of running-bond boxes (length L = 1, height H, thickness T), even courses nx
// full blocks, odd courses a half block at each end and nx − 1 full blocks; course 0 rests on a
// fixed base. Interfaces: bed joints (overlap rectangles, normal +z) and head joints (normal +x),
// four contact points at each interface's corners. Force at a point on the block on the positive
// side f = N n + T1 t1 + T2 t2 (−f on the other). Per free block 6 equilibrium rows about its
// centroid g: forces ±[n t1 t2], moments ±(p − g) × [n t1 t2]. Variable 0 is the load
// multiplier α ≥ 0, whose column is α times the horizontal load W_i at every block's centroid
// (a dense column); b holds the self-weight. Maximise α (c = −e₀). Forces are in units of a
// full block's weight, lengths in units of L.
//
// Strength, per contact point:
//   Cone:    (μN, T1, T2) ∈ Q³                       (three variables per point)
//   Pyramid: (a, b, c, d) ≥ 0, μN = (a + b)/2 = (c + d)/2, T1 = (b − a)/2, T2 = (d − c)/2,
//            i.e. |T1| ≤ μN and |T2| ≤ μN, with one extra row a + b − c − d = 0 per point
//            (the circumscribed 4-sided pyramid: an LP).

#include <Eigen/Geometry>
#include <algorithm>
#include <vector>

#include "rbla/conic/problem.hpp"

namespace rbla::conic::testing {

struct WallOptions {
  int nx = 38;                ///< full blocks per even course
  int ny = 50;                ///< courses
  double height = 0.5;        ///< H / L
  double thickness = 0.75;    ///< T / L
  double friction = 0.6;      ///< μ
  bool out_of_plane = false;  ///< load along y instead of x
  bool pyramid = false;       ///< LP with the 4-sided pyramid instead of the cone
};

struct WallProblem {
  ConicProblem problem;
  int num_blocks = 0;
  int num_interfaces = 0;
  int num_points = 0;
};

inline WallProblem make_wall_problem(const WallOptions& o) {
  struct Block {
    double x0, x1, z0, z1;
    Eigen::Vector3d centroid;
    double weight;
  };
  struct Interface {
    int positive, negative;  // −1: the fixed base
    Eigen::Vector3d n, t1, t2;
    std::vector<Eigen::Vector3d> points;
  };
  const double L = 1.0, H = o.height, T = o.thickness;
  std::vector<Block> blocks;
  std::vector<std::vector<int>> courses(static_cast<std::size_t>(o.ny));
  for (int j = 0; j < o.ny; ++j) {
    std::vector<std::pair<double, double>> spans;
    if (j % 2 == 0) {
      for (int i = 0; i < o.nx; ++i) spans.push_back({i * L, (i + 1) * L});
    } else {
      spans.push_back({0, L / 2});
      for (int i = 0; i < o.nx - 1; ++i) spans.push_back({L / 2 + i * L, L / 2 + (i + 1) * L});
      spans.push_back({o.nx * L - L / 2, o.nx * L});
    }
    for (auto [a, b] : spans) {
      courses[static_cast<std::size_t>(j)].push_back(static_cast<int>(blocks.size()));
      blocks.push_back({a, b, j * H, (j + 1) * H,
                        Eigen::Vector3d(0.5 * (a + b), 0.5 * T, (j + 0.5) * H), (b - a) / L});
    }
  }
  std::vector<Interface> interfaces;
  const Eigen::Vector3d ex(1, 0, 0), ey(0, 1, 0), ez(0, 0, 1);
  auto bed = [&](int lower, int upper, double a, double b, double z) {
    Interface f{upper, lower, ez, ex, ey, {}};
    for (double x : {a, b}) {
      for (double y : {0.0, T}) f.points.emplace_back(x, y, z);
    }
    interfaces.push_back(f);
  };
  for (int i : courses[0])
    bed(-1, i, blocks[static_cast<std::size_t>(i)].x0, blocks[static_cast<std::size_t>(i)].x1, 0.0);
  for (int j = 0; j + 1 < o.ny; ++j) {
    for (int lo : courses[static_cast<std::size_t>(j)]) {
      for (int up : courses[static_cast<std::size_t>(j) + 1]) {
        const Block& a = blocks[static_cast<std::size_t>(lo)];
        const Block& b = blocks[static_cast<std::size_t>(up)];
        const double x0 = std::max(a.x0, b.x0), x1 = std::min(a.x1, b.x1);
        if (x1 - x0 > 1e-9) bed(lo, up, x0, x1, a.z1);
      }
    }
  }
  for (int j = 0; j < o.ny; ++j) {
    const auto& row = courses[static_cast<std::size_t>(j)];
    for (std::size_t k = 0; k + 1 < row.size(); ++k) {
      const Block& left = blocks[static_cast<std::size_t>(row[k])];
      Interface f{row[k + 1], row[k], ex, ey, ez, {}};
      for (double y : {0.0, T}) {
        for (double z : {left.z0, left.z1}) f.points.emplace_back(left.x1, y, z);
      }
      interfaces.push_back(f);
    }
  }

  WallProblem out;
  out.num_blocks = static_cast<int>(blocks.size());
  out.num_interfaces = static_cast<int>(interfaces.size());
  for (const auto& f : interfaces) out.num_points += static_cast<int>(f.points.size());
  const int per_point = o.pyramid ? 4 : 3;
  const int equilibrium_rows = 6 * out.num_blocks;
  const int m = equilibrium_rows + (o.pyramid ? out.num_points : 0);
  const int n = 1 + per_point * out.num_points;
  ConicProblem& p = out.problem;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(n) * 13);
  p.b = Eigen::VectorXd::Zero(m);
  p.c = Eigen::VectorXd::Zero(n);
  p.c[0] = -1.0;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const int r = 6 * static_cast<int>(i);
    t.emplace_back(r + (o.out_of_plane ? 1 : 0), 0, blocks[i].weight);
    p.b[r + 2] = blocks[i].weight;  // A f + α f_L = −f_D with f_D = (0, 0, −W_i)
  }
  int column = 1;
  int point_index = 0;
  for (const auto& f : interfaces) {
    // Force per unit of each variable.
    std::vector<Eigen::Vector3d> directions;
    if (o.pyramid) {
      const Eigen::Vector3d normal = f.n / (2 * o.friction);
      directions = {normal - 0.5 * f.t1, normal + 0.5 * f.t1, -0.5 * f.t2, 0.5 * f.t2};
    } else {
      directions = {f.n / o.friction, f.t1, f.t2};
    }
    for (const auto& point : f.points) {
      for (int d = 0; d < per_point; ++d) {
        for (auto [block, sign] : {std::pair{f.positive, 1.0}, std::pair{f.negative, -1.0}}) {
          if (block < 0) continue;
          const int r = 6 * block;
          const Eigen::Vector3d force = sign * directions[static_cast<std::size_t>(d)];
          const Eigen::Vector3d moment =
              (point - blocks[static_cast<std::size_t>(block)].centroid).cross(force);
          for (int k = 0; k < 3; ++k) {
            if (force[k] != 0.0) t.emplace_back(r + k, column + d, force[k]);
            if (std::abs(moment[k]) > 1e-14) t.emplace_back(r + 3 + k, column + d, moment[k]);
          }
        }
      }
      if (o.pyramid) {
        const int link = equilibrium_rows + point_index;  // a + b − c − d = 0
        t.emplace_back(link, column, 1.0);
        t.emplace_back(link, column + 1, 1.0);
        t.emplace_back(link, column + 2, -1.0);
        t.emplace_back(link, column + 3, -1.0);
      } else {
        p.cones.soc_dims.push_back(3);
      }
      column += per_point;
      ++point_index;
    }
  }
  p.cones.num_nonneg = o.pyramid ? n : 1;
  p.A.resize(m, n);
  p.A.setFromTriplets(t.begin(), t.end());
  p.A.makeCompressed();
  return out;
}

}  // namespace rbla::conic::testing
