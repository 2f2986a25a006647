#pragma once
// Sparse primal–dual interior-point solver for ConicProblem (LP + second-order cones):
// homogeneous self-dual embedding, Nesterov–Todd scaling, Mehrotra predictor–corrector, Ruiz
// equilibration, normal equations A W² Aᵀ factored by CHOLMOD (symbolic analysis once per
// ConicSolver), dense columns by a bordered solve, two-level iterative refinement (PCG on the
// normal equations, correction of the Newton direction's primal/gap residuals). If the bordered
// dense-column solve loses accuracy late in a solve, the dense columns are moved into the sparse
// factor for the rest of that solve (one extra symbolic analysis, kept for later solves).
// Not supported: free variables (model them as differences of nonnegatives, or bound them),
// semidefinite / exponential cones. Warm start: see ConicSolver::set_warm_start.

#include <functional>
#include <memory>

#include "rbla/conic/info.hpp"
#include "rbla/conic/problem.hpp"
#include "rbla/conic/settings.hpp"

namespace rbla::conic {

/// Called once per iteration after the row is computed; return false to cancel the solve.
using ProgressCallback = std::function<bool(const IterationRow&)>;

class ConicSolver {
 public:
  /// Validates problem and settings (throws ConicSetupError), equilibrates, builds the normal
  /// matrix pattern and runs the symbolic factorisation.
  explicit ConicSolver(ConicProblem problem, Settings settings = {});
  ~ConicSolver();
  ConicSolver(ConicSolver&&) noexcept;
  ConicSolver& operator=(ConicSolver&&) noexcept;
  ConicSolver(const ConicSolver&) = delete;
  ConicSolver& operator=(const ConicSolver&) = delete;

  /// Runs the interior-point method from the default start. Never throws for solve outcomes.
  Solution solve();

  /// New data with the same dimensions / sparsity: the symbolic factorisation is reused.
  void update_b(const Eigen::VectorXd& b);
  void update_c(const Eigen::VectorXd& c);
  /// values in the order of problem().A.valuePtr() (compressed column order), length nnz(A).
  void update_A_values(const Eigen::VectorXd& values);
  /// All of A's values, b and c at once (one re-equilibration instead of three): `problem` must
  /// have this solver's dimensions, cones and sparsity pattern of A (throws ConicSetupError).
  void update(const ConicProblem& problem);

  /// Starts the next solve() near a known solution of a nearby problem (same dimensions), e.g.
  /// the previous step of a sequence of update_b() solves: Skajaa, Andersen & Ye (2013),
  /// "Warmstarting the homogeneous and self-dual interior point method for linear and conic
  /// quadratic problems", Math. Prog. Comp. 5: x₀ = λ x̂ + (1 − λ) e, z₀ = λ ẑ + (1 − λ) e,
  /// y₀ = λ ŷ, τ₀ = 1, κ₀ = μ(x₀, z₀), with x̂, ŷ, ẑ the given point in the solver's scaled
  /// variables and λ = Settings::warm_start_weight. Used once: later solves start cold unless
  /// this is called again. Ignored (cold start) when the point is not finite or the blend is not
  /// interior. x, z in the cone K; y the equality multipliers (Solution's x, y, z).
  void set_warm_start(const Eigen::VectorXd& x, const Eigen::VectorXd& y, const Eigen::VectorXd& z);

  void set_progress_callback(ProgressCallback callback);
  /// Tolerances, limits and output may be changed between solves. Structural fields
  /// (ordering, dense_*, equilibrate*) are read at construction only.
  Settings& settings();
  const ConicProblem& problem() const;
  /// Number of symbolic analyses performed so far (1 after construction; updates keep it).
  int num_symbolic_analyses() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One-shot convenience: ConicSolver(problem, settings).solve().
Solution solve(const ConicProblem& problem, const Settings& settings = {});

}  // namespace rbla::conic
