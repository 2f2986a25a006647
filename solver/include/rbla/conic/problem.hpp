#pragma once
// Conic program in primal standard form (the SeDuMi / MOSEK form):
//
//   minimise  cᵀx   subject to  A x = b,  x ∈ K,
//   K = R_+^{num_nonneg} × Q^{q_1} × … × Q^{q_k},   Q^q = {(t, u) ∈ R × R^{q-1} : ‖u‖₂ ≤ t}.
//
// Dual:  maximise bᵀy  subject to  c − Aᵀy = z ∈ K* (= K: both cones are self-dual).
// Variables are ordered as the cones: first the nonnegative block, then each second-order cone
// with its t component first. The solver knows nothing about the meaning of the rows.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <stdexcept>
#include <string>
#include <vector>

namespace rbla::conic {

/// Cone K = R_+^{num_nonneg} × Q^{soc_dims[0]} × … in variable order.
struct ConeSpec {
  Eigen::Index num_nonneg = 0;         ///< size of the leading nonnegative orthant
  std::vector<Eigen::Index> soc_dims;  ///< dimension of each second-order cone (≥ 2), in order

  /// Total number of variables covered: num_nonneg + Σ soc_dims.
  Eigen::Index dimension() const;
  /// Barrier parameter ν = num_nonneg + number of second-order cones.
  Eigen::Index degree() const;
};

struct ConicProblem {
  Eigen::SparseMatrix<double> A;  ///< m×n equality matrix (column-major, compressed)
  Eigen::VectorXd b;              ///< m right-hand sides
  Eigen::VectorXd c;              ///< n objective coefficients
  ConeSpec cones;                 ///< cone of x; cones.dimension() must equal n

  /// Readable messages for every inconsistency (dimensions, NaN/Inf, cone sizes); empty if valid.
  std::vector<std::string> validate() const;
};

/// Whether `a` and `b` have the same dimensions, cones and sparsity pattern of A (both
/// compressed): one solver's symbolic analysis serves both (ConicSolver::update).
bool same_shape(const ConicProblem& a, const ConicProblem& b);

/// Bad problem data or settings, detected at setup. Solve outcomes are never exceptions:
/// they are a SolveStatus in Info.
class ConicSetupError : public std::runtime_error {
 public:
  explicit ConicSetupError(const std::string& what) : std::runtime_error(what) {}
  /// Joins messages as "prefix: m1; m2; ...".
  static ConicSetupError from_messages(const std::string& prefix,
                                       const std::vector<std::string>& messages);
};

/// The problem is too large for the memory this process may use (see Settings::memory_limit_bytes):
/// thrown after the symbolic analysis, before the numeric factorisation would allocate.
class ConicResourceError : public ConicSetupError {
 public:
  using ConicSetupError::ConicSetupError;
};

}  // namespace rbla::conic
