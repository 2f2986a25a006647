#pragma once
// Ruiz equilibration of the equality matrix (Ruiz 2001, "A scaling algorithm to equilibrate both
// rows and columns norms in matrices"; used by OSQP and Clarabel), adapted to cones: all columns
// of one second-order cone share one factor, so the scaled variable stays in the same cone.
//
//   Ã = D A E,   b̃ = s_b D b,   c̃ = s_c E c
//   x = E x̃ / s_b,   y = D ỹ / s_c,   z = E⁻¹ z̃ / s_c.

#include <Eigen/SparseCore>

#include "cone.hpp"

namespace rbla::conic::detail {

struct Equilibration {
  Eigen::VectorXd row_scale;  ///< D
  Eigen::VectorXd col_scale;  ///< E
  double b_scale = 1.0;       ///< s_b
  double c_scale = 1.0;       ///< s_c
};

/// Identity scaling of the given size.
Equilibration identity_equilibration(Eigen::Index rows, Eigen::Index cols);

/// Ruiz sweeps on A; then s_b, s_c make ‖b̃‖∞ and ‖c̃‖∞ ≈ 1. Factors clamped to [min, max].
Equilibration ruiz_equilibration(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b,
                                 const Eigen::VectorXd& c, const std::vector<ScalingBlock>& groups,
                                 int sweeps, double min_scaling, double max_scaling);

/// scaled = D A E with the same pattern as A (values only).
void apply_equilibration(const Equilibration& eq, const Eigen::SparseMatrix<double>& A,
                         Eigen::SparseMatrix<double>& scaled);

}  // namespace rbla::conic::detail
