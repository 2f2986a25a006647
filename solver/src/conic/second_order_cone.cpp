#include <cmath>
#include <limits>

#include "cone.hpp"

namespace rbla::conic::detail {

SecondOrderCone::SecondOrderCone(Eigen::Index offset, Eigen::Index dim)
    : Cone(offset, dim), wbar_(Vec::Zero(dim)), v_(Vec::Zero(dim)), lambda_(Vec::Zero(dim)) {
  wbar_[0] = 1.0;
  v_[0] = 1.0;
  lambda_[0] = 1.0;
}

void SecondOrderCone::set_identity(VecRef e) const {
  e.setZero();
  e[0] = 1.0;
}

double SecondOrderCone::jordan_norm(ConstVecRef v) {
  const double tail = v.tail(v.size() - 1).norm();
  const double product = (v[0] - tail) * (v[0] + tail);
  if (!(v[0] > tail) || !(product > 0)) return -1.0;
  return std::sqrt(product);
}

bool SecondOrderCone::update_scaling(ConstVecRef x, ConstVecRef z) {
  const Eigen::Index q = dim();
  const double x_norm = jordan_norm(x);
  const double z_norm = jordan_norm(z);
  if (x_norm <= 0 || z_norm <= 0) return false;
  // x̄ = x / ‖x‖_J, z̄ = z / ‖z‖_J, without temporaries (see max_step).
  const double gamma = std::sqrt(0.5 * (1.0 + x.dot(z) / (x_norm * z_norm)));
  wbar_[0] = (x[0] / x_norm + z[0] / z_norm) / (2.0 * gamma);
  wbar_.tail(q - 1) = (x.tail(q - 1) / x_norm - z.tail(q - 1) / z_norm) / (2.0 * gamma);
  // Re-normalise so that w̄ᵀJw̄ = 1 holds to rounding (W's formulas depend on it).
  const double w_norm = jordan_norm(wbar_);
  if (w_norm <= 0) return false;
  wbar_ /= w_norm;
  v_ = wbar_;
  v_[0] += 1.0;
  v_ /= std::sqrt(2.0 * (wbar_[0] + 1.0));
  beta_ = std::sqrt(x_norm / z_norm);
  // λ = W z; CVXOPT computes the same quantity.
  mul_W(z, lambda_);
  lambda_norm_ = jordan_norm(lambda_);
  return lambda_norm_ > 0;
}

void SecondOrderCone::lambda(VecRef out) const { out = lambda_; }

void SecondOrderCone::mul_W(ConstVecRef v, VecRef out) const {
  // β (2 v (vᵀ·) − J ·)
  const double wv = v_.dot(v);
  out = 2.0 * wv * v_;
  out[0] -= v[0];
  out.tail(dim() - 1) += v.tail(dim() - 1);
  out *= beta_;
}

void SecondOrderCone::mul_Winv(ConstVecRef v, VecRef out) const {
  // β⁻¹ (2 J v_ (v_ᵀ J ·) − J ·)
  const Eigen::Index q = dim();
  const double wJv = v_[0] * v[0] - v_.tail(q - 1).dot(v.tail(q - 1));
  out[0] = 2.0 * wJv * v_[0] - v[0];
  out.tail(q - 1) = -2.0 * wJv * v_.tail(q - 1) + v.tail(q - 1);
  out /= beta_;
}

void SecondOrderCone::mul_W2(ConstVecRef v, VecRef out) const {
  // β² (2 w̄ (w̄ᵀv) − J v): the same arithmetic as the packed block the normal matrix uses, so
  // that iterative refinement on M and the recovered dx agree.
  const double beta2 = beta_ * beta_;
  const double wv = wbar_.dot(v);
  out = (2.0 * beta2 * wv) * wbar_;
  out[0] -= beta2 * v[0];
  out.tail(dim() - 1) += beta2 * v.tail(dim() - 1);
}

void SecondOrderCone::jordan_product(ConstVecRef a, ConstVecRef b, VecRef out) const {
  // a ∘ b = (aᵀb, a₀ b₁ + b₀ a₁)
  const Eigen::Index q = dim();
  const double first = a.dot(b);
  out.tail(q - 1) = a[0] * b.tail(q - 1) + b[0] * a.tail(q - 1);
  out[0] = first;
}

void SecondOrderCone::lambda_divide(ConstVecRef d, VecRef out) const {
  // λ ∘ v = d  ⇒  v₀ = (λ₀ d₀ − λ₁ᵀd₁) / det λ,  v₁ = (d₁ − v₀ λ₁) / λ₀   (CVXOPT sinv).
  const Eigen::Index q = dim();
  const double l0 = lambda_[0];
  const double det = (l0 - lambda_.tail(q - 1).norm()) * (l0 + lambda_.tail(q - 1).norm());
  const double v0 = (l0 * d[0] - lambda_.tail(q - 1).dot(d.tail(q - 1))) / det;
  out.tail(q - 1) = (d.tail(q - 1) - v0 * lambda_.tail(q - 1)) / l0;
  out[0] = v0;
}

double SecondOrderCone::max_step(ConstVecRef v, ConstVecRef dv) const {
  // Map v to the identity e by the automorphism H(v̄)⁻¹ (v̄ = v/√det v); then
  // e + α ρ ∈ K  ⇔  α (‖ρ₁‖ − ρ₀) ≤ 1. Same formula as ECOS (conelp.c, lineSearch).
  // No temporaries: called for every cone several times per iteration (22524 cones on the
  // façade), where a heap vector per call was a measurable share of the iteration.
  const double v_norm = jordan_norm(v);
  if (v_norm <= 0) return 0.0;
  return step_to_boundary(v, v_norm, dv);
}

double SecondOrderCone::step_to_boundary(ConstVecRef v, double v_norm, ConstVecRef dv) {
  const Eigen::Index q = v.size();
  const double inv = 1.0 / v_norm;
  const double vbar0 = v[0] * inv;
  const double rho0_unscaled = vbar0 * dv[0] - inv * v.tail(q - 1).dot(dv.tail(q - 1));
  const double factor = (rho0_unscaled + dv[0]) / (vbar0 + 1.0);
  const double rho0 = rho0_unscaled / v_norm;
  double rho1_sq = 0.0;
  for (Eigen::Index i = 1; i < q; ++i) {
    const double r = dv[i] - factor * inv * v[i];
    rho1_sq += r * r;
  }
  const double rho1_norm = std::sqrt(rho1_sq) / v_norm;
  const double excess = rho1_norm - rho0;
  return excess > 0 ? 1.0 / excess : std::numeric_limits<double>::infinity();
}

void SecondOrderCone::centrality_correction(ConstVecRef v, double lo, double hi,
                                            VecRef out) const {
  // v = e₋ u₋ + e₊ u₊ with e± = v₀ ± ‖v₁‖, u± = ½ (1, ±v₁/‖v₁‖); each eigenvalue moves alone.
  const Eigen::Index q = dim();
  const double r = v.tail(q - 1).norm();
  const double t_minus = centrality_change(v[0] - r, lo, hi);
  const double t_plus = centrality_change(v[0] + r, lo, hi);
  out[0] = 0.5 * (t_minus + t_plus);
  if (r > 0) {
    out.tail(q - 1) = (0.5 * (t_plus - t_minus) / r) * v.tail(q - 1);
  } else {
    out.tail(q - 1).setZero();
  }
}

void SecondOrderCone::append_scaling_blocks(std::vector<ScalingBlock>& blocks) const {
  blocks.push_back({offset(), dim()});
}

double* SecondOrderCone::pack_W2(double* out) const {
  // W² = β² (2 w̄ w̄ᵀ − J).
  const Eigen::Index q = dim();
  const double beta2 = beta_ * beta_;
  Eigen::Map<Eigen::MatrixXd> block(out, q, q);
  block.noalias() = (2.0 * beta2) * wbar_ * wbar_.transpose();
  block(0, 0) -= beta2;
  for (Eigen::Index i = 1; i < q; ++i) block(i, i) += beta2;
  return out + q * q;
}

}  // namespace rbla::conic::detail
