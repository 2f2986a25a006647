#pragma once
// Normal equations of the scaled Newton system:  M dy = r,  M = A W² Aᵀ = Σ_blocks A_k W²_k A_kᵀ,
// where block k is one SOC (dense q×q W²) or one nonnegative variable (scalar W²).
//
// The pattern of M (lower triangle) is built once; each block keeps its rows R_k, a dense copy of
// its columns A_k (|R_k|×q) and the positions of its r(r+1)/2 contributions in M's value array,
// so assembly only overwrites values (Clarabel's `datamaps` idea).
//
// Dense columns (nonnegative variables with many nonzeros, e.g. a load multiplier touching every
// equilibrium row) are kept out of M: with M_s the sparse part, D the dense columns and
// d = diag(W²) over them, M = M_s + D diag(d) Dᵀ is solved by the bordered system
//   [M_s  D; Dᵀ −diag(1/d)] [dy; w] = [r; 0]
// ⇒ (Dᵀ M_s⁻¹ D + diag(1/d)) w = Dᵀ M_s⁻¹ r,  dy = M_s⁻¹ (r − D w)   (Schur complement, k×k).
// This form stays well defined when d → 0 or d → ∞ (unlike Sherman–Morrison–Woodbury in d).
//
// M_s is factored as M_s + δI, by one CHOLMOD factor or by SplitCholesky on two threads (then
// each domain's blocks are assembled on their own thread, their separator–separator terms into
// their domain's share); (δ = static regularisation, raised on failure); each solve is
// then refined by preconditioned CG on the exact, unregularised M (applied as A (W² (Aᵀ v)),
// never formed). When M_s becomes nearly singular (the dense column carries directions nothing
// else does), M_s⁻¹D blows up and the bordered solve loses accuracy; the caller detects that
// from the Newton residuals and switches to a NormalEquations built without dense columns.

#include <Eigen/Cholesky>
#include <Eigen/SparseCore>
#include <memory>
#include <string>
#include <vector>

#include "cone.hpp"
#include "linear_solver.hpp"

namespace rbla::conic::detail {

struct FactorReport {
  bool ok = false;
  int retries = 0;
  double shift = 0;
  double assembly_seconds = 0;
  double factor_seconds = 0;
};

class NormalEquations {
 public:
  /// fork_join (may be null: one thread): try SplitCholesky on its two threads, and assemble
  /// the two domains concurrently; one factor if the split declines.
  NormalEquations(const Eigen::SparseMatrix<double>& A, const std::vector<ScalingBlock>& blocks,
                  const std::vector<bool>& is_dense_column, Ordering ordering,
                  ForkJoin* fork_join);

  /// New values of A with the same pattern (the symbolic factorisation is kept).
  void set_A_values(const Eigen::SparseMatrix<double>& A);

  /// Assembles M_s from the packed W² blocks (ConeSet::pack_W2 order) and factors it.
  /// blas_threads > 0: OpenBLAS threads during the numeric factorisation.
  FactorReport factor(const std::vector<double>& packed_W2, double reg_static,
                      double reg_retry_factor, int reg_max_retries, int blas_threads = 0);

  /// Solves M dy = rhs with the last factor, then preconditioned CG on the exact M until
  /// ‖rhs − M dy‖∞ ≤ target or refine_max_iter steps; returns the CG steps taken.
  int solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& dy, int refine_max_iter, double target);

  /// Plain solves (no refinement) of M a = rhs_a and M b = rhs_b, in one pass over the factor:
  /// the triangular solves are memory bound, so the second right-hand side costs a fraction
  /// of the first.
  void solve_pair(const Eigen::VectorXd& rhs_a, const Eigen::VectorXd& rhs_b, Eigen::VectorXd& a,
                  Eigen::VectorXd& b);

  /// out = M v with the exact M of the last factor() call (all blocks, no regularisation).
  void multiply(const Eigen::VectorXd& v, Eigen::VectorXd& out) const;

  long num_factor_solves() const { return num_factor_solves_; }  ///< right-hand sides solved
  long num_multiplies() const { return num_multiplies_; }          ///< products with M
  int num_dense_columns() const { return static_cast<int>(dense_blocks_.size()); }
  long num_matrix_nonzeros() const { return static_cast<long>(row_ind_.size()); }
  bool is_split() const { return split_ != nullptr; }
  long factor_nonzeros() const;
  double factor_bytes() const;   ///< known after construction (symbolic analysis)
  double factor_flops() const;
  std::string backend_name() const;
  int num_analyses() const { return num_analyses_; }

 private:
  void solve_regularised(const Eigen::VectorXd& rhs, Eigen::VectorXd& out);
  /// x ← the regularised solve of each of `columns` columns of x (m values each): the factor,
  /// then the dense columns' bordering.
  void solve_regularised(double* x, int columns);
  /// x ← (M_s + δI)⁻¹ x, column by column, by whichever factor is in use.
  void solve_factor(double* x, int columns);

  struct BlockData {
    Eigen::Index first_col = 0;
    int size = 0;
    std::vector<int> rows;       // R_k, ascending
    std::size_t a_offset = 0;    // into local_A_: |R_k|×size, column-major
    std::size_t w2_offset = 0;   // into packed W²
    std::size_t map_offset = 0;  // into value_map_: r(r+1)/2 positions (column b, rows a ≥ b)
    bool dense = false;
    signed char separator_share = -1;  // SplitCholesky domain whose share gets its SS terms
  };
  void collect_blocks(const Eigen::SparseMatrix<double>& A, const std::vector<ScalingBlock>& blocks,
                      const std::vector<bool>& is_dense_column,
                      std::vector<std::vector<int>>& lower_rows_of_col);
  void build_pattern(std::vector<std::vector<int>>& lower_rows_of_col);
  void build_value_map();
  void choose_backend(Ordering ordering);
  void assemble();
  void factor_dense_schur();
  /// Adds block bd's terms A_k W²_k A_kᵀ to M (or to its domain's separator share).
  void add_block(const BlockData& bd, std::vector<double>& scratch);
  template <class Add>
  void add_terms(const BlockData& bd, const double* Ak, const int* pos,
                 std::vector<double>& scratch, const Add& add);

  Eigen::Index m_ = 0;
  std::vector<BlockData> blocks_;
  std::vector<int> dense_blocks_;  // indices into blocks_
  std::vector<double> local_A_;
  std::vector<int> nnz_to_local_;  // A.valuePtr()[p] → local_A_ index
  std::vector<int> value_map_;
  std::vector<int> col_ptr_, row_ind_;  // lower triangle of M_s
  std::vector<int> diag_pos_;
  std::vector<double> values_;
  std::vector<double> packed_W2_;  // copy from the last factor() (for multiply)
  Eigen::Index multiply_split_ = 0;           // with fork_join_: the helper's first column
  mutable Eigen::VectorXd multiply_other_;    // and its share of the product
  std::vector<double> scratch_[2];  // one per thread
  ForkJoin* fork_join_ = nullptr;
  std::unique_ptr<LinearSolver> solver_;
  SplitDomainSolver* split_ = nullptr;  // solver_, when it is the split one
  std::vector<int> domain_blocks_[2];   // with split_: the (non-dense) blocks of each domain
  int num_analyses_ = 0;
  double shift_ = 0;
  long num_factor_solves_ = 0;
  mutable long num_multiplies_ = 0;

  // Dense-column Schur complement data, refreshed per factorisation.
  Eigen::MatrixXd dense_D_;       // m × k
  Eigen::MatrixXd dense_Minv_D_;  // M_s⁻¹ D
  Eigen::LDLT<Eigen::MatrixXd> dense_schur_;
};

}  // namespace rbla::conic::detail
