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
//
// Fixed coordinates (a row of A with one nonzero a, in a column with no other nonzero: a cone
// coordinate set by its own equality, such as the radius of a capped friction cone) are
// eliminated before factoring. Such a row e touches only its own block k, so M_EE is local to the
// block and the Schur complement of the fixed rows is the block's own term with W²_k replaced by
//   W̃² = W² − W²_{:E} G,   G = (W²_EE)⁻¹ W²_{E:}        (the a's cancel),
// which has no more nonzeros than the block already adds. M̃ = M_KK − Σ A_R W²_{:E} G A_Rᵀ is
// factored; a right-hand side is reduced by r̃ = r_K − A_R Gᵀ (r_E / a), and the fixed rows'
// solution is recovered as dy_E = ((W²_EE)⁻¹ (r_E / a) − G A_Rᵀ dy_K) / a. Left in M, each such
// row is a one-column supernode of CHOLMOD's factor: on the capped 1920-block façade (11 000 of
// them) a factorisation took about three times as long for similar flops.
// The subtraction cancels most of M_KK's terms where W² is ill-conditioned (late in a solve),
// so M̃ only preconditions: CG multiplies by the exact M (M_KK kept as assembled, and the fixed
// blocks' own terms), as without fixed rows.

#include <Eigen/Cholesky>
#include <Eigen/SparseCore>
#include <functional>
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
  /// Fixed rows are eliminated when there are at least min_fixed_rows of them.
  NormalEquations(const Eigen::SparseMatrix<double>& A, const std::vector<ScalingBlock>& blocks,
                  const std::vector<bool>& is_dense_column, Ordering ordering,
                  ForkJoin* fork_join, int min_fixed_rows = kMinFixedRows);

  /// Fewer fixed rows than this stay in M. Their elimination pays through CHOLMOD's supernodes
  /// (thousands of one-column ones), and on a 2-row problem with data spanning twelve decades
  /// the eliminated preconditioner stalled at a 1e-11 gap where the whole factor did not.
  static constexpr int kMinFixedRows = 256;

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

  /// out = M v with the exact M of the last factor() call (all blocks and rows, no
  /// regularisation).
  void multiply(const Eigen::VectorXd& v, Eigen::VectorXd& out) const;

  long num_factor_solves() const { return num_factor_solves_; }  ///< right-hand sides solved
  long num_multiplies() const { return num_multiplies_; }          ///< products with M
  int num_dense_columns() const { return static_cast<int>(dense_blocks_.size()); }
  int num_fixed_rows() const { return static_cast<int>(full_m_ - m_); }  ///< eliminated
  long num_matrix_nonzeros() const { return static_cast<long>(row_ind_.size()); }
  bool is_split() const { return split_ != nullptr; }
  long factor_nonzeros() const;
  double factor_bytes() const;   ///< known after construction (symbolic analysis)
  double factor_flops() const;
  std::string backend_name() const;
  int num_analyses() const { return num_analyses_; }

 private:
  /// out = the lower triangle `lower` (M's pattern over the rows that are not fixed) times v,
  /// plus the dense columns' terms.
  void multiply_lower(const std::vector<double>& lower, const Eigen::VectorXd& v,
                      Eigen::VectorXd& out) const;
  /// out ≈ M⁻¹ rhs by the regularised factor (and the fixed rows' elimination): CG's
  /// preconditioner and the plain solve.
  void precondition(const Eigen::VectorXd& rhs, Eigen::VectorXd& out);
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
    int fixed_column = -1;             // its one fixed coordinate (block-local), if it has one
  };
  /// A block's coordinates fixed by rows of their own (see the top of this file).
  struct FixedBlock {
    int block = 0;               // into blocks_
    std::vector<int> local;      // fixed coordinates E, block-local, ascending
    std::vector<int> rows;       // their rows (of A's numbering)
    std::vector<int> a_at;       // their entries of A, in fixed_a_
    std::size_t G_offset = 0;    // into fixed_G_: G = (W²_EE)⁻¹ W²_{E:}, |E|×q column-major
    std::size_t EE_offset = 0;   // into fixed_EE_inverse_: (W²_EE)⁻¹, |E|×|E|
  };
  /// A's row in M̃'s numbering; −1 − t for the t-th fixed row.
  int row_of_M(int row) const {
    return reduced_row_.empty() ? row : reduced_row_[static_cast<std::size_t>(row)];
  }
  // Fixed rows (normal_equations_fixed.cpp).
  void find_fixed_rows(const Eigen::SparseMatrix<double>& A, const std::vector<ScalingBlock>& blocks,
                       const std::vector<bool>& is_dense_column, int min_fixed_rows);
  /// Each fixed block's G and (W²_EE)⁻¹ from packed_W2_; false when a fixed entry of A is zero
  /// (the row fixes nothing) or W²_EE is not positive definite.
  bool eliminate_fixed();
  /// values_ (M_KK, assembled from the blocks' own W²) less each fixed block's
  /// A_R W²_{:E} G A_Rᵀ: M̃, the matrix factored.
  void subtract_fixed_terms();
  void reduce(const Eigen::VectorXd& full, Eigen::VectorXd& reduced) const;
  void expand(const Eigen::VectorXd& full_rhs, const Eigen::VectorXd& reduced, Eigen::VectorXd& full) const;
  /// out (full) = M v (full) from M_KK v_K (exact_values_) and the fixed blocks' own terms.
  void multiply_full(const Eigen::VectorXd& v, Eigen::VectorXd& out) const;
  /// t = A_Rᵀ v over the block's rows that are not fixed (q values), and out[R] += A_R g.
  void block_At(const BlockData& bd, const Eigen::VectorXd& v, double* t) const;
  void add_block_A(const BlockData& bd, const double* g, Eigen::VectorXd& out) const;
  /// The rows that are not fixed, full numbering ↔ M̃'s.
  void gather_free(const Eigen::VectorXd& full, Eigen::VectorXd& free) const;
  void scatter_free(const Eigen::VectorXd& free, Eigen::VectorXd& full) const;
  /// work(begin, end, half) over fixed_blocks_: the second half on fork_join_'s helper, if any.
  void for_fixed_halves(const std::function<void(std::size_t, std::size_t, int)>& work) const;
  /// u = r_E / a over the block's fixed rows.
  void fixed_rhs(const FixedBlock& fb, const Eigen::VectorXd& full, double* u) const;
  void collect_blocks(const Eigen::SparseMatrix<double>& A, const std::vector<ScalingBlock>& blocks,
                      const std::vector<bool>& is_dense_column,
                      std::vector<std::vector<int>>& lower_rows_of_col);
  void build_pattern(std::vector<std::vector<int>>& lower_rows_of_col);
  void build_value_map();
  void choose_backend(Ordering ordering);
  void assemble();
  /// values_ at the separator–separator positions from the two domains' shares.
  void sum_separator_shares();
  void factor_dense_schur();
  /// Adds block bd's terms A_k W²_k A_kᵀ to M (or to its domain's separator share).
  /// W2_k: the q×q matrix to use instead of the block's packed W² (null: the packed one).
  void add_block(const BlockData& bd, std::vector<double>& scratch, const double* W2_k = nullptr);
  /// W2_k: the block's q×q W² (null: its packed W²).
  template <class Add>
  void add_terms(const BlockData& bd, const double* Ak, const int* pos,
                 std::vector<double>& scratch, const Add& add, const double* W2_k = nullptr);

  Eigen::Index m_ = 0;       // rows of the factored system (A's rows less the fixed ones)
  Eigen::Index full_m_ = 0;  // A's rows
  std::vector<int> reduced_row_;  // A's row → row_of_M (empty: no row fixed)
  std::vector<FixedBlock> fixed_blocks_;
  std::vector<double> fixed_a_;   // the fixed rows' entries of A
  std::vector<double> exact_values_;  // M_KK before the elimination (what CG multiplies by)
  std::vector<double> fixed_G_, fixed_EE_inverse_;
  int max_block_size_ = 0;
  mutable Eigen::VectorXd reduced_scratch_[4];  // precondition()'s, multiply_full()'s v and out, reduce()'s second half
  std::vector<BlockData> blocks_;
  std::vector<int> dense_blocks_;  // indices into blocks_
  std::vector<double> local_A_;
  std::vector<int> nnz_to_local_;  // A.valuePtr()[p] → local_A_ index (−1 − t: fixed_a_[t])
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
