#include "equilibration.hpp"

#include <algorithm>
#include <cmath>

namespace rbla::conic::detail {

Equilibration identity_equilibration(Eigen::Index rows, Eigen::Index cols) {
  Equilibration eq;
  eq.row_scale = Eigen::VectorXd::Ones(rows);
  eq.col_scale = Eigen::VectorXd::Ones(cols);
  return eq;
}

Equilibration ruiz_equilibration(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b,
                                 const Eigen::VectorXd& c, const std::vector<ScalingBlock>& groups,
                                 int sweeps, double min_scaling, double max_scaling) {
  Equilibration eq = identity_equilibration(A.rows(), A.cols());
  Eigen::VectorXd row_norm(A.rows()), col_norm(A.cols());
  auto clamp = [&](double v) { return std::min(max_scaling, std::max(min_scaling, v)); };
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    row_norm.setZero();
    col_norm.setZero();
    for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it) {
        const double v = std::abs(eq.row_scale[it.row()] * it.value() * eq.col_scale[j]);
        row_norm[it.row()] = std::max(row_norm[it.row()], v);
        col_norm[j] = std::max(col_norm[j], v);
      }
    }
    double worst = 0;
    for (Eigen::Index i = 0; i < A.rows(); ++i) {
      if (row_norm[i] > 0) {
        eq.row_scale[i] = clamp(eq.row_scale[i] / std::sqrt(row_norm[i]));
        worst = std::max(worst, std::abs(1.0 - row_norm[i]));
      }
    }
    for (const ScalingBlock& g : groups) {
      const double norm = col_norm.segment(g.first, g.size).maxCoeff();
      if (norm > 0) {
        eq.col_scale.segment(g.first, g.size)
            .setConstant(clamp(eq.col_scale[g.first] / std::sqrt(norm)));
        worst = std::max(worst, std::abs(1.0 - norm));
      }
    }
    if (worst < 1e-3) break;  // already equilibrated to within 0.1 %
  }
  const double b_norm = eq.row_scale.cwiseProduct(b).lpNorm<Eigen::Infinity>();
  const double c_norm = eq.col_scale.cwiseProduct(c).lpNorm<Eigen::Infinity>();
  eq.b_scale = b_norm > 0 ? clamp(1.0 / b_norm) : 1.0;
  eq.c_scale = c_norm > 0 ? clamp(1.0 / c_norm) : 1.0;
  return eq;
}

void apply_equilibration(const Equilibration& eq, const Eigen::SparseMatrix<double>& A,
                         Eigen::SparseMatrix<double>& scaled) {
  if (scaled.rows() != A.rows() || scaled.cols() != A.cols() || scaled.nonZeros() != A.nonZeros()) {
    scaled = A;
  }
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const double* values = A.valuePtr();
  double* out = scaled.valuePtr();
  for (Eigen::Index j = 0; j < A.cols(); ++j) {
    for (int p = outer[j]; p < outer[j + 1]; ++p) {
      out[p] = eq.row_scale[inner[p]] * values[p] * eq.col_scale[j];
    }
  }
}

}  // namespace rbla::conic::detail
