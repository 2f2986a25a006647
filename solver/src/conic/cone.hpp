#pragma once
// Small interface each cone implements (Clarabel's cones/ layout). All vectors are this cone's
// segment of a global vector. Notation (Vandenberghe, "The CVXOPT linear and quadratic cone
// program solvers", 2010, §4): the Nesterov–Todd scaling W of the pair (x, z) satisfies
//   λ = W z = W⁻¹ x   (W symmetric positive definite, W K = K),
// and the linearised complementarity is  λ ∘ (W dz + W⁻¹ dx) = d,  "∘" the Jordan product.

#include <Eigen/Core>
#include <algorithm>
#include <memory>
#include <vector>

#include "fork_join.hpp"

namespace rbla::conic::detail {

using Vec = Eigen::VectorXd;
using VecRef = Eigen::Ref<Eigen::VectorXd>;
using ConstVecRef = Eigen::Ref<const Eigen::VectorXd>;

/// A group of variables whose W² is one dense block (an SOC; a single nonnegative variable).
struct ScalingBlock {
  Eigen::Index first = 0;  ///< first variable (global index)
  Eigen::Index size = 0;
};

class Cone {
 public:
  Cone(Eigen::Index offset, Eigen::Index dim) : offset_(offset), dim_(dim) {}
  virtual ~Cone() = default;
  Eigen::Index offset() const { return offset_; }
  Eigen::Index dim() const { return dim_; }

  virtual Eigen::Index degree() const = 0;
  virtual void set_identity(VecRef e) const = 0;
  /// Computes W and λ from interior x, z; false if either is not strictly interior.
  virtual bool update_scaling(ConstVecRef x, ConstVecRef z) = 0;
  virtual void lambda(VecRef out) const = 0;
  virtual void mul_W(ConstVecRef v, VecRef out) const = 0;
  virtual void mul_Winv(ConstVecRef v, VecRef out) const = 0;
  virtual void mul_W2(ConstVecRef v, VecRef out) const = 0;
  /// out = a ∘ b.
  virtual void jordan_product(ConstVecRef a, ConstVecRef b, VecRef out) const = 0;
  /// out = λ \ d, i.e. the v with λ ∘ v = d.
  virtual void lambda_divide(ConstVecRef d, VecRef out) const = 0;
  /// Largest α ≥ 0 with v + α dv ∈ K for interior v (+inf if unbounded).
  virtual double max_step(ConstVecRef v, ConstVecRef dv) const = 0;
  /// Smallest eigenvalue of v over this cone's factors (v_i for R_+, v₀ − ‖v₁‖ for an SOC):
  /// v + t e is interior exactly when t > −min_eigenvalue(v).
  virtual double min_eigenvalue(ConstVecRef v) const = 0;
  /// max_step(λ, dv) for the λ of the last update_scaling, with what depends on λ alone cached
  /// (the solver asks this several times per iteration for every cone).
  virtual double max_step_from_lambda(ConstVecRef dv) const = 0;
  /// Appends, for each factor (an entry of R_+, a second-order cone) whose boundary the step
  /// λ + α dv reaches at some α < limit, that α.
  virtual void append_steps_from_lambda(ConstVecRef dv, double limit, std::vector<double>& out) const = 0;
  /// Gondzio's centrality target for a trial complementarity product v: out = P(v) − v, where P
  /// moves each eigenvalue of v (each entry for R_+; v₀ ± ‖v₁‖ along v's own spectral frame for
  /// an SOC) into [lo, hi]; a decrease is capped at −hi (Gondzio 1996, §3).
  virtual void centrality_correction(ConstVecRef v, double lo, double hi, VecRef out) const = 0;
  virtual void append_scaling_blocks(std::vector<ScalingBlock>& blocks) const = 0;
  /// Writes the dense W² of each of this cone's blocks, column-major, consecutively.
  virtual double* pack_W2(double* out) const = 0;

 private:
  Eigen::Index offset_;
  Eigen::Index dim_;
};

/// Gondzio's projection of one eigenvalue into [lo, hi], as a change, never below −hi.
inline double centrality_change(double eigenvalue, double lo, double hi) {
  if (eigenvalue < lo) return lo - eigenvalue;
  if (eigenvalue > hi) return std::max(hi - eigenvalue, -hi);
  return 0.0;
}

/// R_+^n: W = diag(√(x/z)), λ = √(x z), Jordan product = elementwise product.
class NonnegativeCone final : public Cone {
 public:
  NonnegativeCone(Eigen::Index offset, Eigen::Index dim);
  Eigen::Index degree() const override { return dim(); }
  void set_identity(VecRef e) const override;
  bool update_scaling(ConstVecRef x, ConstVecRef z) override;
  void lambda(VecRef out) const override;
  void mul_W(ConstVecRef v, VecRef out) const override;
  void mul_Winv(ConstVecRef v, VecRef out) const override;
  void mul_W2(ConstVecRef v, VecRef out) const override;
  void jordan_product(ConstVecRef a, ConstVecRef b, VecRef out) const override;
  void lambda_divide(ConstVecRef d, VecRef out) const override;
  double max_step(ConstVecRef v, ConstVecRef dv) const override;
  double min_eigenvalue(ConstVecRef v) const override { return v.minCoeff(); }
  double max_step_from_lambda(ConstVecRef dv) const override { return max_step(lambda_, dv); }
  void append_steps_from_lambda(ConstVecRef dv, double limit, std::vector<double>& out) const override;
  void centrality_correction(ConstVecRef v, double lo, double hi, VecRef out) const override;
  void append_scaling_blocks(std::vector<ScalingBlock>& blocks) const override;
  double* pack_W2(double* out) const override;

 private:
  Vec w_;  // diagonal of W
  Vec lambda_;
};

/// Q^q = {(t, u) : ‖u‖ ≤ t}, J = diag(1, −1, …, −1), det v = vᵀJv.
/// NT scaling (CVXOPT doc §4.2): x̄ = x/√det x, z̄ = z/√det z, γ = √((1 + x̄ᵀz̄)/2),
/// w̄ = (x̄ + J z̄)/(2γ) (so w̄ᵀJw̄ = 1), β = (det x / det z)^¼, and its Jordan square root
/// v = (w̄ + e)/√(2(w̄₀ + 1)) (CVXOPT stores this v):
/// W = β (2 v vᵀ − J),  W⁻¹ = β⁻¹ (2 J v vᵀ J − J),  W² = β² (2 w̄ w̄ᵀ − J).
///
/// One object holds a whole run of consecutive cones Q^{q₁} × … × Q^{q_k}, their w̄, v and λ
/// stored flat in the variables' order: a façade has ~22500 three-dimensional friction cones,
/// and one object (and one virtual call, one heap vector) per cone cost more than the
/// arithmetic: the cone operations took ~15 % of an interior-point run that way.
class SecondOrderCones final : public Cone {
 public:
  SecondOrderCones(Eigen::Index offset, const std::vector<Eigen::Index>& dims);
  Eigen::Index degree() const override { return static_cast<Eigen::Index>(dims_.size()); }
  void set_identity(VecRef e) const override;
  bool update_scaling(ConstVecRef x, ConstVecRef z) override;
  void lambda(VecRef out) const override;
  void mul_W(ConstVecRef v, VecRef out) const override;
  void mul_Winv(ConstVecRef v, VecRef out) const override;
  void mul_W2(ConstVecRef v, VecRef out) const override;
  void jordan_product(ConstVecRef a, ConstVecRef b, VecRef out) const override;
  void lambda_divide(ConstVecRef d, VecRef out) const override;
  double max_step(ConstVecRef v, ConstVecRef dv) const override;
  double min_eigenvalue(ConstVecRef v) const override;
  double max_step_from_lambda(ConstVecRef dv) const override;
  void append_steps_from_lambda(ConstVecRef dv, double limit, std::vector<double>& out) const override;
  void centrality_correction(ConstVecRef v, double lo, double hi, VecRef out) const override;
  void append_scaling_blocks(std::vector<ScalingBlock>& blocks) const override;
  double* pack_W2(double* out) const override;

  /// √(v₀² − ‖v₁‖²) computed as √((v₀ − ‖v₁‖)(v₀ + ‖v₁‖)); ≤ 0 → returns −1 (not interior).
  static double jordan_norm(const double* v, int q);
  static double jordan_norm(ConstVecRef v) { return jordan_norm(v.data(), static_cast<int>(v.size())); }
  /// Largest α with v + α dv ∈ Q^q, for interior v with v_norm = jordan_norm(v) > 0.
  static double step_to_boundary(const double* v, double v_norm, const double* dv, int q);

 private:
  std::vector<int> dims_;
  std::vector<Eigen::Index> starts_;  // cone k is [starts_[k], starts_[k + 1]) of this run
  Vec wbar_;
  Vec v_;
  Vec lambda_;
  std::vector<double> beta_;
  std::vector<double> lambda_norm_;  // jordan_norm of each cone's λ
};

/// The product cone in variable order, with whole-vector versions of the cone operations.
class ConeSet {
 public:
  ConeSet() = default;
  /// fork_join (may be null): with many second-order cones, half of them are worked on by its
  /// helper thread.
  ConeSet(Eigen::Index num_nonneg, const std::vector<Eigen::Index>& soc_dims,
          ForkJoin* fork_join = nullptr);
  Eigen::Index dim() const { return dim_; }
  Eigen::Index degree() const { return degree_; }
  const std::vector<std::unique_ptr<Cone>>& cones() const { return cones_; }

  void set_identity(VecRef e) const;
  bool update_scaling(const Vec& x, const Vec& z);
  void lambda(Vec& out) const;
  void mul_W(const Vec& v, Vec& out) const;
  void mul_Winv(const Vec& v, Vec& out) const;
  void mul_W2(const Vec& v, Vec& out) const;
  void jordan_product(const Vec& a, const Vec& b, Vec& out) const;
  void lambda_divide(const Vec& d, Vec& out) const;
  double max_step(const Vec& v, const Vec& dv) const;
  double min_eigenvalue(const Vec& v) const;
  double max_step_from_lambda(const Vec& dv) const;
  /// Each factor's step to its boundary along dv from λ, those below `limit` (Cone's).
  void append_steps_from_lambda(const Vec& dv, double limit, std::vector<double>& out) const;
  void centrality_correction(const Vec& v, double lo, double hi, Vec& out) const;
  std::vector<ScalingBlock> scaling_blocks() const;
  void pack_W2(std::vector<double>& out) const;  ///< out must be sized Σ block size²

 private:
  /// f(i) for every cone i, those from split_at_ on by the helper thread when there is one.
  template <class F>
  void for_each_cone(const F& f) const;

  std::vector<std::unique_ptr<Cone>> cones_;
  Eigen::Index dim_ = 0;
  Eigen::Index degree_ = 0;
  ForkJoin* fork_join_ = nullptr;  // set only when the cones are split
  std::size_t split_at_ = 0;       // first cone of the helper's half
  std::vector<std::size_t> packed_offset_;  // where each cone's W² blocks start in pack_W2's output
};

}  // namespace rbla::conic::detail
