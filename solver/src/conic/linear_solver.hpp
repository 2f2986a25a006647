#pragma once
// Backends that factor the regularised normal matrix M + δI (symmetric positive definite, given
// by its lower triangle in compressed columns, pattern fixed at construction) and solve with the
// factor; NormalEquations assembles M and picks one (make_linear_solver). The symbolic analysis
// is done once per pattern (Ceres' SparseCholesky; Clarabel's ldlsolvers/ behind one trait).
//
// A distributed factorisation (MUMPS, Amestoy, Duff, L'Excellent & Koster 2001, or a
// partitioned solver on several machines) would be one more LinearSolver: its constructor runs
// the analysis phase on the pattern (MUMPS JOB = 1, symmetric positive definite SYM = 1, the
// lower triangle as its (IRN, JCN) coordinates once, then only A values), factorize() the
// numeric phase (JOB = 2, the shift added to the diagonal entries, which the pattern always
// holds) returning false on INFOG(1) = −10 (not positive definite) so that the caller raises δ,
// and solve() the solution phase (JOB = 3) on the gathered right-hand sides, several columns
// at once. Nothing above NormalEquations would change.

#include <memory>
#include <string>
#include <vector>

#include "fork_join.hpp"
#include "rbla/conic/settings.hpp"
#include "sparse_cholesky.hpp"
#include "split_cholesky.hpp"

namespace rbla::conic::detail {

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  /// Factors M + shift·I, M's lower-triangle values in the pattern's order. False when the
  /// matrix is not numerically positive definite (the caller raises the shift and retries).
  virtual bool factorize(const double* values, double shift) = 0;
  /// x ← (M + shift·I)⁻¹ x with the last successful factor, for each of `columns` columns (n
  /// values each, column-major); one pass over the factor serves all of them.
  virtual void solve(double* x, int columns) = 0;
  /// BLAS threads for the numeric factorisation when the caller asks for `requested`.
  virtual int blas_threads(int requested) const { return requested; }
  virtual long factor_nonzeros() const = 0;
  virtual double factor_bytes() const = 0;  ///< known after construction (symbolic analysis)
  virtual double factor_flops() const = 0;
  virtual std::string name() const = 0;
};

/// One CHOLMOD supernodal factor (sparse_cholesky.hpp) on the calling thread.
class CholmodSolver final : public LinearSolver {
 public:
  /// The pattern arrays must outlive this object.
  CholmodSolver(Ordering ordering, int n, const int* col_ptr, const int* row_ind);
  bool factorize(const double* values, double shift) override;
  void solve(double* x, int columns) override;
  long factor_nonzeros() const override { return cholesky_.factor_nonzeros(); }
  double factor_bytes() const override { return cholesky_.factor_bytes(); }
  double factor_flops() const override { return cholesky_.factor_flops(); }
  std::string name() const override { return cholesky_.backend_name(); }

 private:
  SparseCholesky cholesky_;
};

/// Two CHOLMOD factors on two threads, coupled through a dense separator (split_cholesky.hpp).
/// The assembly must give, besides M's values, each domain's share of the separator–separator
/// entries (shares()).
class SplitDomainSolver final : public LinearSolver {
 public:
  /// Null when the split is not worth it (SplitCholesky::analyze declines).
  static std::unique_ptr<SplitDomainSolver> create(Ordering ordering, ForkJoin& fork_join, int n,
                                                   const int* col_ptr, const int* row_ind);
  bool factorize(const double* values, double shift) override;
  void solve(double* x, int columns) override;
  /// Two domains already take both cores: a BLAS team inside each would oversubscribe them.
  int blas_threads(int) const override { return 1; }
  long factor_nonzeros() const override { return split_.factor_nonzeros(); }
  double factor_bytes() const override { return split_.factor_bytes(); }
  double factor_flops() const override { return split_.factor_flops(); }
  std::string name() const override { return split_.backend_name(); }

  const SplitCholesky& split() const { return split_; }
  /// Per separator slot, the part of M's entry that domain d's terms contribute (to be
  /// refilled before each factorize()).
  std::vector<double>& share(int d) { return shares_[d]; }

 private:
  SplitDomainSolver(Ordering ordering, ForkJoin& fork_join) : split_(ordering, fork_join) {}
  SplitCholesky split_;
  std::vector<double> shares_[2];
};

/// The split solver on fork_join's two threads when there is a second thread and the split is
/// worth it, else one CHOLMOD factor.
std::unique_ptr<LinearSolver> make_linear_solver(Ordering ordering, ForkJoin* fork_join, int n,
                                                 const int* col_ptr, const int* row_ind);

}  // namespace rbla::conic::detail
