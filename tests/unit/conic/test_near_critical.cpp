// Infeasibility certificates close to the feasibility boundary: the planar limit-analysis LP of
// a semicircular arch of N radial voussoirs slightly thinner than its least thickness
// (t/R ≈ 0.1074 for N = 40). The primal (equilibrium with admissible contact forces) is then
// infeasible, but only just: the normal matrix A W² Aᵀ becomes ill-conditioned (smallest
// eigenvalue below the static regularisation), so the Newton directions need refinement to
// reduce the primal residual. Without it the embedding's iterates shrink together and the
// certificate residual stalls near 1e-5 (regression test for that).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rbla/conic/solver.hpp"
#include "test_helpers.hpp"

using namespace rbla::conic;
using namespace rbla::conic::testing;

namespace {

// Unknowns: per joint j = 0..N (at angle θ_j = π j/N; joints 0 and N on fixed abutments) and per
// contact point (intrados, extrados) two nonnegatives u, v with normal n = u + v and radial
// shear s = μ (u − v), which describes |s| ≤ μ n exactly; then the load multiplier α ≥ 0.
// Rows: force x, force y and moment of each voussoir. Minimise −α (maximise the horizontal load
// multiplier); self-weight W_i at the centroid, horizontal load α W_i.
ConicProblem arch_lp(int num_voussoirs, double thickness, double radius = 1.0, double mu = 5.0) {
  const int N = num_voussoirs;
  const double ri = radius - 0.5 * thickness, re = radius + 0.5 * thickness;
  const int n = 4 * (N + 1) + 1, m = 3 * N, alpha = n - 1;
  std::vector<Eigen::Triplet<double>> t;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(m);
  auto angle = [&](int j) { return M_PI * j / N; };
  for (int j = 0; j <= N; ++j) {
    const double th = angle(j);
    const double tx = -std::sin(th), ty = std::cos(th);  // joint normal: direction of growing θ
    const double rx = std::cos(th), ry = std::sin(th);   // radial: the shear direction
    for (int k = 0; k < 2; ++k) {
      const double r = k == 0 ? ri : re;
      const double px = r * rx, py = r * ry;
      for (int s = 0; s < 2; ++s) {
        const int col = 4 * j + 2 * k + s;
        const double sign_shear = s == 0 ? mu : -mu;
        // Force on the voussoir above the joint (block j), into it; the one below gets −f.
        const double fx = tx + sign_shear * rx, fy = ty + sign_shear * ry;
        const double moment = px * fy - py * fx;
        for (int side = 0; side < 2; ++side) {
          const int block = side == 0 ? j : j - 1;
          const double sg = side == 0 ? 1.0 : -1.0;
          if (block < 0 || block >= N) continue;  // abutments are fixed: no rows
          t.emplace_back(3 * block, col, sg * fx);
          t.emplace_back(3 * block + 1, col, sg * fy);
          t.emplace_back(3 * block + 2, col, sg * moment);
        }
      }
    }
  }
  for (int i = 0; i < N; ++i) {
    // Voussoir i: quadrilateral with its chords; area and centroid by the shoelace formula.
    const double a0 = angle(i), a1 = angle(i + 1);
    const double vx[4] = {ri * std::cos(a0), re * std::cos(a0), re * std::cos(a1), ri * std::cos(a1)};
    const double vy[4] = {ri * std::sin(a0), re * std::sin(a0), re * std::sin(a1), ri * std::sin(a1)};
    double area = 0, cx = 0, cy = 0;
    for (int k = 0; k < 4; ++k) {
      const int l = (k + 1) % 4;
      const double cross = vx[k] * vy[l] - vx[l] * vy[k];
      area += 0.5 * cross;
      cx += (vx[k] + vx[l]) * cross;
      cy += (vy[k] + vy[l]) * cross;
    }
    cx /= 6 * area;
    cy /= 6 * area;
    const double W = std::abs(area);
    // Σ contact forces + dead (0, −W) + α (W, 0) = 0, moments about the origin likewise.
    b[3 * i + 1] = W;
    b[3 * i + 2] = cx * W;  // moment of (0, −W) at (cx, cy) is −cx W, moved to the right side
    t.emplace_back(3 * i, alpha, W);
    t.emplace_back(3 * i + 2, alpha, -cy * W);
  }
  ConicProblem p;
  p.A.resize(m, n);
  p.A.setFromTriplets(t.begin(), t.end());
  p.A.makeCompressed();
  p.b = b;
  p.c = Eigen::VectorXd::Zero(n);
  p.c[alpha] = -1.0;
  p.cones.num_nonneg = n;
  return p;
}

}  // namespace

TEST(ConicNearCritical, ThickArchHasPositiveMultiplier) {
  const Solution sol = solve(arch_lp(40, 0.15));
  ASSERT_EQ(sol.info.status, SolveStatus::Solved) << sol.info.brief_report();
  EXPECT_LT(sol.info.primal_objective, -1e-3);  // α > 0
}

TEST(ConicNearCritical, ArchJustBelowLeastThicknessIsCertifiedInfeasible) {
  // Least thickness of this model: t/R in (0.1073, 0.1074) for N = 20, (0.1074, 0.1075) for
  // N = 40 and 80 (measured with this solver); 0.1056 at N = 40 is the case that stalled.
  for (const int N : {20, 40, 80}) {
    for (const double t : {0.1, 0.1056, 0.1060, 0.1065, 0.1070}) {
      SCOPED_TRACE("N=" + std::to_string(N) + " t=" + std::to_string(t));
      const ConicProblem p = arch_lp(N, t);
      const Solution sol = solve(p);
      ASSERT_EQ(sol.info.status, SolveStatus::PrimalInfeasible) << sol.info.brief_report();
      EXPECT_TRUE(sol.info.failure_reason.empty()) << sol.info.failure_reason;
      EXPECT_LE(sol.info.certificate_residual, Settings{}.tol_infeas);
      EXPECT_LE(primal_certificate_error(p, sol.y), 1e-7);
      EXPECT_LE(sol.info.iterations, 40);
    }
  }
}
