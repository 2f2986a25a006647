#include "scaled_problem.hpp"

#include <algorithm>
#include <functional>

namespace rbla::conic::detail {

double inf_norm(const Vec& v) { return v.size() ? v.lpNorm<Eigen::Infinity>() : 0.0; }

void ScaledProblem::rescale(const ConicProblem& original, const Settings& settings,
                            const std::vector<ScalingBlock>& blocks) {
  if (settings.equilibrate) {
    equilibration_ = ruiz_equilibration(original.A, original.b, original.c, blocks,
                                        settings.equilibrate_max_iter,
                                        settings.equilibrate_min_scaling,
                                        settings.equilibrate_max_scaling);
  } else {
    equilibration_ = identity_equilibration(original.A.rows(), original.A.cols());
  }
  apply_equilibration(equilibration_, original.A, A_);
  if (fork_join_) {
    // Row-major copy for A v by rows; each thread takes rows (or, for Aᵀ v, columns) holding
    // half of the nonzeros.
    A_rows_ = A_;
    const auto half_of = [](const int* outer, Eigen::Index size) {
      const int half = outer[size] / 2;
      return static_cast<Eigen::Index>(std::lower_bound(outer, outer + size + 1, half) - outer);
    };
    row_split_ = half_of(A_rows_.outerIndexPtr(), A_rows_.outerSize());
    col_split_ = half_of(A_.outerIndexPtr(), A_.outerSize());
  }
  b_ = equilibration_.b_scale * equilibration_.row_scale.cwiseProduct(original.b);
  c_ = equilibration_.c_scale * equilibration_.col_scale.cwiseProduct(original.c);
}

// With two threads A v goes by the rows of A_rows_ and Aᵀ v by the columns of A_, both one dot
// product per compressed vector.
void ScaledProblem::multiply_A(const Vec& v, Vec& out) const {
  if (!fork_join_) {
    out.noalias() = A_ * v;
    return;
  }
  dot_each_vector(A_rows_, row_split_, v, out);
}

void ScaledProblem::multiply_At(const Vec& v, Vec& out) const {
  if (!fork_join_) {
    out.noalias() = A_.transpose() * v;
    return;
  }
  dot_each_vector(A_, col_split_, v, out);
}

// out[k] = (compressed vector k of S) · v, vectors [0, split) on this thread, the rest on the
// helper's.
template <class Sparse>
void ScaledProblem::dot_each_vector(const Sparse& S, Eigen::Index split, const Vec& v,
                                    Vec& out) const {
  const Eigen::Index count = S.outerSize();
  out.resize(count);
  const int* outer = S.outerIndexPtr();
  const int* inner = S.innerIndexPtr();
  const double* values = S.valuePtr();
  auto range = [&](Eigen::Index begin, Eigen::Index end) {
    for (Eigen::Index k = begin; k < end; ++k) {
      double sum = 0;
      for (int p = outer[k]; p < outer[k + 1]; ++p) sum += values[p] * v[inner[p]];
      out[k] = sum;
    }
  };
  const std::function<void()> first = [&] { range(0, split); };
  const std::function<void()> second = [&] { range(split, count); };
  fork_join_->run(first, second);
}

}  // namespace rbla::conic::detail
