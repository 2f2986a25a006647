// Experiment: can an interior-point run stop early and finish by projecting onto the optimal
// face it has identified (Mehrotra & Ye 1993, "Finding an interior point in the optimal face of
// linear programs")? For an LP (nonnegative cone only):
//
//   1. solve to relative gap G (default 1e-4) and take x, y, z;
//   2. guess the partition: B = {i : x_i ≥ z_i} with each column scaled to unit norm (x_i > 0
//      at the optimum), N = the rest;
//   3. primal: x_N = 0 and x_B the point nearest x_B^k with A_B x_B = b;
//      dual: y nearest y^k in the least-squares sense of A_Bᵀ y = c_B, and z = c − Aᵀy;
//      both from one factor of A_B A_Bᵀ + δI (δ relative 1e-12), refined;
//   4. report whether the projected pair is optimal to the solver's own stopping test
//      (feasibility 1e-8, x ≥ 0, z ≥ −tol, gap 1e-8): then the run could have stopped at G.
//
//   rbla_conic_face_projection problem.cbf [G ...]
//
// Prints, per G, the iterations to G, the iterations of a full solve, and the projected pair's
// residuals, cone violations and gap. Bench only: the solver itself does not do this.
#include "rbla/conic/io.hpp"
#include "rbla/conic/solver.hpp"

#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

using SpMat = Eigen::SparseMatrix<double>;
using Vec = Eigen::VectorXd;

struct Projection {
  Vec x, y, z;
  int basic = 0;
  bool factored = false;
};

SpMat columns(const SpMat& A, const std::vector<int>& keep) {
  SpMat out(A.rows(), static_cast<Eigen::Index>(keep.size()));
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t j = 0; j < keep.size(); ++j)
    for (SpMat::InnerIterator it(A, keep[j]); it; ++it) t.emplace_back(it.row(), static_cast<int>(j), it.value());
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

Projection project(const rbla::conic::ConicProblem& p, const rbla::conic::Solution& s) {
  Projection out;
  // x_i ≥ z_i in the units of a column scaled to unit norm (x_i ‖a_i‖ against z_i / ‖a_i‖): the
  // test does not depend on the units of each variable.
  std::vector<int> basic;
  for (Eigen::Index i = 0; i < s.x.size(); ++i) {
    const double norm = p.A.col(i).norm();
    if (s.x[i] * norm * norm >= s.z[i]) basic.push_back(static_cast<int>(i));
  }
  out.basic = static_cast<int>(basic.size());
  const SpMat AB = columns(p.A, basic);
  SpMat K = AB * AB.transpose();
  double diag = 0.0;
  for (Eigen::Index i = 0; i < K.rows(); ++i) diag = std::max(diag, K.coeff(i, i));
  SpMat reg(K.rows(), K.cols());
  reg.setIdentity();
  K += (1e-12 * diag) * reg;
  Eigen::SimplicialLDLT<SpMat> ldlt(K);
  out.factored = ldlt.info() == Eigen::Success;
  if (!out.factored) return out;
  Vec xB(basic.size());
  for (std::size_t j = 0; j < basic.size(); ++j) xB[static_cast<Eigen::Index>(j)] = s.x[basic[j]];
  Vec cB(basic.size());
  for (std::size_t j = 0; j < basic.size(); ++j) cB[static_cast<Eigen::Index>(j)] = p.c[basic[j]];
  Vec y = s.y;
  for (int round = 0; round < 4; ++round) {
    xB += AB.transpose() * ldlt.solve(p.b - AB * xB);
    y += ldlt.solve(AB * (cB - AB.transpose() * y));
  }
  out.x = Vec::Zero(s.x.size());
  for (std::size_t j = 0; j < basic.size(); ++j) out.x[basic[j]] = xB[static_cast<Eigen::Index>(j)];
  out.y = y;
  out.z = p.c - p.A.transpose() * y;
  return out;
}

void report(const rbla::conic::ConicProblem& p, double G, const rbla::conic::Solution& early,
            const Projection& pr, double reference) {
  if (!pr.factored) {
    std::printf("G %.0e: %d iterations; factor of A_B A_B^T failed\n", G, early.info.iterations);
    return;
  }
  const double res_p = (p.A * pr.x - p.b).lpNorm<Eigen::Infinity>() /
                       std::max(1.0, p.b.lpNorm<Eigen::Infinity>() + pr.x.lpNorm<Eigen::Infinity>());
  const double zscale = std::max(1.0, p.c.lpNorm<Eigen::Infinity>() + pr.y.lpNorm<Eigen::Infinity>());
  int x_negative = 0, z_negative = 0;
  for (Eigen::Index i = 0; i < pr.x.size(); ++i) {
    if (pr.x[i] < 0) ++x_negative;
    if (pr.z[i] < -1e-8 * zscale) ++z_negative;
  }
  const double primal = p.c.dot(pr.x), dual = p.b.dot(pr.y);
  const double gap = std::abs(primal - dual) / std::max(1.0, std::min(std::abs(primal), std::abs(dual)));
  const double error = std::abs(primal - reference) / std::max(1.0, std::abs(reference));
  std::printf(
      "G %.0e: %d iterations, |B| %d of %d (rows %d); projected: res_primal %.1e, min x %.1e (%d < 0), "
      "min z %.1e of %.1e (%d below -1e-8), gap %.1e, objective %.12g (error %.1e against the full solve) -> %s\n",
      G, early.info.iterations, pr.basic, static_cast<int>(pr.x.size()), static_cast<int>(p.A.rows()), res_p,
      pr.x.minCoeff(), x_negative, pr.z.minCoeff(), zscale, z_negative, gap, primal, error,
      (res_p <= 1e-8 && x_negative == 0 && z_negative == 0 && gap <= 1e-8) ? "OPTIMAL" : "not optimal");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s problem.cbf [G ...]\n", argv[0]);
    return 2;
  }
  try {
    const rbla::conic::ConicProblem problem = rbla::conic::read_cbf_file(argv[1]);
    if (!problem.cones.soc_dims.empty()) {
      std::fprintf(stderr, "error: LP only (this problem has second-order cones)\n");
      return 2;
    }
    rbla::conic::Settings full;
    const rbla::conic::Solution reference = rbla::conic::solve(problem, full);
    std::printf("full solve: %d iterations, objective %.12g\n", reference.info.iterations,
                reference.info.primal_objective);
    std::vector<double> gaps;
    for (int k = 2; k < argc; ++k) gaps.push_back(std::atof(argv[k]));
    if (gaps.empty()) gaps = {1e-3, 1e-4, 1e-5, 1e-6};
    for (const double G : gaps) {
      rbla::conic::Settings loose;
      loose.tol_gap_rel = loose.tol_gap_abs = loose.tol_feas = G;
      const rbla::conic::Solution early = rbla::conic::solve(problem, loose);
      report(problem, G, early, project(problem, early), reference.info.primal_objective);
    }
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
    return 1;
  }
}
