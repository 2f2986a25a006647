#pragma once
// The Newton system of the homogeneous embedding (variables.hpp), reduced to the normal
// equations. With NT scaling W (λ = W z = W⁻¹ x; Vandenberghe 2010, §4) and right-hand sides
// (η, d, d_κ):
//   A dx − b dτ = −η r_p,   −Aᵀdy + c dτ − dz = −η r_d,   bᵀdy − cᵀdx − dκ = −η r_g,
//   λ ∘ (W dz + W⁻¹ dx) = d,   κ dτ + τ dκ = d_κ,
// with r_p, r_d, r_g of residuals.hpp. Eliminating dz and dx:
//   dx = W² (Aᵀdy − c dτ + r₁),   r₁ = W⁻¹(λ \ d) − η r_d,
//   M dy = −η r_p − A W² r₁ + (A W² c + b) dτ,   M = A W² Aᵀ.
// Writing dy = p + q dτ with M q = A W² c + b (once per iteration) and M p = −η r_p − A W² r₁,
// the last two equations give the scalar
//   dτ = (−η r_g − bᵀp + cᵀW²(Aᵀp + r₁) + d_κ/τ) / (bᵀq − cᵀW²(Aᵀq − c) + κ/τ),
// whose denominator equals ‖W(Aᵀq − c)‖² + κ/τ > 0 (the same elimination as CVXOPT's conelp
// and ECOS, there on the augmented system).
//
// M is factored by NormalEquations over a LinearSolver backend (linear_solver.hpp); when its
// bordered dense-column solve loses accuracy, the system moves to a second NormalEquations with
// the dense columns inside the sparse factor, for the rest of that solve.

#include <memory>

#include "cone.hpp"
#include "normal_equations.hpp"
#include "residuals.hpp"
#include "scaled_problem.hpp"
#include "variables.hpp"

namespace rbla::conic::detail {

/// Accuracy the Newton directions need: bounds on the errors of the primal equation,
/// e_p = A dx − b dτ + η r_p, and of the gap equation, e_g (the refinement's targets).
struct DirectionAccuracy {
  // ‖e_p‖∞, |e_g| at or below this are as good as exact: a step of length α leaves
  // (1 − αη) r_p + α e_p, so e_p ≤ 1e-3 ‖r_p‖ does not slow the Newton decrease of r_p.
  // refine_tol_rel (1 + ‖b‖τ) is an absolute floor.
  double exact = 0;
  // Larger errors are still harmless while r_p stays where it cannot change the answer. Step
  // after step, r_p settles near e_p / η (it gains α e_p and loses αη r_p), r_g near e_g / η.
  // In original units r_p moves the objective gap by y_origᵀ r_orig = ŷᵀr̂ / (s_c s_b τ²)
  // (cᵀx − bᵀy = xᵀz − r_dᵀx + yᵀr_p) and the feasibility measure by ‖D⁻¹ r̂‖∞ / (s_b τ);
  // r_g is the gap itself, scaled by s_c s_b τ (evaluate_metrics()). A tenth of what would use
  // up the gap or the feasibility tolerance is allowed: the budgets below are for |ŷ|ᵀ|e_p|,
  // ‖D⁻¹ e_p‖∞ and |e_g| at η = 1. The objective is judged by the measured |ŷ|ᵀ|e_p| rather
  // than ‖ŷ‖₁ ‖e_p‖∞: late in degenerate solves the error of a plain correction sits on rows
  // where ŷ is small, two orders under the ‖ŷ‖₁ ‖e_p‖∞ bound, and refinement chasing that
  // bound spent most of its solves in CG passes that could not get there (the error's floor is
  // the cancellation in A W² (Aᵀp + r₁), which CG on M does not reach).
  double objective = 0;
  double feasibility = 0;
  double gap = 0;
  // An ‖e_p‖∞ that meets the budgets at η = 1 whatever ŷ: the CG target in M (whose residual
  // is not e_p) and the scale of the refinement's failure test.
  double uniform = 0;

  /// Whether errors (e_p, e_g) of a direction with this η are acceptable; abs_y = |ŷ|.
  bool accepts(const Vec& ep, double eg, double eta, const Vec& abs_y,
               const Vec& row_scale) const;
};

DirectionAccuracy direction_accuracy(const ConicProblem& original, const ScaledProblem& scaled,
                                     const Settings& settings, const Residuals& residuals,
                                     const Variables& v);

class KktSystem {
 public:
  /// `normal`: the normal equations of the construction (the dense-column fallback is built on
  /// first need, with the same blocks, ordering and threads, and kept).
  KktSystem(std::unique_ptr<NormalEquations> normal, const ScaledProblem& scaled,
            const ConeSet& cones, const Settings& settings);

  /// Back to the first normal equations (each solve starts there).
  void reset() { ne_ = normal_.get(); }
  NormalEquations& normal() { return *ne_; }
  const NormalEquations& first_normal() const { return *normal_; }
  const NormalEquations* fallback_normal() const { return without_dense_.get(); }
  void set_A_values(const Eigen::SparseMatrix<double>& A);

  /// Assembles and factors M for the packed W² (ConeSet::pack_W2); timings into info.
  bool factor(const std::vector<double>& packed_W2, int factor_threads, Info& info);

  /// Per-iteration state the directions depend on: residuals, τ, κ, accuracy targets.
  void begin_iteration(const Residuals& residuals, const Variables& v,
                       const DirectionAccuracy& accuracy);

  /// The predictor: solves M q = A W² c + b and M p for (η = 1, d, d_κ) in one pass over the
  /// factor, then the affine direction (refined when `refine`).
  void solve_affine(const Vec& d, double d_kappa, bool refine, Direction& out);
  /// The direction for (η, d, d_κ) by one plain solve (error about that of the factor, 1e-8
  /// late in a solve), to be refined by refine() if it is the one taken.
  void solve(double eta, const Vec& d, double d_kappa, Direction& out);
  /// Refines `dir` on the unreduced residuals (see kkt_system.cpp); dz_current: out.z already
  /// belongs to (x, y, τ). True when a correction changed the direction.
  bool refine(double eta, double d_kappa, bool dz_current, Direction& dir);

  /// The bordered dense-column solve lost accuracy in this iteration's refinement.
  bool refinement_failed() const { return refinement_failed_; }
  /// Moves the dense columns into the sparse factor for the rest of this solve (one more
  /// symbolic analysis the first time). False when there are none to move.
  bool drop_dense_columns(const std::vector<bool>& is_dense, Ordering ordering,
                          ForkJoin* fork_join, Info& info);
  /// Refinement (CG and correction) steps since the last call.
  int take_refine_steps();

 private:
  void prepare_rhs(double eta, const Vec& d);
  void finish_tau_column();
  void direction_from_p(double eta, double d_kappa, bool refine_it, Direction& out);
  void dz_from_dual_equation(double eta, Direction& dir);

  std::unique_ptr<NormalEquations> normal_;
  std::unique_ptr<NormalEquations> without_dense_;
  NormalEquations* ne_ = nullptr;
  const ScaledProblem& scaled_;
  const ConeSet& cones_;
  const Settings& settings_;

  // This iteration's data (begin_iteration).
  const Residuals* residuals_ = nullptr;
  double tau_ = 1, kappa_ = 1;
  DirectionAccuracy accuracy_;
  Vec abs_y_;
  bool refinement_failed_ = false;
  int refine_steps_ = 0;

  // q of dy = p + q dτ, with W²(Aᵀq − c) and the dτ denominator.
  Vec q_, q_rhs_, W2c_, Atq_c_, dxq_;
  double denominator_ = 0;
  // Scratch of the solves and the refinement.
  Vec ds_tilde_, r1_, rhs_, p_, tmp_, ep_, dp_, ddx_;
};

}  // namespace rbla::conic::detail
