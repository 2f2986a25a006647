#include "sparse_cholesky.hpp"

#include <cholmod.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

#include "rbla/conic/problem.hpp"

// Thread counts through the libraries' documented calls: OpenBLAS's openblas_set_num_threads
// (an extension declared in its cblas.h) and OpenMP's omp_set_max_active_levels (OpenMP 5.2
// §18.2.15). They are weak references: the program links whatever BLAS the system's libblas.so.3
// alternative is (OpenBLAS, reference BLAS, BLIS...) and whatever OpenMP runtime CHOLMOD was
// built with, if any; a call that no loaded library provides is a null pointer and leaves that
// setting alone. Nothing here defines or replaces a library symbol.
extern "C" {
void openblas_set_num_threads(int threads) __attribute__((weak));
int openblas_get_num_threads() __attribute__((weak));
void omp_set_max_active_levels(int levels) __attribute__((weak));
int omp_get_max_active_levels() __attribute__((weak));
}

namespace rbla::conic::detail {

namespace {
/// Makes CHOLMOD's OpenMP regions inactive (one thread) on the calling thread for its lifetime.
/// CHOLMOD 3 (Debian 12) opens a parallel region with a compiled-in team of
/// CHOLMOD_OMP_NUM_THREADS = 4 for small loops inside every supernode's update (cholmod_core.h),
/// whatever OMP_NUM_THREADS says: on two cores, with OpenBLAS's threads and the solver's second
/// thread next to it, the team's hand-overs cost more than the loops. A region is active only
/// while fewer than max-active-levels regions enclose it, so 0 makes every region run on the
/// encountering thread alone, num_threads clause or not (OpenMP 5.2 §10.1.1). The setting
/// belongs to the calling thread's data environment (OpenMP ≥ 5.0, libgomp ≥ 11): the two
/// domains of SplitCholesky, factored on two threads at once, each set and restore their own.
class SerialOpenMp {
 public:
  SerialOpenMp() {
    if (!omp_set_max_active_levels || !omp_get_max_active_levels) return;
    saved_ = omp_get_max_active_levels();
    omp_set_max_active_levels(0);
  }
  ~SerialOpenMp() {
    if (saved_ >= 0) omp_set_max_active_levels(saved_);
  }
  SerialOpenMp(const SerialOpenMp&) = delete;
  SerialOpenMp& operator=(const SerialOpenMp&) = delete;

 private:
  int saved_ = -1;
};
}  // namespace

int current_blas_threads() { return openblas_get_num_threads ? openblas_get_num_threads() : 0; }

namespace {
[[noreturn]] void throw_analysis_failure(int status, int rows) {
  if (status == CHOLMOD_OUT_OF_MEMORY) {
    throw ConicResourceError("CHOLMOD ran out of memory in the symbolic analysis (" +
                             std::to_string(rows) + " rows)");
  }
  throw ConicSetupError("CHOLMOD symbolic analysis failed (status " + std::to_string(status) + ")");
}

// OpenBLAS's BUFFER_SIZE on x86-64 (32 << 22 bytes in its Makefile.system, 0.3.21 in Debian 12)
// and the page it adds for alignment: the malloc(134221824) that gdb shows it retrying.
constexpr double kOpenBlasBufferBytes = 134221824.0;
std::atomic<int> blas_callers_served{0};
}  // namespace

double blas_buffer_bytes_to_reserve(int callers) {
  if (!openblas_get_num_threads) return 0.0;
  return std::max(0, callers - blas_callers_served.load()) * kOpenBlasBufferBytes;
}

void note_blas_callers(int callers) {
  int served = blas_callers_served.load();
  while (served < callers && !blas_callers_served.compare_exchange_weak(served, callers)) {
  }
}

bool can_allocate(double bytes) {
  if (!(bytes > 0)) return true;
  if (bytes >= static_cast<double>(std::numeric_limits<std::size_t>::max())) return false;
  // volatile: a malloc whose result is only freed may be elided by the compiler.
  void* volatile probe = std::malloc(static_cast<std::size_t>(bytes));
  if (!probe) return false;
  std::free(probe);
  return true;
}

BlasThreads::BlasThreads(int threads) {
  if (threads <= 0 || !openblas_set_num_threads || !openblas_get_num_threads) return;
  previous_ = openblas_get_num_threads();
  openblas_set_num_threads(threads);
}

BlasThreads::~BlasThreads() {
  if (previous_ > 0) openblas_set_num_threads(previous_);
}

struct SparseCholesky::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  cholmod_sparse matrix{};  // header only: points at the caller's arrays
  cholmod_dense* solution = nullptr;
  cholmod_dense* work_y = nullptr;
  cholmod_dense* work_e = nullptr;
  Ordering ordering;
  int n = 0;
  int trailing = 0;
  int leading_ordering = -1;  // CHOLMOD's choice for the leading block when trailing > 0
  // The same matrix as its upper triangle (CSC), which CHOLMOD's supernodal factorisation
  // permutes with one transpose instead of two (cholmod_factorize.c).
  std::vector<int> upper_col_ptr, upper_row_ind, lower_to_upper;
  std::vector<double> upper_values;

  void set_upper_pattern(int n, const int* col_ptr, const int* row_ind);
  cholmod_factor* analyze_keeping_trailing(int n, int trailing);
};

// `matrix` becomes the pattern of the upper triangle (the lower one transposed), with
// lower_to_upper mapping each lower-triangle position to its upper-triangle position.
void SparseCholesky::Impl::set_upper_pattern(int n, const int* col_ptr, const int* row_ind) {
  cholmod_sparse& a = matrix;
  std::memset(&a, 0, sizeof a);
  a.nrow = static_cast<size_t>(n);
  a.ncol = static_cast<size_t>(n);
  const int nnz = col_ptr[n];
  auto& up = upper_col_ptr;
  auto& ui = upper_row_ind;
  auto& map = lower_to_upper;
  up.assign(static_cast<std::size_t>(n) + 1, 0);
  ui.resize(static_cast<std::size_t>(nnz));
  map.resize(static_cast<std::size_t>(nnz));
  upper_values.resize(static_cast<std::size_t>(nnz));
  for (int p = 0; p < nnz; ++p) ++up[static_cast<std::size_t>(row_ind[p]) + 1];
  for (int j = 0; j < n; ++j) up[j + 1] += up[j];
  std::vector<int> next(up.begin(), up.end() - 1);
  for (int j = 0; j < n; ++j) {
    for (int p = col_ptr[j]; p < col_ptr[j + 1]; ++p) {
      const int q = next[static_cast<std::size_t>(row_ind[p])]++;
      ui[static_cast<std::size_t>(q)] = j;  // column j of the lower triangle is row j of the upper
      map[static_cast<std::size_t>(p)] = q;
    }
  }
  a.nzmax = static_cast<size_t>(nnz);
  a.p = up.data();
  a.i = ui.data();
  a.x = nullptr;
  a.stype = 1;  // upper triangle stored
  a.itype = CHOLMOD_INT;
  a.xtype = CHOLMOD_PATTERN;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = 1;
  a.packed = 1;
}

// Orders the leading block by the chosen method (its upper triangle is the first `lead` columns
// of the upper triangle), then appends the trailing rows and analyses the whole matrix with that
// permutation as given and no postorder, which would move them.
cholmod_factor* SparseCholesky::Impl::analyze_keeping_trailing(int n, int trailing) {
  cholmod_common& c = common;
  cholmod_sparse& a = matrix;
  const int lead = n - trailing;
  std::vector<int> perm(static_cast<std::size_t>(n));
  if (lead > 0) {
    a.nrow = a.ncol = static_cast<size_t>(lead);
    a.nzmax = static_cast<size_t>(upper_col_ptr[static_cast<std::size_t>(lead)]);
    cholmod_factor* leading = cholmod_analyze(&a, &c);
    if (!leading || c.status < CHOLMOD_OK) {
      if (leading) cholmod_free_factor(&leading, &c);
      throw_analysis_failure(c.status, lead);
    }
    const int* leading_perm = static_cast<const int*>(leading->Perm);
    std::copy(leading_perm, leading_perm + lead, perm.begin());
    leading_ordering = leading->ordering;
    cholmod_free_factor(&leading, &c);
    a.nrow = a.ncol = static_cast<size_t>(n);
    a.nzmax = static_cast<size_t>(upper_col_ptr[static_cast<std::size_t>(n)]);
  }
  for (int k = lead; k < n; ++k) perm[static_cast<std::size_t>(k)] = k;
  const int nmethods = c.nmethods, method = c.method[0].ordering, postorder = c.postorder;
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_GIVEN;
  c.postorder = 0;
  cholmod_factor* analysed = cholmod_analyze_p(&a, perm.data(), nullptr, 0, &c);
  c.nmethods = nmethods;
  c.method[0].ordering = method;
  c.postorder = postorder;
  if (analysed && !std::equal(perm.begin(), perm.end(), static_cast<const int*>(analysed->Perm))) {
    cholmod_free_factor(&analysed, &c);
    throw ConicSetupError("CHOLMOD did not keep the given ordering");
  }
  return analysed;
}

SparseCholesky::SparseCholesky(Ordering ordering) : impl_(std::make_unique<Impl>()) {
  impl_->ordering = ordering;
  cholmod_start(&impl_->common);
  cholmod_common& c = impl_->common;
  c.print = 0;  // "not positive definite" is an expected outcome here, handled by the caller
  c.supernodal = CHOLMOD_SUPERNODAL;
  switch (ordering) {
    case Ordering::Best:
      // cholmod_analyze tries both and keeps the one with the fewest nonzeros in L.
      c.nmethods = 2;
      c.method[0].ordering = CHOLMOD_AMD;
      c.method[1].ordering = CHOLMOD_METIS;
      break;
    case Ordering::Amd:
      c.nmethods = 1;
      c.method[0].ordering = CHOLMOD_AMD;
      break;
    case Ordering::Metis:
      c.nmethods = 1;
      c.method[0].ordering = CHOLMOD_METIS;
      break;
    case Ordering::CholmodDefault:
      break;
  }
  c.postorder = 1;
}

SparseCholesky::~SparseCholesky() {
  cholmod_common& c = impl_->common;
  if (impl_->factor) cholmod_free_factor(&impl_->factor, &c);
  if (impl_->solution) cholmod_free_dense(&impl_->solution, &c);
  if (impl_->work_y) cholmod_free_dense(&impl_->work_y, &c);
  if (impl_->work_e) cholmod_free_dense(&impl_->work_e, &c);
  cholmod_finish(&c);
}

void SparseCholesky::analyze(int n, const int* col_ptr, const int* row_ind, int trailing) {
  cholmod_common& c = impl_->common;
  if (impl_->factor) cholmod_free_factor(&impl_->factor, &c);
  impl_->n = n;
  impl_->trailing = trailing;
  ++num_analyses_;
  if (n == 0) return;  // no equality rows: nothing to factor
  impl_->set_upper_pattern(n, col_ptr, row_ind);
  impl_->factor = trailing == 0 ? cholmod_analyze(&impl_->matrix, &c)
                                : impl_->analyze_keeping_trailing(n, trailing);
  if (!impl_->factor || c.status < CHOLMOD_OK) {
    if (impl_->factor) cholmod_free_factor(&impl_->factor, &c);
    throw_analysis_failure(c.status, n);
  }
}

bool SparseCholesky::factorize(const double* values, double shift) {
  if (impl_->n == 0) return true;
  cholmod_common& c = impl_->common;
  cholmod_sparse& a = impl_->matrix;
  {
    const int nnz = static_cast<int>(impl_->lower_to_upper.size());
    const int* map = impl_->lower_to_upper.data();
    double* upper = impl_->upper_values.data();
    for (int p = 0; p < nnz; ++p) upper[map[p]] = values[p];
  }
  a.x = impl_->upper_values.data();
  a.xtype = CHOLMOD_REAL;
  double beta[2] = {shift, 0.0};
  const SerialOpenMp serial_openmp;
  const int ok = cholmod_factorize_p(&a, beta, nullptr, 0, impl_->factor, &c);
  a.xtype = CHOLMOD_PATTERN;
  a.x = nullptr;
  if (c.status == CHOLMOD_OUT_OF_MEMORY) {
    throw ConicResourceError("CHOLMOD ran out of memory in the numeric factorisation (" +
                             std::to_string(impl_->n) + " rows)");
  }
  if (!ok || c.status == CHOLMOD_NOT_POSDEF || impl_->factor->minor < impl_->factor->n) {
    return false;
  }
  if (impl_->factor->is_super) note_blas_callers(1);  // a simplicial factor calls no LAPACK
  return c.status >= CHOLMOD_OK;
}

void SparseCholesky::solve(double* x, int columns) {
  if (impl_->n == 0 || columns == 0) return;
  solve_system(CHOLMOD_A, x, columns);
}

void SparseCholesky::solve_triangular(bool transpose, Eigen::MatrixXd& x) {
  if (impl_->n == 0 || x.cols() == 0) return;
  solve_system(transpose ? CHOLMOD_Lt : CHOLMOD_L, x.data(), static_cast<int>(x.cols()));
}

void SparseCholesky::solve_system(int system, double* x, int columns) {
  cholmod_dense b{};
  b.nrow = static_cast<size_t>(impl_->n);
  b.ncol = static_cast<size_t>(columns);
  b.nzmax = b.nrow * b.ncol;
  b.d = b.nrow;
  b.x = x;
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  cholmod_solve2(system, impl_->factor, &b, nullptr, &impl_->solution, nullptr, &impl_->work_y,
                 &impl_->work_e, &impl_->common);
  const double* solution = static_cast<const double*>(impl_->solution->x);
  std::copy(solution, solution + b.nzmax, x);
}

const int* SparseCholesky::permutation() const {
  return impl_->factor ? static_cast<const int*>(impl_->factor->Perm) : nullptr;
}

void SparseCholesky::trailing_factor(double* out) const {
  const int t = impl_->trailing, lead = impl_->n - t;
  std::fill(out, out + static_cast<std::size_t>(t) * static_cast<std::size_t>(t), 0.0);
  if (t == 0) return;
  const cholmod_factor* L = impl_->factor;
  const int* super = static_cast<const int*>(L->super);
  const int* pi = static_cast<const int*>(L->pi);
  const int* px = static_cast<const int*>(L->px);
  const int* row = static_cast<const int*>(L->s);
  const double* x = static_cast<const double*>(L->x);
  // Supernode s holds columns super[s] … super[s+1]−1 as a dense block of pi[s+1]−pi[s] rows
  // (row indices s[pi[s]…]), column-major from x[px[s]] (cholmod_factor.h). Columns from
  // `lead` on have only rows from `lead` on.
  for (std::size_t s = L->nsuper; s-- > 0;) {
    const int first = super[s], end = super[s + 1];
    if (end <= lead) break;
    const int rows = pi[s + 1] - pi[s];
    for (int k = std::max(first, lead); k < end; ++k) {
      const double* column = x + px[s] + static_cast<std::ptrdiff_t>(k - first) * rows;
      for (int r = k - first; r < rows; ++r) {
        const int i = row[pi[s] + r];
        out[static_cast<std::size_t>(i - lead) +
            static_cast<std::size_t>(k - lead) * static_cast<std::size_t>(t)] = column[r];
      }
    }
  }
}

double SparseCholesky::factor_bytes() const {
  const cholmod_factor* L = impl_->factor;
  if (!L) return 0.0;
  // Supernodal: xsize values and ssize row indices; simplicial: about lnz of each.
  const double values = L->is_super ? static_cast<double>(L->xsize) : impl_->common.lnz;
  const double indices = L->is_super ? static_cast<double>(L->ssize) : impl_->common.lnz;
  return values * sizeof(double) + indices * sizeof(int) +
         static_cast<double>(L->n) * (2 * sizeof(double) + 4 * sizeof(int));
}

double SparseCholesky::factor_flops() const { return impl_->common.fl; }

long SparseCholesky::factor_nonzeros() const {
  const cholmod_common& c = impl_->common;
  return static_cast<long>(c.lnz);
}

std::string SparseCholesky::backend_name() const {
  std::string ordering = to_string(impl_->ordering);
  if (impl_->ordering == Ordering::Best && impl_->factor) {
    const int chosen = impl_->trailing > 0 ? impl_->leading_ordering : impl_->factor->ordering;
    ordering = chosen == CHOLMOD_METIS ? "METIS, best of AMD and METIS"
                                       : "AMD, best of AMD and METIS";
  }
  return std::string("CHOLMOD supernodal LL' (") + ordering + ")";
}

}  // namespace rbla::conic::detail
