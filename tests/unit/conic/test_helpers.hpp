#pragma once
// Small builders shared by the conic tests.

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "rbla/conic/problem.hpp"

namespace rbla::conic::testing {

/// Dense row-major description → ConicProblem.
inline ConicProblem make_problem(int rows, int cols, const std::vector<double>& dense_A,
                                 const std::vector<double>& b, const std::vector<double>& c,
                                 Eigen::Index num_nonneg, std::vector<Eigen::Index> soc_dims = {}) {
  ConicProblem p;
  std::vector<Eigen::Triplet<double>> triplets;
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      const double v = dense_A[static_cast<std::size_t>(i * cols + j)];
      if (v != 0.0) triplets.emplace_back(i, j, v);
    }
  }
  p.A.resize(rows, cols);
  p.A.setFromTriplets(triplets.begin(), triplets.end());
  p.A.makeCompressed();
  p.b = Eigen::Map<const Eigen::VectorXd>(b.data(), static_cast<Eigen::Index>(b.size()));
  p.c = Eigen::Map<const Eigen::VectorXd>(c.data(), static_cast<Eigen::Index>(c.size()));
  p.cones.num_nonneg = num_nonneg;
  p.cones.soc_dims = std::move(soc_dims);
  return p;
}

}  // namespace rbla::conic::testing

namespace rbla::conic::testing {

/// How far v is outside K (0 if inside): max over nonnegative entries of −v_i and over SOCs of
/// ‖u‖ − t.
inline double cone_violation(const Eigen::VectorXd& v, const ConeSpec& cones) {
  double worst = 0;
  for (Eigen::Index i = 0; i < cones.num_nonneg; ++i) worst = std::max(worst, -v[i]);
  Eigen::Index k = cones.num_nonneg;
  for (Eigen::Index q : cones.soc_dims) {
    worst = std::max(worst, v.segment(k + 1, q - 1).norm() - v[k]);
    k += q;
  }
  return worst;
}

/// Checks a primal-infeasibility certificate y: bᵀy > 0 and −Aᵀy ∈ K*, scaled so bᵀy = 1.
inline double primal_certificate_error(const ConicProblem& p, const Eigen::VectorXd& y) {
  const double bty = p.b.dot(y);
  if (!(bty > 0)) return std::numeric_limits<double>::infinity();
  const Eigen::VectorXd s = -(p.A.transpose() * (y / bty));
  return cone_violation(s, p.cones);
}

/// Checks a dual-infeasibility (unboundedness) certificate x: cᵀx < 0, A x = 0, x ∈ K, scaled
/// so cᵀx = −1.
inline double dual_certificate_error(const ConicProblem& p, const Eigen::VectorXd& x) {
  const double ctx = p.c.dot(x);
  if (!(ctx < 0)) return std::numeric_limits<double>::infinity();
  const Eigen::VectorXd xs = x / (-ctx);
  return std::max((p.A * xs).lpNorm<Eigen::Infinity>(), cone_violation(xs, p.cones));
}

}  // namespace rbla::conic::testing
