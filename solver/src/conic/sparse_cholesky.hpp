#pragma once
// CHOLMOD supernodal LLᵀ of a symmetric positive definite matrix given by its lower triangle
// (CSC). Symbolic analysis (fill-reducing ordering + supernodal structure) is done once per
// pattern; each numeric factorisation reuses it (Ceres' SparseCholesky idea).

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "rbla/conic/settings.hpp"

namespace rbla::conic::detail {

/// Sets OpenBLAS's thread count for its lifetime and restores it after (no effect when the BLAS
/// in use is not OpenBLAS, or for threads ≤ 0). CHOLMOD's solves call dtrsv/dgemv per supernode
/// and small factorisations call the BLAS on blocks of a few dozen rows: with a second thread
/// these spend much of their time in thread hand-over (sched_yield, futex), most of all on a
/// shared machine, where a second BLAS thread can double the CPU time for no less wall time.
/// Large factors gain from threads. Set through openblas_set_num_threads (sparse_cholesky.cpp).
class BlasThreads {
 public:
  explicit BlasThreads(int threads);
  ~BlasThreads();
  BlasThreads(const BlasThreads&) = delete;
  BlasThreads& operator=(const BlasThreads&) = delete;

 private:
  int previous_ = 0;
};

/// OpenBLAS's current thread count; 0 when the BLAS is not OpenBLAS.
int current_blas_threads();

/// Address space that `callers` threads factoring at once still need for OpenBLAS's work
/// buffers, in bytes: 0 for another BLAS, or for buffers already in OpenBLAS's pool. OpenBLAS
/// takes one buffer per concurrent caller of its LAPACK (dpotrf, dlauum) at the first call
/// and keeps it; when malloc refuses one (an address-space limit, `ulimit -v`), it retries
/// forever instead of failing, so a solver must make sure of this memory before it factors.
double blas_buffer_bytes_to_reserve(int callers);
/// Records that `callers` threads have factored at once, so their buffers are in the pool.
void note_blas_callers(int callers);
/// Whether `bytes` can be allocated now (allocated and freed at once, never touched).
bool can_allocate(double bytes);

class SparseCholesky {
 public:
  explicit SparseCholesky(Ordering ordering);
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  /// Pattern of the lower triangle, sorted row indices per column; the arrays must stay alive
  /// (and unchanged) while this object is used. trailing > 0 keeps the last `trailing` rows
  /// last, in their order: the fill-reducing ordering is computed for the leading block alone,
  /// so the factor's last columns hold the Cholesky factor of the Schur complement of that
  /// block (used by SplitCholesky).
  void analyze(int n, const int* col_ptr, const int* row_ind, int trailing = 0);
  /// Factors (M + shift·I) with M's lower-triangle values in the pattern's order. False if
  /// CHOLMOD reports that the matrix is not positive definite (the caller then retries);
  /// ConicResourceError if it ran out of memory.
  bool factorize(const double* values, double shift);
  /// x ← (M + shift·I)⁻¹ x with the last successful factor, for each of `columns` columns (n
  /// values each, column-major): one pass over the factor serves all of them, and the solves
  /// are memory bound.
  void solve(double* x, int columns);
  /// x ← L⁻¹ x (transpose false) or L⁻ᵀ x (true), L the factor of P (M + shift·I) Pᵀ, for each
  /// column: x is in the permuted order, no permutation is applied.
  void solve_triangular(bool transpose, Eigen::MatrixXd& x);
  /// P as a list: row k of the permuted matrix is row permutation()[k] of M.
  const int* permutation() const;
  /// The last t columns of L (t = trailing of analyze()) as a dense t×t lower triangle,
  /// column-major; the entries above the diagonal are zero.
  void trailing_factor(double* out) const;

  long factor_nonzeros() const;
  /// Bytes of the numeric factor (values and supernode indices), known after analyze().
  double factor_bytes() const;
  /// Floating-point operations of one numeric factorisation (from the symbolic analysis).
  double factor_flops() const;
  std::string backend_name() const;
  int num_analyses() const { return num_analyses_; }

 private:
  /// x (n × columns, column-major) ← the solution of CHOLMOD's system `system` (CHOLMOD_A,
  /// _L, _Lt) with right-hand sides x.
  void solve_system(int system, double* x, int columns);

  struct Impl;
  std::unique_ptr<Impl> impl_;
  int num_analyses_ = 0;
};

}  // namespace rbla::conic::detail
