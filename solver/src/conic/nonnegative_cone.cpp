#include <cmath>
#include <limits>

#include "cone.hpp"

namespace rbla::conic::detail {

NonnegativeCone::NonnegativeCone(Eigen::Index offset, Eigen::Index dim)
    : Cone(offset, dim), w_(Vec::Ones(dim)), lambda_(Vec::Ones(dim)) {}

void NonnegativeCone::set_identity(VecRef e) const { e.setOnes(); }

bool NonnegativeCone::update_scaling(ConstVecRef x, ConstVecRef z) {
  for (Eigen::Index i = 0; i < dim(); ++i) {
    if (!(x[i] > 0) || !(z[i] > 0)) return false;
    w_[i] = std::sqrt(x[i] / z[i]);
    lambda_[i] = std::sqrt(x[i] * z[i]);
  }
  return true;
}

void NonnegativeCone::lambda(VecRef out) const { out = lambda_; }
void NonnegativeCone::mul_W(ConstVecRef v, VecRef out) const { out = w_.cwiseProduct(v); }
void NonnegativeCone::mul_Winv(ConstVecRef v, VecRef out) const { out = v.cwiseQuotient(w_); }
void NonnegativeCone::mul_W2(ConstVecRef v, VecRef out) const {
  out = w_.cwiseProduct(w_).cwiseProduct(v);
}
void NonnegativeCone::jordan_product(ConstVecRef a, ConstVecRef b, VecRef out) const {
  out = a.cwiseProduct(b);
}
void NonnegativeCone::lambda_divide(ConstVecRef d, VecRef out) const {
  out = d.cwiseQuotient(lambda_);
}

double NonnegativeCone::max_step(ConstVecRef v, ConstVecRef dv) const {
  double step = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < dim(); ++i) {
    if (dv[i] < 0) step = std::min(step, -v[i] / dv[i]);
  }
  return step;
}

void NonnegativeCone::append_steps_from_lambda(ConstVecRef dv, double limit,
                                               std::vector<double>& out) const {
  for (Eigen::Index i = 0; i < dim(); ++i) {
    if (dv[i] >= 0) continue;
    const double step = -lambda_[i] / dv[i];
    if (step < limit) out.push_back(step);
  }
}

void NonnegativeCone::centrality_correction(ConstVecRef v, double lo, double hi,
                                            VecRef out) const {
  for (Eigen::Index i = 0; i < dim(); ++i) out[i] = centrality_change(v[i], lo, hi);
}

void NonnegativeCone::append_scaling_blocks(std::vector<ScalingBlock>& blocks) const {
  for (Eigen::Index i = 0; i < dim(); ++i) blocks.push_back({offset() + i, 1});
}

double* NonnegativeCone::pack_W2(double* out) const {
  for (Eigen::Index i = 0; i < dim(); ++i) *out++ = w_[i] * w_[i];
  return out;
}

}  // namespace rbla::conic::detail
