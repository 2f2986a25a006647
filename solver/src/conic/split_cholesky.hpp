#pragma once
// Cholesky factorisation of a symmetric positive definite M on two threads, by one level of
// nested dissection (George 1973; the "subdomain + interface" form of Schur-complement domain
// decomposition, Saad, Iterative Methods for Sparse Linear Systems, 2nd ed., §14.2).
//
// A node separator S of M's graph splits the rows into two domains that M does not couple:
//   M = [M₀₀ 0 M₀ₛ; 0 M₁₁ M₁ₛ; Mₛ₀ Mₛ₁ Mₛₛ].
// Mₛₛ is split into the parts the caller's two groups of terms contribute, Mₛₛ = Hₛ⁽⁰⁾ + Hₛ⁽¹⁾
// (for M = Σ_k A_k W_k² A_kᵀ each term touches one domain, or the separator only), and domain d
// factors its own positive definite matrix with the separator last,
//   K_d = [M_dd M_dₛ; Mₛ_d Hₛ⁽ᵈ⁾ + (δ/2)I + D] = [L_d 0; B_d T_d][L_d 0; B_d T_d]ᵀ,
// by CHOLMOD, concurrently (D = diag Mₛₛ keeps K_d safely definite; it is taken off below). With
// δ the shift of M, T₀T₀ᵀ + T₁T₁ᵀ − 2D = Mₛₛ + δI − Σ_d B_d B_dᵀ is the Schur complement of the
// separator in M + δI, factored densely (LAPACK) as Lₛ Lₛᵀ; the blocks L_d, B_d and Lₛ are those
// of the Cholesky factor of M + δI in this ordering, so the solves are those of that factor,
// the two domains' triangular solves running concurrently:
//   forward:  [y_d; w_d] = K_d-factor⁻¹ [b_d; 0]      ⇒ B_d y_d = −T_d w_d
//             xₛ = (Lₛ Lₛᵀ)⁻¹ (bₛ + T₀w₀ + T₁w₁)
//   backward: [x_d; xₛ] = K_d-factor⁻ᵀ [y_d; T_dᵀ xₛ]  ⇒ x_d = L_d⁻ᵀ (y_d − B_dᵀ xₛ).
// Worth it when the factorisation and the solves are large enough to hide the hand-overs
// between the threads (SplitCholesky::analyze declines otherwise).

#include <Eigen/Core>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "fork_join.hpp"
#include "rbla/conic/settings.hpp"
#include "sparse_cholesky.hpp"

namespace rbla::conic::detail {

class SplitCholesky {
 public:
  /// The domains run on the calling thread and fork_join's helper.
  SplitCholesky(Ordering ordering, ForkJoin& fork_join);
  ~SplitCholesky();
  SplitCholesky(const SplitCholesky&) = delete;
  SplitCholesky& operator=(const SplitCholesky&) = delete;

  /// Bisects the graph of M (lower triangle, sorted row indices per column, diagonal present;
  /// the arrays must outlive this object) by a METIS node separator and analyses both domains.
  /// False, leaving the object unusable, when the split is not worth it: a domain with under a
  /// fifth of the rows, a separator of more than a quarter, or one whose dense work would be
  /// over half the domains' own; or when the domains are coupled (never, for a
  /// true separator).
  bool analyze(int n, const int* col_ptr, const int* row_ind);

  /// 0 or 1 for a row of that domain, 2 for a separator row.
  const std::vector<unsigned char>& part_of_row() const { return part_; }
  /// For each position p of M's lower triangle: its slot among the separator–separator entries,
  /// or −1 when p is not such an entry.
  const std::vector<int>& separator_slot() const { return slot_of_position_; }
  int num_separator_slots() const { return num_slots_; }
  /// The inverse: the position in M's lower triangle of each slot.
  const std::vector<int>& separator_positions() const { return position_of_slot_; }

  /// Factors M + shift·I. values: M's lower triangle in the pattern's order; share0/share1: per
  /// separator slot, the parts of those entries that terms of domain 0 and 1 contribute (their
  /// sum is M's value there; a term on the separator alone counts for either). False when M is
  /// not numerically positive definite (the caller then raises the shift).
  bool factorize(const double* values, const double* share0, const double* share1, double shift);
  /// out = (M + shift·I)⁻¹ rhs with the last successful factorisation, for each of `columns`
  /// columns (n values each, column-major; one pass over the factors serves all of them). out may be
  /// rhs: all of rhs is read before out is written.
  void solve(const double* rhs, int columns, double* out);

  long factor_nonzeros() const;
  double factor_bytes() const;
  double factor_flops() const;
  int separator_size() const { return static_cast<int>(separator_rows_.size()); }
  std::string backend_name() const;

 private:
  struct Domain;
  using Column = std::vector<std::pair<int, int>>;  // (local row, source) of one local column
  bool bisect(int n, const int* col_ptr, const int* row_ind);
  std::vector<int> number_rows(const int count[3]);
  bool gather_domain_entries(int n, const int* col_ptr, const int* row_ind,
                             const std::vector<int>& local, std::vector<Column> (&columns)[2]);
  void build_domain(Domain& domain, std::vector<Column>& cols, int s);
  double separator_diagonal(const double* values, int j) const;
  std::vector<unsigned char> part_;
  std::vector<int> separator_rows_;
  std::vector<int> slot_of_position_, position_of_slot_;
  int num_slots_ = 0;
  int n_ = 0;
  const int* m_col_ptr_ = nullptr;  // M's pattern (the caller's)
  std::unique_ptr<Domain> domains_[2];
  Eigen::MatrixXd separator_factor_;  // Lₛ (lower triangle)
  Eigen::MatrixXd separator_rhs_;
  ForkJoin& fork_join_;
  Ordering ordering_;
};

}  // namespace rbla::conic::detail
