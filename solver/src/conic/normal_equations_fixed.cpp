// The fixed rows of NormalEquations: which rows they are, the Schur complement that removes them
// from M, and the reduction and recovery of right-hand sides and solutions (normal_equations.hpp).
#include <Eigen/Cholesky>

#include "normal_equations.hpp"

#include "fork_join.hpp"

#include <algorithm>
#include <functional>

namespace rbla::conic::detail {

// A row with one nonzero, in a column with no other nonzero, of a block that is not a dense
// column. At least one row stays (every row fixed would leave nothing to factor), and all stay
// when there are fewer than min_fixed_rows.
void NormalEquations::find_fixed_rows(const Eigen::SparseMatrix<double>& A,
                                      const std::vector<ScalingBlock>& blocks,
                                      const std::vector<bool>& is_dense_column, int min_fixed_rows) {
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  std::vector<int> row_count(static_cast<std::size_t>(full_m_), 0);
  for (Eigen::Index p = 0; p < A.nonZeros(); ++p) ++row_count[static_cast<std::size_t>(inner[p])];
  std::vector<int> fixed_column(static_cast<std::size_t>(full_m_), -1);
  int num_fixed = 0;
  for (const ScalingBlock& sb : blocks) {
    for (Eigen::Index j = sb.first; j < sb.first + sb.size; ++j) {
      if (outer[j + 1] - outer[j] != 1 || is_dense_column[static_cast<std::size_t>(j)]) continue;
      const int row = inner[outer[j]];
      if (row_count[static_cast<std::size_t>(row)] != 1) continue;
      fixed_column[static_cast<std::size_t>(row)] = static_cast<int>(j);
      ++num_fixed;
    }
  }
  if (num_fixed == 0 || num_fixed < min_fixed_rows || num_fixed == full_m_) return;
  reduced_row_.assign(static_cast<std::size_t>(full_m_), 0);
  int kept = 0, fixed = 0;
  for (std::size_t i = 0; i < reduced_row_.size(); ++i)
    reduced_row_[i] = fixed_column[i] < 0 ? kept++ : -1 - fixed++;
  m_ = kept;
  fixed_a_.assign(static_cast<std::size_t>(num_fixed), 0.0);
  // One FixedBlock per block with fixed coordinates, in block order.
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    const ScalingBlock& sb = blocks[k];
    FixedBlock fb;
    fb.block = static_cast<int>(k);
    for (Eigen::Index j = sb.first; j < sb.first + sb.size; ++j) {
      if (outer[j + 1] - outer[j] != 1) continue;
      const int row = inner[outer[j]];
      if (fixed_column[static_cast<std::size_t>(row)] != j) continue;
      fb.local.push_back(static_cast<int>(j - sb.first));
      fb.rows.push_back(row);
      fb.a_at.push_back(-1 - reduced_row_[static_cast<std::size_t>(row)]);
    }
    if (fb.local.empty()) continue;
    const std::size_t e = fb.local.size();
    fb.G_offset = fixed_G_.size();
    fb.EE_offset = fixed_EE_inverse_.size();
    fixed_G_.resize(fixed_G_.size() + e * static_cast<std::size_t>(sb.size));
    fixed_EE_inverse_.resize(fixed_EE_inverse_.size() + e * e);
    max_block_size_ = std::max(max_block_size_, static_cast<int>(sb.size));
    fixed_blocks_.push_back(std::move(fb));
  }
}

bool NormalEquations::eliminate_fixed() {
  for (FixedBlock& fb : fixed_blocks_) {
    for (int t : fb.a_at) {
      if (fixed_a_[static_cast<std::size_t>(t)] == 0.0) return false;
    }
    const BlockData& bd = blocks_[static_cast<std::size_t>(fb.block)];
    const int q = bd.size;
    const double* W2 = packed_W2_.data() + bd.w2_offset;  // column-major, symmetric
    double* G = fixed_G_.data() + fb.G_offset;
    double* EE_inverse = fixed_EE_inverse_.data() + fb.EE_offset;
    if (fb.local.size() == 1) {  // one fixed coordinate (a capped cone's radius): no allocation
      const int e = fb.local[0];
      const double pivot = W2[e + q * e];
      if (!(pivot > 0.0)) return false;
      EE_inverse[0] = 1.0 / pivot;
      for (int j = 0; j < q; ++j) G[j] = W2[e + q * j] / pivot;
      continue;
    }
    const Eigen::Index e = static_cast<Eigen::Index>(fb.local.size());
    Eigen::MatrixXd EE(e, e), E_rows(e, q);
    for (Eigen::Index a = 0; a < e; ++a) {
      const int row = fb.local[static_cast<std::size_t>(a)];
      for (int j = 0; j < q; ++j) E_rows(a, j) = W2[row + q * j];
      for (Eigen::Index b = 0; b < e; ++b) EE(a, b) = E_rows(a, fb.local[static_cast<std::size_t>(b)]);
    }
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(EE);
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0.0)) return false;
    Eigen::Map<Eigen::MatrixXd>(EE_inverse, e, e) = ldlt.solve(Eigen::MatrixXd::Identity(e, e));
    Eigen::Map<Eigen::MatrixXd>(G, e, q) = ldlt.solve(E_rows);
  }
  return true;
}

void NormalEquations::block_At(const BlockData& bd, const Eigen::VectorXd& v, double* t) const {
  const std::size_t r = bd.rows.size();
  const double* Ak = local_A_.data() + bd.a_offset;  // r × q, column-major
  for (int j = 0; j < bd.size; ++j) {
    if (j == bd.fixed_column) {  // zero on the rows that are not fixed
      t[j] = 0.0;
      continue;
    }
    double sum = 0.0;
    for (std::size_t a = 0; a < r; ++a) sum += Ak[a + r * static_cast<std::size_t>(j)] * v[bd.rows[a]];
    t[j] = sum;
  }
}

void NormalEquations::add_block_A(const BlockData& bd, const double* g, Eigen::VectorXd& out) const {
  const std::size_t r = bd.rows.size();
  const double* Ak = local_A_.data() + bd.a_offset;
  for (int j = 0; j < bd.size; ++j) {
    if (g[j] == 0.0 || j == bd.fixed_column) continue;
    for (std::size_t a = 0; a < r; ++a) out[bd.rows[a]] += Ak[a + r * static_cast<std::size_t>(j)] * g[j];
  }
}

void NormalEquations::fixed_rhs(const FixedBlock& fb, const Eigen::VectorXd& full, double* u) const {
  for (std::size_t e = 0; e < fb.rows.size(); ++e)
    u[e] = full[fb.rows[e]] / fixed_a_[static_cast<std::size_t>(fb.a_at[e])];
}

void NormalEquations::gather_free(const Eigen::VectorXd& full, Eigen::VectorXd& free) const {
  free.resize(m_);
  for (std::size_t i = 0; i < reduced_row_.size(); ++i) {
    if (reduced_row_[i] >= 0) free[reduced_row_[i]] = full[static_cast<Eigen::Index>(i)];
  }
}

void NormalEquations::scatter_free(const Eigen::VectorXd& free, Eigen::VectorXd& full) const {
  full.resize(full_m_);
  for (std::size_t i = 0; i < reduced_row_.size(); ++i) {
    if (reduced_row_[i] >= 0) full[static_cast<Eigen::Index>(i)] = free[reduced_row_[i]];
  }
}

void NormalEquations::for_fixed_halves(const std::function<void(std::size_t, std::size_t, int)>& work) const {
  const std::size_t n = fixed_blocks_.size();
  if (!fork_join_) {
    work(0, n, 0);
    return;
  }
  const std::function<void()> first = [&] { work(0, n / 2, 0); };
  const std::function<void()> second = [&] { work(n / 2, n, 1); };
  fork_join_->run(first, second);
}

// r̃ = r_K − Σ A_R Gᵀ (r_E / a). With fork_join_ the second half of the fixed blocks adds into
// a vector of its own (blocks of the two halves share rows), summed after.
void NormalEquations::reduce(const Eigen::VectorXd& full, Eigen::VectorXd& reduced) const {
  gather_free(full, reduced);
  Eigen::VectorXd& other = reduced_scratch_[3];
  if (fork_join_) other.setZero(m_);
  for_fixed_halves([&](std::size_t begin, std::size_t end, int half) {
    Eigen::VectorXd& into = half == 0 ? reduced : other;
    std::vector<double> u(static_cast<std::size_t>(max_block_size_)), g(static_cast<std::size_t>(max_block_size_));
    for (std::size_t k = begin; k < end; ++k) {
      const FixedBlock& fb = fixed_blocks_[k];
      const BlockData& bd = blocks_[static_cast<std::size_t>(fb.block)];
      const std::size_t e = fb.rows.size();
      const double* G = fixed_G_.data() + fb.G_offset;
      fixed_rhs(fb, full, u.data());
      for (int j = 0; j < bd.size; ++j) {
        double sum = 0.0;
        for (std::size_t a = 0; a < e; ++a) sum += G[a + e * static_cast<std::size_t>(j)] * u[a];
        g[static_cast<std::size_t>(j)] = -sum;
      }
      add_block_A(bd, g.data(), into);
    }
  });
  if (fork_join_) reduced += other;
}

// dy_K from the reduced solve; dy_E = ((W²_EE)⁻¹ (r_E / a) − G A_Rᵀ dy_K) / a. Each fixed block
// writes only its own rows, so the two halves run on two threads without sharing.
void NormalEquations::expand(const Eigen::VectorXd& full_rhs, const Eigen::VectorXd& reduced,
                             Eigen::VectorXd& full) const {
  scatter_free(reduced, full);
  for_fixed_halves([&](std::size_t begin, std::size_t end, int) {
    std::vector<double> u(static_cast<std::size_t>(max_block_size_)), t(static_cast<std::size_t>(max_block_size_));
    for (std::size_t k = begin; k < end; ++k) {
      const FixedBlock& fb = fixed_blocks_[k];
      const BlockData& bd = blocks_[static_cast<std::size_t>(fb.block)];
      const std::size_t e = fb.rows.size();
      const double* G = fixed_G_.data() + fb.G_offset;
      const double* EE_inverse = fixed_EE_inverse_.data() + fb.EE_offset;
      fixed_rhs(fb, full_rhs, u.data());
      block_At(bd, reduced, t.data());
      for (std::size_t a = 0; a < e; ++a) {
        double dy = 0.0;
        for (std::size_t b = 0; b < e; ++b) dy += EE_inverse[a + e * b] * u[b];
        for (int j = 0; j < bd.size; ++j) dy -= G[a + e * static_cast<std::size_t>(j)] * t[static_cast<std::size_t>(j)];
        full[fb.rows[a]] = dy / fixed_a_[static_cast<std::size_t>(fb.a_at[a])];
      }
    }
  });
}

// M_KK v_K from exact_values_; with t = A_Rᵀ v_K and w = a v_E, a fixed block adds its coupling
// A_R W²_{:E} w to the free rows, and its fixed rows are a (W²_{E:} t + W²_EE w).
void NormalEquations::multiply_full(const Eigen::VectorXd& v, Eigen::VectorXd& out) const {
  Eigen::VectorXd& v_free = reduced_scratch_[1];
  Eigen::VectorXd& out_free = reduced_scratch_[2];
  gather_free(v, v_free);
  multiply_lower(exact_values_, v_free, out_free);
  out.resize(full_m_);
  const std::size_t size = static_cast<std::size_t>(max_block_size_);
  std::vector<double> t(size), w(size), coupling(size);
  for (const FixedBlock& fb : fixed_blocks_) {
    const BlockData& bd = blocks_[static_cast<std::size_t>(fb.block)];
    const int q = bd.size;
    const std::size_t e = fb.rows.size();
    const double* W2 = packed_W2_.data() + bd.w2_offset;
    for (std::size_t a = 0; a < e; ++a) w[a] = fixed_a_[static_cast<std::size_t>(fb.a_at[a])] * v[fb.rows[a]];
    block_At(bd, v_free, t.data());
    for (int j = 0; j < q; ++j) {
      double sum = 0.0;
      for (std::size_t a = 0; a < e; ++a) sum += W2[j + q * fb.local[a]] * w[a];
      coupling[static_cast<std::size_t>(j)] = sum;
    }
    add_block_A(bd, coupling.data(), out_free);
    for (std::size_t a = 0; a < e; ++a) {
      const int row = fb.local[a];
      double sum = 0.0;
      for (int j = 0; j < q; ++j) sum += W2[row + q * j] * t[static_cast<std::size_t>(j)];
      for (std::size_t b = 0; b < e; ++b) sum += W2[row + q * fb.local[b]] * w[b];
      out[fb.rows[a]] = fixed_a_[static_cast<std::size_t>(fb.a_at[a])] * sum;
    }
  }
  for (std::size_t i = 0; i < reduced_row_.size(); ++i) {  // out already holds the fixed rows
    if (reduced_row_[i] >= 0) out[static_cast<Eigen::Index>(i)] = out_free[reduced_row_[i]];
  }
}

}  // namespace rbla::conic::detail
