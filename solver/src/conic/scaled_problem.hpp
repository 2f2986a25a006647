#pragma once
// The problem the interior-point method works on: A, b, c after Ruiz equilibration
// (equilibration.hpp), and the products with A the iteration needs, on two threads when the
// solver has a second one.

#include <Eigen/SparseCore>
#include <vector>

#include "cone.hpp"
#include "equilibration.hpp"
#include "fork_join.hpp"
#include "rbla/conic/problem.hpp"
#include "rbla/conic/settings.hpp"

namespace rbla::conic::detail {

double inf_norm(const Vec& v);

class ScaledProblem {
 public:
  /// fork_join (may be null): products with A by rows / columns on both threads.
  explicit ScaledProblem(ForkJoin* fork_join = nullptr) : fork_join_(fork_join) {}

  /// Recomputes the equilibration of `original` (or the identity, without Settings::equilibrate)
  /// and refreshes A, b, c; the pattern of A must not change between calls.
  void rescale(const ConicProblem& original, const Settings& settings,
               const std::vector<ScalingBlock>& blocks);

  /// out = Ã v and out = Ãᵀ v.
  void multiply_A(const Vec& v, Vec& out) const;
  void multiply_At(const Vec& v, Vec& out) const;

  bool two_threads() const { return fork_join_ != nullptr; }
  const Eigen::SparseMatrix<double>& A() const { return A_; }
  const Vec& b() const { return b_; }
  const Vec& c() const { return c_; }
  const Equilibration& equilibration() const { return equilibration_; }

 private:
  template <class Sparse>
  void dot_each_vector(const Sparse& S, Eigen::Index split, const Vec& v, Vec& out) const;

  ForkJoin* fork_join_ = nullptr;
  Equilibration equilibration_;
  Eigen::SparseMatrix<double> A_;                        // equilibrated
  Eigen::SparseMatrix<double, Eigen::RowMajor> A_rows_;  // with fork_join_: A by rows
  Eigen::Index row_split_ = 0, col_split_ = 0;           // where the helper's half starts
  Vec b_, c_;                                            // equilibrated
};

}  // namespace rbla::conic::detail
