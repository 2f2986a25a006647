#include <cmath>
#include <limits>
#include <numeric>

#include "cone.hpp"

namespace rbla::conic::detail {

SecondOrderCones::SecondOrderCones(Eigen::Index offset, const std::vector<Eigen::Index>& dims)
    : Cone(offset, std::accumulate(dims.begin(), dims.end(), Eigen::Index{0})),
      dims_(dims.begin(), dims.end()),
      beta_(dims.size(), 1.0),
      lambda_norm_(dims.size(), 1.0) {
  starts_.resize(dims.size() + 1, 0);
  for (std::size_t k = 0; k < dims.size(); ++k) starts_[k + 1] = starts_[k] + dims[k];
  wbar_ = Vec::Zero(dim());
  v_ = Vec::Zero(dim());
  lambda_ = Vec::Zero(dim());
  for (std::size_t k = 0; k < dims.size(); ++k) {
    wbar_[starts_[k]] = 1.0;
    v_[starts_[k]] = 1.0;
    lambda_[starts_[k]] = 1.0;
  }
}

double SecondOrderCones::jordan_norm(const double* v, int q) {
  double tail_sq = 0.0;
  for (int i = 1; i < q; ++i) tail_sq += v[i] * v[i];
  const double tail = std::sqrt(tail_sq);
  const double product = (v[0] - tail) * (v[0] + tail);
  if (!(v[0] > tail) || !(product > 0)) return -1.0;
  return std::sqrt(product);
}

void SecondOrderCones::set_identity(VecRef e) const {
  e.setZero();
  for (std::size_t k = 0; k < dims_.size(); ++k) e[starts_[k]] = 1.0;
}

bool SecondOrderCones::update_scaling(ConstVecRef x, ConstVecRef z) {
  for (std::size_t k = 0; k < dims_.size(); ++k) {
    const int q = dims_[k];
    const double* xk = x.data() + starts_[k];
    const double* zk = z.data() + starts_[k];
    const double x_norm = jordan_norm(xk, q);
    const double z_norm = jordan_norm(zk, q);
    if (x_norm <= 0 || z_norm <= 0) return false;
    double xz = 0.0;
    for (int i = 0; i < q; ++i) xz += xk[i] * zk[i];
    // x̄ = x / ‖x‖_J, z̄ = z / ‖z‖_J.
    const double gamma = std::sqrt(0.5 * (1.0 + xz / (x_norm * z_norm)));
    double* w = wbar_.data() + starts_[k];
    w[0] = (xk[0] / x_norm + zk[0] / z_norm) / (2.0 * gamma);
    for (int i = 1; i < q; ++i) w[i] = (xk[i] / x_norm - zk[i] / z_norm) / (2.0 * gamma);
    // Re-normalise so that w̄ᵀJw̄ = 1 holds to rounding (W's formulas depend on it).
    const double w_norm = jordan_norm(w, q);
    if (w_norm <= 0) return false;
    for (int i = 0; i < q; ++i) w[i] /= w_norm;
    double* v = v_.data() + starts_[k];
    const double v_scale = 1.0 / std::sqrt(2.0 * (w[0] + 1.0));
    v[0] = (w[0] + 1.0) * v_scale;
    for (int i = 1; i < q; ++i) v[i] = w[i] * v_scale;
    beta_[k] = std::sqrt(x_norm / z_norm);
    // λ = W z; CVXOPT computes the same quantity.
    double* lambda = lambda_.data() + starts_[k];
    double vz = 0.0;
    for (int i = 0; i < q; ++i) vz += v[i] * zk[i];
    lambda[0] = beta_[k] * (2.0 * vz * v[0] - zk[0]);
    for (int i = 1; i < q; ++i) lambda[i] = beta_[k] * (2.0 * vz * v[i] + zk[i]);
    lambda_norm_[k] = jordan_norm(lambda, q);
    if (!(lambda_norm_[k] > 0)) return false;
  }
  return true;
}

void SecondOrderCones::lambda(VecRef out) const { out = lambda_; }

void SecondOrderCones::mul_W(ConstVecRef v, VecRef out) const {
  // β (2 v (vᵀ·) − J ·)
  for (std::size_t k = 0; k < dims_.size(); ++k) {
    const int q = dims_[k];
    const double* a = v.data() + starts_[k];
    const double* sv = v_.data() + starts_[k];
    double* o = out.data() + starts_[k];
    double wv = 0.0;
    for (int i = 0; i < q; ++i) wv += sv[i] * a[i];
    const double beta = beta_[k];
    o[0] = beta * (2.0 * wv * sv[0] - a[0]);
    for (int i = 1; i < q; ++i) o[i] = beta * (2.0 * wv * sv[i] + a[i]);
  }
}

void SecondOrderCones::mul_Winv(ConstVecRef v, VecRef out) const {
  // β⁻¹ (2 J v (vᵀ J ·) − J ·)
  for (std::size_t k = 0; k < dims_.size(); ++k) {
    const int q = dims_[k];
    const double* a = v.data() + starts_[k];
    const double* sv = v_.data() + starts_[k];
    double* o = out.data() + starts_[k];
    double wJv = sv[0] * a[0];
    for (int i = 1; i < q; ++i) wJv -= sv[i] * a[i];
    const double inv_beta = 1.0 / beta_[k];
    o[0] = inv_beta * (2.0 * wJv * sv[0] - a[0]);
    for (int i = 1; i < q; ++i) o[i] = inv_beta * (a[i] - 2.0 * wJv * sv[i]);
  }
}

void SecondOrderCones::mul_W2(ConstVecRef v, VecRef out) const {
  // β² (2 w̄ (w̄ᵀv) − J v): the same arithmetic as the packed block the normal matrix uses, so
  // that iterative refinement on M and the recovered dx agree.
  for (std::size_t k = 0; k < dims_.size(); ++k) {
    const int q = dims_[k];
    const double* a = v.data() + starts_[k];
    const double* w = wbar_.data() + starts_[k];
    double* o = out.data() + starts_[k];
    const double beta2 = beta_[k] * beta_[k];
    double wv = 0.0;
    for (int i = 0; i < q; ++i) wv += w[i] * a[i];
    const double twice = 2.0 * beta2 * wv;
    o[0] = twice * w[0] - beta2 * a[0];
    for (int i = 1; i < q; ++i) o[i] = twice * w[i] + beta2 * a[i];
  }
}

void SecondOrderCones::jordan_product(ConstVecRef a, ConstVecRef b, VecRef out) const {
  // a ∘ b = (aᵀb, a₀ b₁ + b₀ a₁)
  for (std::size_t k = 0; k < dims_.size(); ++k) {
    const int q = dims_[k];
    const double* ak = a.data() + starts_[k];
    const double* bk = b.data() + starts_[k];
    double* o = out.data() + starts_[k];
    const double a0 = ak[0], b0 = bk[0];
    double first = 0.0;
    for (int i = 0; i < q; ++i) first += ak[i] * bk[i];
    for (int i = 1; i < q; ++i) o[i] = a0 * bk[i] + b0 * ak[i];
    o[0] = first;
  }
}

void SecondOrderCones::lambda_divide(ConstVecRef d, VecRef out) const {
  // λ ∘ v = d  ⇒  v₀ = (λ₀ d₀ − λ₁ᵀd₁) / det λ,  v₁ = (d₁ − v₀ λ₁) / λ₀   (CVXOPT sinv).
  for (std::size_t k = 0; k < dims_.size(); ++k) {
    const int q = dims_[k];
    const double* dk = d.data() + starts_[k];
    const double* l = lambda_.data() + starts_[k];
    double* o = out.data() + starts_[k];
    double tail_sq = 0.0, tail_dot = 0.0;
    for (int i = 1; i < q; ++i) {
      tail_sq += l[i] * l[i];
      tail_dot += l[i] * dk[i];
    }
    const double tail = std::sqrt(tail_sq);
    const double det = (l[0] - tail) * (l[0] + tail);
    const double v0 = (l[0] * dk[0] - tail_dot) / det;
    for (int i = 1; i < q; ++i) o[i] = (dk[i] - v0 * l[i]) / l[0];
    o[0] = v0;
  }
}

double SecondOrderCones::max_step(ConstVecRef v, ConstVecRef dv) const {
  double step = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < dims_.size(); ++k) {
    const int q = dims_[k];
    const double* vk = v.data() + starts_[k];
    const double v_norm = jordan_norm(vk, q);
    if (v_norm <= 0) return 0.0;
    step = std::min(step, step_to_boundary(vk, v_norm, dv.data() + starts_[k], q));
  }
  return step;
}

double SecondOrderCones::min_eigenvalue(ConstVecRef v) const {
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < dims_.size(); ++k) {
    const double* vk = v.data() + starts_[k];
    double tail_sq = 0.0;
    for (int i = 1; i < dims_[k]; ++i) tail_sq += vk[i] * vk[i];
    smallest = std::min(smallest, vk[0] - std::sqrt(tail_sq));
  }
  return smallest;
}

double SecondOrderCones::max_step_from_lambda(ConstVecRef dv) const {
  double step = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < dims_.size(); ++k) {
    step = std::min(step, step_to_boundary(lambda_.data() + starts_[k], lambda_norm_[k],
                                           dv.data() + starts_[k], dims_[k]));
  }
  return step;
}

void SecondOrderCones::append_steps_from_lambda(ConstVecRef dv, double limit,
                                                std::vector<double>& out) const {
  for (std::size_t k = 0; k < dims_.size(); ++k) {
    const double step = step_to_boundary(lambda_.data() + starts_[k], lambda_norm_[k],
                                         dv.data() + starts_[k], dims_[k]);
    if (step < limit) out.push_back(step);
  }
}

double SecondOrderCones::step_to_boundary(const double* v, double v_norm, const double* dv, int q) {
  // Map v to the identity e by the automorphism H(v̄)⁻¹ (v̄ = v/√det v); then
  // e + α ρ ∈ K  ⇔  α (‖ρ₁‖ − ρ₀) ≤ 1. Same formula as ECOS (conelp.c, lineSearch).
  const double inv = 1.0 / v_norm;
  const double vbar0 = v[0] * inv;
  double tail_dot = 0.0;
  for (int i = 1; i < q; ++i) tail_dot += v[i] * dv[i];
  const double rho0_unscaled = vbar0 * dv[0] - inv * tail_dot;
  const double factor = (rho0_unscaled + dv[0]) / (vbar0 + 1.0);
  const double rho0 = rho0_unscaled / v_norm;
  double rho1_sq = 0.0;
  for (int i = 1; i < q; ++i) {
    const double r = dv[i] - factor * inv * v[i];
    rho1_sq += r * r;
  }
  const double rho1_norm = std::sqrt(rho1_sq) / v_norm;
  const double excess = rho1_norm - rho0;
  return excess > 0 ? 1.0 / excess : std::numeric_limits<double>::infinity();
}

void SecondOrderCones::centrality_correction(ConstVecRef v, double lo, double hi,
                                             VecRef out) const {
  // v = e₋ u₋ + e₊ u₊ with e± = v₀ ± ‖v₁‖, u± = ½ (1, ±v₁/‖v₁‖); each eigenvalue moves alone.
  for (std::size_t k = 0; k < dims_.size(); ++k) {
    const int q = dims_[k];
    const double* vk = v.data() + starts_[k];
    double* o = out.data() + starts_[k];
    double r_sq = 0.0;
    for (int i = 1; i < q; ++i) r_sq += vk[i] * vk[i];
    const double r = std::sqrt(r_sq);
    const double t_minus = centrality_change(vk[0] - r, lo, hi);
    const double t_plus = centrality_change(vk[0] + r, lo, hi);
    o[0] = 0.5 * (t_minus + t_plus);
    const double tail_scale = r > 0 ? 0.5 * (t_plus - t_minus) / r : 0.0;
    for (int i = 1; i < q; ++i) o[i] = tail_scale * vk[i];
  }
}

void SecondOrderCones::append_scaling_blocks(std::vector<ScalingBlock>& blocks) const {
  for (std::size_t k = 0; k < dims_.size(); ++k)
    blocks.push_back({offset() + starts_[k], static_cast<Eigen::Index>(dims_[k])});
}

double* SecondOrderCones::pack_W2(double* out) const {
  // W² = β² (2 w̄ w̄ᵀ − J), column-major per cone.
  for (std::size_t k = 0; k < dims_.size(); ++k) {
    const int q = dims_[k];
    const double* w = wbar_.data() + starts_[k];
    const double beta2 = beta_[k] * beta_[k];
    for (int j = 0; j < q; ++j) {
      for (int i = 0; i < q; ++i) out[i + q * j] = 2.0 * beta2 * w[i] * w[j];
      out[j + q * j] += j == 0 ? -beta2 : beta2;
    }
    out += q * q;
  }
  return out;
}

}  // namespace rbla::conic::detail
