#include "normal_equations.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>

#include "rbla/conic/problem.hpp"

namespace rbla::conic::detail {

namespace {
double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

NormalEquations::NormalEquations(const Eigen::SparseMatrix<double>& A,
                                 const std::vector<ScalingBlock>& blocks,
                                 const std::vector<bool>& is_dense_column, Ordering ordering,
                                 ForkJoin* fork_join, int min_fixed_rows)
    : m_(A.rows()), full_m_(A.rows()), fork_join_(fork_join) {
  find_fixed_rows(A, blocks, is_dense_column, min_fixed_rows);
  std::vector<std::vector<int>> lower_rows_of_col(static_cast<std::size_t>(m_));
  collect_blocks(A, blocks, is_dense_column, lower_rows_of_col);
  build_pattern(lower_rows_of_col);
  build_value_map();
  std::size_t max_scratch = 0;
  for (const BlockData& bd : blocks_) {
    max_scratch = std::max(max_scratch, bd.rows.size() * static_cast<std::size_t>(bd.size));
  }
  for (auto& scratch : scratch_) scratch.assign(max_scratch, 0.0);
  set_A_values(A);
  ++num_analyses_;
  multiply_split_ = static_cast<Eigen::Index>(
      std::lower_bound(col_ptr_.begin(), col_ptr_.end(), col_ptr_.back() / 2) - col_ptr_.begin());
  multiply_split_ = std::min(multiply_split_, m_);
  choose_backend(ordering);
  if (!dense_blocks_.empty()) dense_D_.setZero(m_, static_cast<Eigen::Index>(dense_blocks_.size()));
}

// Per block: its rows (of M̃), where its entries of A go in the local dense copy of its columns
// (or, on a fixed row, in fixed_a_), and (unless it is a dense column) the rows its terms add to
// in each column of M̃'s lower triangle.
void NormalEquations::collect_blocks(const Eigen::SparseMatrix<double>& A,
                                     const std::vector<ScalingBlock>& blocks,
                                     const std::vector<bool>& is_dense_column,
                                     std::vector<std::vector<int>>& lower_rows_of_col) {
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  nnz_to_local_.assign(static_cast<std::size_t>(A.nonZeros()), -1);
  std::size_t a_total = 0, w2_total = 0, map_total = 0;
  blocks_.reserve(blocks.size());
  for (const ScalingBlock& sb : blocks) {
    BlockData bd;
    bd.first_col = sb.first;
    bd.size = static_cast<int>(sb.size);
    bd.dense = sb.size == 1 && is_dense_column[static_cast<std::size_t>(sb.first)];
    for (Eigen::Index j = sb.first; j < sb.first + sb.size; ++j) {
      for (int p = outer[j]; p < outer[j + 1]; ++p) {
        const int row = row_of_M(inner[p]);
        if (row >= 0) bd.rows.push_back(row);
      }
    }
    std::sort(bd.rows.begin(), bd.rows.end());
    bd.rows.erase(std::unique(bd.rows.begin(), bd.rows.end()), bd.rows.end());
    const std::size_t r = bd.rows.size();
    bd.a_offset = a_total;
    bd.w2_offset = w2_total;
    bd.map_offset = map_total;
    for (Eigen::Index j = sb.first; j < sb.first + sb.size; ++j) {
      for (int p = outer[j]; p < outer[j + 1]; ++p) {
        const int row = row_of_M(inner[p]);
        if (row < 0) {  // a fixed row: −1 − its index in fixed_a_
          nnz_to_local_[static_cast<std::size_t>(p)] = row;
          continue;
        }
        const auto a = std::lower_bound(bd.rows.begin(), bd.rows.end(), row) - bd.rows.begin();
        nnz_to_local_[static_cast<std::size_t>(p)] = static_cast<int>(
            a_total + static_cast<std::size_t>(a) + r * static_cast<std::size_t>(j - sb.first));
      }
    }
    a_total += r * static_cast<std::size_t>(sb.size);
    w2_total += static_cast<std::size_t>(sb.size * sb.size);
    if (!bd.dense) {
      map_total += r * (r + 1) / 2;
      for (std::size_t b = 0; b < r; ++b) {
        auto& col = lower_rows_of_col[static_cast<std::size_t>(bd.rows[b])];
        col.insert(col.end(), bd.rows.begin() + static_cast<long>(b), bd.rows.end());
      }
    } else {
      dense_blocks_.push_back(static_cast<int>(blocks_.size()));
    }
    blocks_.push_back(std::move(bd));
  }
  for (const FixedBlock& fb : fixed_blocks_) {
    if (fb.local.size() == 1) blocks_[static_cast<std::size_t>(fb.block)].fixed_column = fb.local[0];
  }
  local_A_.assign(a_total, 0.0);
  packed_W2_.assign(w2_total, 0.0);
  value_map_.resize(map_total);
}

// Pattern of M_s's lower triangle, with the full diagonal (regularisation lives there).
void NormalEquations::build_pattern(std::vector<std::vector<int>>& lower_rows_of_col) {
  col_ptr_.assign(static_cast<std::size_t>(m_) + 1, 0);
  for (Eigen::Index i = 0; i < m_; ++i) {
    auto& col = lower_rows_of_col[static_cast<std::size_t>(i)];
    col.push_back(static_cast<int>(i));
    std::sort(col.begin(), col.end());
    col.erase(std::unique(col.begin(), col.end()), col.end());
    col_ptr_[static_cast<std::size_t>(i) + 1] =
        col_ptr_[static_cast<std::size_t>(i)] + static_cast<int>(col.size());
  }
  row_ind_.reserve(static_cast<std::size_t>(col_ptr_.back()));
  diag_pos_.resize(static_cast<std::size_t>(m_));
  for (Eigen::Index i = 0; i < m_; ++i) {
    auto& col = lower_rows_of_col[static_cast<std::size_t>(i)];
    diag_pos_[static_cast<std::size_t>(i)] =
        static_cast<int>(row_ind_.size());  // diagonal is first
    row_ind_.insert(row_ind_.end(), col.begin(), col.end());
    std::vector<int>().swap(col);
  }
  values_.assign(row_ind_.size(), 0.0);
}

// Where each block's contributions land in M's values.
void NormalEquations::build_value_map() {
  for (const BlockData& bd : blocks_) {
    if (bd.dense) continue;
    std::size_t cursor = bd.map_offset;
    const std::size_t r = bd.rows.size();
    for (std::size_t b = 0; b < r; ++b) {
      const int col = bd.rows[b];
      const int* begin = row_ind_.data() + col_ptr_[static_cast<std::size_t>(col)];
      const int* end = row_ind_.data() + col_ptr_[static_cast<std::size_t>(col) + 1];
      for (std::size_t a = b; a < r; ++a) {
        value_map_[cursor++] =
            static_cast<int>(std::lower_bound(begin, end, bd.rows[a]) - row_ind_.data());
      }
    }
  }
}

void NormalEquations::choose_backend(Ordering ordering) {
  solver_ = make_linear_solver(ordering, fork_join_, static_cast<int>(m_), col_ptr_.data(),
                               row_ind_.data());
  split_ = dynamic_cast<SplitDomainSolver*>(solver_.get());
  if (!split_) return;
  // A block lies in one domain and the separator (the separator decouples the domains); one on
  // the separator alone counts for domain 0. Only blocks that reach the separator add to a
  // share.
  const auto& part = split_->split().part_of_row();
  for (std::size_t k = 0; k < blocks_.size(); ++k) {
    BlockData& bd = blocks_[k];
    if (bd.dense) continue;
    int domain = 0;
    bool on_separator = false;
    for (int row : bd.rows) {
      const unsigned char p = part[static_cast<std::size_t>(row)];
      if (p == 2)
        on_separator = true;
      else
        domain = p;
    }
    if (on_separator) bd.separator_share = static_cast<signed char>(domain);
    domain_blocks_[domain].push_back(static_cast<int>(k));
  }
}

void NormalEquations::set_A_values(const Eigen::SparseMatrix<double>& A) {
  const double* values = A.valuePtr();
  for (std::size_t p = 0; p < nnz_to_local_.size(); ++p) {
    const int to = nnz_to_local_[p];
    if (to >= 0)
      local_A_[static_cast<std::size_t>(to)] = values[p];
    else
      fixed_a_[static_cast<std::size_t>(-1 - to)] = values[p];
  }
}

FactorReport NormalEquations::factor(const std::vector<double>& packed_W2, double reg_static,
                                     double reg_retry_factor, int reg_max_retries,
                                     int blas_threads) {
  FactorReport report;
  auto start = std::chrono::steady_clock::now();
  packed_W2_ = packed_W2;
  if (!eliminate_fixed()) return report;
  assemble();
  if (!fixed_blocks_.empty()) {
    exact_values_ = values_;
    subtract_fixed_terms();
  }
  double max_diag = 0;
  for (int p : diag_pos_) max_diag = std::max(max_diag, values_[static_cast<std::size_t>(p)]);
  report.assembly_seconds = seconds_since(start);

  start = std::chrono::steady_clock::now();
  // Clarabel's form: a constant plus ε² times the largest diagonal entry (the data are
  // equilibrated, so the constant is relative to O(1) entries).
  constexpr double eps = std::numeric_limits<double>::epsilon();
  double shift = reg_static + eps * eps * max_diag;
  const BlasThreads threads(solver_->blas_threads(blas_threads));
  for (int attempt = 0; attempt <= reg_max_retries; ++attempt) {
    if (solver_->factorize(values_.data(), shift)) {
      report.ok = true;
      break;
    }
    ++report.retries;
    shift *= reg_retry_factor;
  }
  shift_ = shift;
  report.shift = shift;
  if (report.ok && !dense_blocks_.empty()) factor_dense_schur();
  report.factor_seconds = seconds_since(start);
  return report;
}

// M_s's values from the blocks' terms A_k W²_k A_kᵀ (dense columns left out).
void NormalEquations::assemble() {
  std::fill(values_.begin(), values_.end(), 0.0);
  if (!split_) {
    for (const BlockData& bd : blocks_) {
      if (!bd.dense) add_block(bd, scratch_[0]);
    }
    return;
  }
  for (int d = 0; d < 2; ++d) std::fill(split_->share(d).begin(), split_->share(d).end(), 0.0);
  // Each domain's blocks on their own thread: they write disjoint entries of M, except the
  // separator–separator ones, which go to their domain's share only and are summed after.
  const std::function<void()> domain0 = [this] {
    for (int k : domain_blocks_[0]) add_block(blocks_[static_cast<std::size_t>(k)], scratch_[0]);
  };
  const std::function<void()> domain1 = [this] {
    for (int k : domain_blocks_[1]) add_block(blocks_[static_cast<std::size_t>(k)], scratch_[1]);
  };
  fork_join_->run(domain0, domain1);
  sum_separator_shares();
}

void NormalEquations::sum_separator_shares() {
  const std::vector<int>& positions = split_->split().separator_positions();
  for (std::size_t slot = 0; slot < positions.size(); ++slot)
    values_[static_cast<std::size_t>(positions[slot])] =
        split_->share(0)[slot] + split_->share(1)[slot];
}

// The bordered system's Schur complement Dᵀ M_s⁻¹ D + diag(1/d) (normal_equations.hpp), with
// M_s⁻¹ D kept for the solves.
void NormalEquations::factor_dense_schur() {
  const Eigen::Index k = static_cast<Eigen::Index>(dense_blocks_.size());
  dense_Minv_D_.resize(m_, k);
  Eigen::MatrixXd schur(k, k);
  Eigen::VectorXd column, solved;
  for (Eigen::Index j = 0; j < k; ++j) {
    const BlockData& bd =
        blocks_[static_cast<std::size_t>(dense_blocks_[static_cast<std::size_t>(j)])];
    column.setZero(m_);
    for (std::size_t a = 0; a < bd.rows.size(); ++a) column[bd.rows[a]] = local_A_[bd.a_offset + a];
    dense_D_.col(j) = column;
    solved = column;
    solve_factor(solved.data(), 1);
    dense_Minv_D_.col(j) = solved;
  }
  schur.noalias() = dense_D_.transpose() * dense_Minv_D_;
  for (Eigen::Index j = 0; j < k; ++j) {
    const BlockData& bd =
        blocks_[static_cast<std::size_t>(dense_blocks_[static_cast<std::size_t>(j)])];
    const double d = std::max(packed_W2_[bd.w2_offset], 1e-300);
    schur(j, j) += 1.0 / d;
  }
  dense_schur_.compute(schur);
}

void NormalEquations::add_block(const BlockData& bd, std::vector<double>& scratch, const double* W2_k) {
  const std::size_t r = bd.rows.size();
  const double* Ak = local_A_.data() + bd.a_offset;
  const int* pos = value_map_.data() + bd.map_offset;
  if (bd.separator_share >= 0) {
    // A block reaching the separator: its separator–separator terms go to its domain's share
    // alone (summed into M after both domains are assembled; the shares must be sums of their
    // own terms, as a difference of M's value and the other share could lose the small one).
    const std::vector<int>& slot_of = split_->split().separator_slot();
    std::vector<double>& share = split_->share(bd.separator_share);
    auto add = [&](std::size_t p, double term) {
      const int slot = slot_of[p];
      if (slot >= 0)
        share[static_cast<std::size_t>(slot)] += term;
      else
        values_[p] += term;
    };
    add_terms(bd, Ak, pos, scratch, add, W2_k);
    return;
  }
  if (bd.size == 1 && !W2_k) {
    const double w = packed_W2_[bd.w2_offset];
    for (std::size_t b = 0; b < r; ++b) {
      const double wb = w * Ak[b];
      for (std::size_t a = b; a < r; ++a) values_[static_cast<std::size_t>(*pos++)] += wb * Ak[a];
    }
    return;
  }
  add_terms(bd, Ak, pos, scratch, [this](std::size_t p, double term) { values_[p] += term; }, W2_k);
}

template <class Add>
void NormalEquations::add_terms(const BlockData& bd, const double* Ak, const int* pos,
                                std::vector<double>& scratch, const Add& add, const double* W2_k) {
  // B = A_k W²_k (r×q), then G = B A_kᵀ, lower triangle only.
  const Eigen::Index rr = static_cast<Eigen::Index>(bd.rows.size());
  Eigen::Map<const Eigen::MatrixXd> A_local(Ak, rr, bd.size);
  Eigen::Map<const Eigen::MatrixXd> W2(W2_k ? W2_k : packed_W2_.data() + bd.w2_offset, bd.size, bd.size);
  Eigen::Map<Eigen::MatrixXd> B(scratch.data(), rr, bd.size);
  B.noalias() = A_local * W2;
  for (Eigen::Index b = 0; b < rr; ++b) {
    for (Eigen::Index a = b; a < rr; ++a) {
      add(static_cast<std::size_t>(*pos++), B.row(a).dot(A_local.row(b)));
    }
  }
}

// The Schur complement's terms cancel much of M_KK's where W² is ill-conditioned (late in a
// solve), so M̃ is only the preconditioner: CG multiplies by the exact M. With SplitCholesky the
// separator–separator terms go to the block's share, as in assemble() (the split factor reads
// them there).
void NormalEquations::subtract_fixed_terms() {
  Eigen::MatrixXd removed;
  for (const FixedBlock& fb : fixed_blocks_) {
    const BlockData& bd = blocks_[static_cast<std::size_t>(fb.block)];
    const Eigen::Index e = static_cast<Eigen::Index>(fb.local.size());
    Eigen::Map<const Eigen::MatrixXd> W2(packed_W2_.data() + bd.w2_offset, bd.size, bd.size);
    Eigen::Map<const Eigen::MatrixXd> G(fixed_G_.data() + fb.G_offset, e, bd.size);
    removed.setZero(bd.size, bd.size);
    for (Eigen::Index a = 0; a < e; ++a) removed.noalias() -= W2.col(fb.local[static_cast<std::size_t>(a)]) * G.row(a);
    add_block(bd, scratch_[0], removed.data());
  }
  if (split_) sum_separator_shares();  // values_ agrees with the shares (the diagonal, δ)
}

void NormalEquations::solve_factor(double* x, int columns) { solver_->solve(x, columns); }

long NormalEquations::factor_nonzeros() const { return solver_->factor_nonzeros(); }
double NormalEquations::factor_bytes() const { return solver_->factor_bytes(); }
double NormalEquations::factor_flops() const { return solver_->factor_flops(); }
std::string NormalEquations::backend_name() const { return solver_->name(); }

void NormalEquations::solve_regularised(double* x, int columns) {
  num_factor_solves_ += columns;
  solve_factor(x, columns);
  if (!dense_blocks_.empty()) {
    Eigen::Map<Eigen::MatrixXd> solutions(x, m_, columns);
    const Eigen::MatrixXd w = dense_schur_.solve(dense_D_.transpose() * solutions);
    solutions.noalias() -= dense_Minv_D_ * w;
  }
}

void NormalEquations::solve_regularised(const Eigen::VectorXd& rhs, Eigen::VectorXd& out) {
  out = rhs;
  solve_regularised(out.data(), 1);
}

void NormalEquations::precondition(const Eigen::VectorXd& rhs, Eigen::VectorXd& out) {
  if (reduced_row_.empty()) {
    solve_regularised(rhs, out);
    return;
  }
  Eigen::VectorXd& reduced = reduced_scratch_[0];
  reduce(rhs, reduced);
  solve_regularised(reduced.data(), 1);
  expand(rhs, reduced, out);
}

void NormalEquations::solve_pair(const Eigen::VectorXd& rhs_a, const Eigen::VectorXd& rhs_b,
                                 Eigen::VectorXd& a, Eigen::VectorXd& b) {
  Eigen::MatrixXd both(m_, 2);
  if (reduced_row_.empty()) {
    both.col(0) = rhs_a;
    both.col(1) = rhs_b;
  } else {
    Eigen::VectorXd reduced;
    reduce(rhs_a, reduced);
    both.col(0) = reduced;
    reduce(rhs_b, reduced);
    both.col(1) = reduced;
  }
  solve_regularised(both.data(), 2);
  if (reduced_row_.empty()) {
    a = both.col(0);
    b = both.col(1);
  } else {
    expand(rhs_a, both.col(0), a);
    expand(rhs_b, both.col(1), b);
  }
}

void NormalEquations::multiply(const Eigen::VectorXd& v, Eigen::VectorXd& out) const {
  if (reduced_row_.empty())
    multiply_lower(values_, v, out);
  else
    multiply_full(v, out);
}

void NormalEquations::multiply_lower(const std::vector<double>& lower, const Eigen::VectorXd& v,
                                     Eigen::VectorXd& out) const {
  // M v from the lower triangle assembled for the last factorisation (exact M_s, the shift δ is
  // CHOLMOD's), plus A_k (W²_k (A_kᵀ v)) for the dense columns kept out of it. Called once per CG
  // step. Per block through A_k instead, a large share of a 3-D solve went there: every block
  // re-gathers the rows it touches, M's lower triangle visits each entry once.
  ++num_multiplies_;
  const int* col_ptr = col_ptr_.data();
  const int* row_ind = row_ind_.data();
  const double* values = lower.data();
  auto columns = [&](Eigen::Index begin, Eigen::Index end, Eigen::VectorXd& into) {
    into.setZero(m_);
    for (Eigen::Index j = begin; j < end; ++j) {
      const int first = col_ptr[j], last = col_ptr[j + 1];
      const double vj = v[j];
      double sum = values[first] * vj;  // the diagonal comes first in each column
      for (int p = first + 1; p < last; ++p) {
        const int i = row_ind[p];
        sum += values[p] * v[i];
        into[i] += values[p] * vj;
      }
      into[j] += sum;
    }
  };
  if (fork_join_) {
    // Half of the entries per thread, each scattering into its own vector.
    const std::function<void()> first = [&] { columns(0, multiply_split_, out); };
    const std::function<void()> second = [&] { columns(multiply_split_, m_, multiply_other_); };
    fork_join_->run(first, second);
    out += multiply_other_;
  } else {
    columns(0, m_, out);
  }
  for (int index : dense_blocks_) {
    const BlockData& bd = blocks_[static_cast<std::size_t>(index)];
    const std::size_t r = bd.rows.size();
    const double* Ak = local_A_.data() + bd.a_offset;  // r × 1
    double u = 0;
    for (std::size_t a = 0; a < r; ++a) u += Ak[a] * v[bd.rows[a]];
    u *= packed_W2_[bd.w2_offset];
    for (std::size_t a = 0; a < r; ++a) out[bd.rows[a]] += Ak[a] * u;
  }
}

int NormalEquations::solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& dy, int refine_max_iter,
                           double target) {
  // Preconditioned conjugate gradients on the exact M, preconditioned by the regularised factor
  // (M_s + δI with the dense-column bordering). Unlike plain iterative refinement (Richardson),
  // CG also converges when a few eigenvalues of the preconditioned operator are far from 1,
  // which is what δ does to the near-null directions of M late in the iteration.
  precondition(rhs, dy);
  if (refine_max_iter == 0) return 0;
  Eigen::VectorXd residual, product, preconditioned, direction;
  multiply(dy, product);
  residual = rhs - product;
  double residual_norm = residual.lpNorm<Eigen::Infinity>();
  if (residual_norm <= target) return 0;
  Eigen::VectorXd best = dy;
  double best_norm = residual_norm;
  precondition(residual, preconditioned);
  direction = preconditioned;
  double rz = residual.dot(preconditioned);
  int steps = 0;
  while (steps < refine_max_iter) {
    ++steps;
    multiply(direction, product);
    const double curvature = direction.dot(product);
    if (!(curvature > 0) || !(rz > 0)) break;
    const double step = rz / curvature;
    dy += step * direction;
    residual -= step * product;
    residual_norm = residual.lpNorm<Eigen::Infinity>();
    if (residual_norm < best_norm) {
      best = dy;
      best_norm = residual_norm;
    }
    if (residual_norm <= target) break;
    precondition(residual, preconditioned);
    const double rz_next = residual.dot(preconditioned);
    direction = preconditioned + (rz_next / rz) * direction;
    rz = rz_next;
  }
  dy.swap(best);
  return steps;
}

}  // namespace rbla::conic::detail
