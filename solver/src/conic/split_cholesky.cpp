#include "split_cholesky.hpp"

#include <cholmod.h>

#include <algorithm>
#include <cstring>
#include <functional>
#include <utility>

#include "rbla/conic/problem.hpp"

// BLAS and LAPACK (libblas.so.3 / liblapack.so.3, OpenBLAS on the README's install). The
// trailing lengths are the hidden Fortran string-length arguments.
extern "C" {
void dlauum_(const char* uplo, const int* n, double* a, const int* lda, int* info,
             std::size_t uplo_len);
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info,
             std::size_t uplo_len);
}

namespace rbla::conic::detail {

struct SplitCholesky::Domain {
  explicit Domain(Ordering ordering) : factor(ordering) {}
  std::vector<int> rows;  // local → global: this domain's rows ascending, then the separator's
  int interior = 0;       // how many of `rows` are the domain's own
  std::vector<int> col_ptr, row_ind;  // K_d's lower triangle in local numbering
  std::vector<int> source;  // per entry: its position in M's values, or −1 − slot (separator)
  std::vector<double> values;
  SparseCholesky factor;
  Eigen::MatrixXd trailing;  // T_d
  Eigen::MatrixXd flipped;   // J T_d J, then J T_d T_dᵀ J (J reverses the order)
  Eigen::MatrixXd work, coupling;  // one column per right-hand side
};

SplitCholesky::SplitCholesky(Ordering ordering, ForkJoin& fork_join)
    : fork_join_(fork_join), ordering_(ordering) {}
SplitCholesky::~SplitCholesky() = default;

double SplitCholesky::separator_diagonal(const double* values, int j) const {
  // M's diagonal entry is the first of its column.
  return values[m_col_ptr_[separator_rows_[static_cast<std::size_t>(j)]]];
}

bool SplitCholesky::analyze(int n, const int* col_ptr, const int* row_ind) {
  n_ = n;
  m_col_ptr_ = col_ptr;
  if (n < 2 || !bisect(n, col_ptr, row_ind)) return false;
  int count[3] = {0, 0, 0};
  for (unsigned char p : part_) ++count[p];
  if (std::min(count[0], count[1]) < n / 5 || count[2] > n / 4) return false;
  const std::vector<int> local = number_rows(count);
  const int s = static_cast<int>(separator_rows_.size());
  std::vector<Column> columns[2];
  if (!gather_domain_entries(n, col_ptr, row_ind, local, columns)) return false;
  for (int d = 0; d < 2; ++d) build_domain(*domains_[d], columns[d], s);
  separator_factor_.setZero(s, s);
  separator_rhs_.setZero(s, 1);
  // One after the other: METIS keeps its random state in a global (gk_randinit), so two
  // concurrent orderings would race and differ from run to run.
  for (auto& domain : domains_)
    domain->factor.analyze(domain->interior + s, domain->col_ptr.data(), domain->row_ind.data(), s);
  // The separator's dense work (two T Tᵀ, 2s³/3, and its Cholesky, s³/3) is on top of what one
  // factor would do; where it would be half as much as the domains' own, one factor is
  // cheaper (the dense work runs at BLAS-3 speed, several times the sparse factor's).
  const double dense_flops = static_cast<double>(s) * s * s;
  const double domain_flops =
      domains_[0]->factor.factor_flops() + domains_[1]->factor.factor_flops();
  return dense_flops <= 0.5 * domain_flops;
}

// Node separator of M's graph (METIS through CHOLMOD; the diagonal is ignored) into part_.
bool SplitCholesky::bisect(int n, const int* col_ptr, const int* row_ind) {
  part_.assign(static_cast<std::size_t>(n), 2);
  cholmod_common common;
  cholmod_start(&common);
  common.print = 0;
  cholmod_sparse pattern{};
  pattern.nrow = pattern.ncol = static_cast<size_t>(n);
  pattern.nzmax = static_cast<size_t>(col_ptr[n]);
  pattern.p = const_cast<int*>(col_ptr);
  pattern.i = const_cast<int*>(row_ind);
  pattern.stype = -1;  // lower triangle stored
  pattern.itype = CHOLMOD_INT;
  pattern.xtype = CHOLMOD_PATTERN;
  pattern.dtype = CHOLMOD_DOUBLE;
  pattern.sorted = 1;
  pattern.packed = 1;
  // METIS balances the two sides only loosely, and differently with and without CHOLMOD's
  // compression of identical rows (which one is better varies from problem to problem). Both
  // are tried and the one with the smaller larger side, counting the separator twice (both
  // domains factor it), is kept: the two threads wait for the slower domain.
  long best_cost = -1;
  for (const int compress : {0, 1}) {
    std::vector<int> partition(static_cast<std::size_t>(n), 2);
    const long separator =
        cholmod_bisect(&pattern, nullptr, 0, compress, partition.data(), &common);
    if (separator < 0 || common.status < CHOLMOD_OK) continue;
    long side[3] = {0, 0, 0};
    for (int p : partition) ++side[p];
    const long cost = std::max(side[0], side[1]) + 2 * side[2];
    if (best_cost >= 0 && cost >= best_cost) continue;
    best_cost = cost;
    for (int i = 0; i < n; ++i)
      part_[static_cast<std::size_t>(i)] =
          static_cast<unsigned char>(partition[static_cast<std::size_t>(i)]);
  }
  cholmod_finish(&common);
  return best_cost >= 0;
}

// Local numbering: each domain's rows, then the separator's, ascending. Creates the domains.
std::vector<int> SplitCholesky::number_rows(const int count[3]) {
  const int n = static_cast<int>(part_.size());
  std::vector<int> local(static_cast<std::size_t>(n));
  separator_rows_.clear();
  for (int d = 0; d < 2; ++d) {
    domains_[d] = std::make_unique<Domain>(ordering_);
    domains_[d]->interior = count[d];
  }
  for (int i = 0; i < n; ++i) {
    const unsigned char p = part_[static_cast<std::size_t>(i)];
    if (p == 2) {
      local[static_cast<std::size_t>(i)] = static_cast<int>(separator_rows_.size());
      separator_rows_.push_back(i);
    } else {
      local[static_cast<std::size_t>(i)] = static_cast<int>(domains_[p]->rows.size());
      domains_[p]->rows.push_back(i);
    }
  }
  for (auto& domain : domains_)
    domain->rows.insert(domain->rows.end(), separator_rows_.begin(), separator_rows_.end());
  return local;
}

// Each K_d's lower triangle: the entries of M inside domain d and between it and the
// separator, and all separator–separator entries (values from the shares, numbered as slots).
// False when an entry couples the two domains (not a separator after all).
bool SplitCholesky::gather_domain_entries(int n, const int* col_ptr, const int* row_ind,
                                          const std::vector<int>& local,
                                          std::vector<Column> (&columns)[2]) {
  const int s = static_cast<int>(separator_rows_.size());
  slot_of_position_.assign(static_cast<std::size_t>(col_ptr[n]), -1);
  position_of_slot_.clear();
  num_slots_ = 0;
  for (int d = 0; d < 2; ++d)
    columns[d].resize(static_cast<std::size_t>(domains_[d]->interior + s));
  auto add = [&](int d, int lr, int lc, int source) {
    columns[d][static_cast<std::size_t>(std::min(lr, lc))].emplace_back(std::max(lr, lc), source);
  };
  for (int c = 0; c < n; ++c) {
    const unsigned char pc = part_[static_cast<std::size_t>(c)];
    for (int p = col_ptr[c]; p < col_ptr[c + 1]; ++p) {
      const int r = row_ind[p];
      const unsigned char pr = part_[static_cast<std::size_t>(r)];
      if (pr == 2 && pc == 2) {
        const int slot = num_slots_++;
        slot_of_position_[static_cast<std::size_t>(p)] = slot;
        position_of_slot_.push_back(p);
        for (int d = 0; d < 2; ++d) {
          const int base = domains_[d]->interior;
          add(d, base + local[static_cast<std::size_t>(r)], base + local[static_cast<std::size_t>(c)],
              -1 - slot);
        }
        continue;
      }
      if (pr != 2 && pc != 2 && pr != pc) return false;
      const int d = pr != 2 ? pr : pc;
      const int base = domains_[d]->interior;
      add(d, local[static_cast<std::size_t>(r)] + (pr == 2 ? base : 0),
          local[static_cast<std::size_t>(c)] + (pc == 2 ? base : 0), p);
    }
  }
  return true;
}

// K_d's compressed columns from the gathered (row, source) entries, and its dense work space.
void SplitCholesky::build_domain(Domain& domain, std::vector<Column>& cols, int s) {
  domain.col_ptr.assign(cols.size() + 1, 0);
  for (std::size_t j = 0; j < cols.size(); ++j) {
    std::sort(cols[j].begin(), cols[j].end());
    domain.col_ptr[j + 1] = domain.col_ptr[j] + static_cast<int>(cols[j].size());
    if (cols[j].empty() || cols[j].front().first != static_cast<int>(j))
      throw ConicSetupError("SplitCholesky: the normal matrix's pattern lacks a diagonal entry");
  }
  domain.row_ind.clear();
  domain.source.clear();
  domain.row_ind.reserve(static_cast<std::size_t>(domain.col_ptr.back()));
  domain.source.reserve(static_cast<std::size_t>(domain.col_ptr.back()));
  for (auto& col : cols) {
    for (const auto& [row, source] : col) {
      domain.row_ind.push_back(row);
      domain.source.push_back(source);
    }
    Column().swap(col);
  }
  domain.values.assign(domain.row_ind.size(), 0.0);
  domain.trailing.setZero(s, s);
  domain.flipped.setZero(s, s);
  domain.work.setZero(domain.interior + s, 1);
  domain.coupling.setZero(s, 1);
}

bool SplitCholesky::factorize(const double* values, const double* share0, const double* share1,
                              double shift) {
  const int s = separator_size();
  bool ok[2] = {false, false};
  const double* shares[2] = {share0, share1};
  auto factor_domain = [&](int d) {
    Domain& domain = *domains_[d];
    const double* share = shares[d];
    const std::size_t nnz = domain.values.size();
    for (std::size_t e = 0; e < nnz; ++e) {
      const int source = domain.source[e];
      domain.values[e] = source >= 0 ? values[source] : share[-1 - source];
    }
    // The shift on the diagonal (the first entry of each column): whole inside the domain,
    // half on the separator, whose two halves add up to M's. The separator's diagonal also
    // gets M's own diagonal there, D, taken off again from the sum of the two T Tᵀ: without it
    // K_d's Schur complement is only δ/2 in directions that the other domain stiffens, and
    // rounding (ε times M's entries, which span 1e±10 late in a solve) makes it indefinite.
    for (int j = 0; j < domain.interior; ++j)
      domain.values[static_cast<std::size_t>(domain.col_ptr[static_cast<std::size_t>(j)])] +=
          shift;
    for (int j = 0; j < s; ++j)
      domain.values[static_cast<std::size_t>(
          domain.col_ptr[static_cast<std::size_t>(domain.interior + j)])] +=
          0.5 * shift + separator_diagonal(values, j);
    ok[d] = domain.factor.factorize(domain.values.data(), 0.0);
    if (!ok[d] || s == 0) return;
    domain.factor.trailing_factor(domain.trailing.data());
    // T Tᵀ in s³/3 flops: LAPACK's dlauum forms U Uᵀ of an upper triangular U, and with J
    // the reversal, T Tᵀ = J (J T J)(J T J)ᵀ J where J T J is upper triangular.
    const Eigen::Index last = s - 1;
    for (Eigen::Index k = 0; k < s; ++k)
      for (Eigen::Index i = 0; i <= k; ++i)
        domain.flipped(i, k) = domain.trailing(last - i, last - k);
    int info = 0;
    dlauum_("U", &s, domain.flipped.data(), &s, &info, 1);
  };
  const std::function<void()> first = [&] { factor_domain(0); };
  const std::function<void()> second = [&] { factor_domain(1); };
  fork_join_.run(first, second);
  if (!ok[0] || !ok[1]) return false;
  if (s > 0) note_blas_callers(2);  // both threads ran dlauum at once
  if (s == 0) return true;
  // Lower triangle of T₀T₀ᵀ + T₁T₁ᵀ − 2D, read back from the flipped upper triangles.
  const Eigen::Index last = s - 1;
  for (Eigen::Index j = 0; j < s; ++j) {
    for (Eigen::Index i = j; i < s; ++i)
      separator_factor_(i, j) =
          domains_[0]->flipped(last - i, last - j) + domains_[1]->flipped(last - i, last - j);
    separator_factor_(j, j) -= 2 * separator_diagonal(values, static_cast<int>(j));
  }
  int info = 0;
  dpotrf_("L", &s, separator_factor_.data(), &s, &info, 1);
  return info == 0;
}

void SplitCholesky::solve(const double* rhs_data, int columns, double* out_data) {
  const int s = separator_size();
  const Eigen::Map<const Eigen::MatrixXd> rhs(rhs_data, n_, columns);
  Eigen::Map<Eigen::MatrixXd> out(out_data, n_, columns);
  auto forward = [&](int d) {
    Domain& domain = *domains_[d];
    const int* perm = domain.factor.permutation();
    const int* rows = domain.rows.data();
    domain.work.resize(domain.interior + s, columns);
    for (Eigen::Index j = 0; j < columns; ++j)
      for (int k = 0; k < domain.interior; ++k) domain.work(k, j) = rhs(rows[perm[k]], j);
    domain.work.bottomRows(s).setZero();
    domain.factor.solve_triangular(false, domain.work);
    domain.coupling.noalias() =
        domain.trailing.triangularView<Eigen::Lower>() * domain.work.bottomRows(s);  // = −B_d y_d
  };
  auto backward = [&](int d) {
    Domain& domain = *domains_[d];
    domain.work.bottomRows(s).noalias() =
        domain.trailing.triangularView<Eigen::Lower>().transpose() * separator_rhs_;
    domain.factor.solve_triangular(true, domain.work);
    const int* perm = domain.factor.permutation();
    const int* rows = domain.rows.data();
    for (Eigen::Index j = 0; j < columns; ++j)
      for (int k = 0; k < domain.interior; ++k) out(rows[perm[k]], j) = domain.work(k, j);
  };
  const std::function<void()> forward0 = [&] { forward(0); };
  const std::function<void()> forward1 = [&] { forward(1); };
  fork_join_.run(forward0, forward1);
  separator_rhs_.resize(s, columns);
  for (Eigen::Index c = 0; c < columns; ++c)
    for (int j = 0; j < s; ++j)
      separator_rhs_(j, c) = rhs(separator_rows_[static_cast<std::size_t>(j)], c) +
                             domains_[0]->coupling(j, c) + domains_[1]->coupling(j, c);
  separator_factor_.triangularView<Eigen::Lower>().solveInPlace(separator_rhs_);
  separator_factor_.triangularView<Eigen::Lower>().transpose().solveInPlace(separator_rhs_);
  const std::function<void()> backward0 = [&] { backward(0); };
  const std::function<void()> backward1 = [&] { backward(1); };
  fork_join_.run(backward0, backward1);
  for (Eigen::Index c = 0; c < columns; ++c)
    for (int j = 0; j < s; ++j)
      out(separator_rows_[static_cast<std::size_t>(j)], c) = separator_rhs_(j, c);
}

long SplitCholesky::factor_nonzeros() const {
  return domains_[0]->factor.factor_nonzeros() + domains_[1]->factor.factor_nonzeros();
}

double SplitCholesky::factor_bytes() const {
  const double s = separator_size();
  return domains_[0]->factor.factor_bytes() + domains_[1]->factor.factor_bytes() +
         5 * s * s * sizeof(double);  // separator factor, two T and two J T Tᵀ J
}

double SplitCholesky::factor_flops() const {
  const double s = separator_size();
  return domains_[0]->factor.factor_flops() + domains_[1]->factor.factor_flops() +
         s * s * s;  // two T Tᵀ, s³/3 each, and the separator's Cholesky
}

std::string SplitCholesky::backend_name() const {
  return domains_[0]->factor.backend_name() + " on two domains and a separator of " +
         std::to_string(separator_size()) + " rows, two threads";
}

}  // namespace rbla::conic::detail
