// A conic solver kept between the analyses of a search or a sweep (weakest direction, critical
// friction, most harmful settlement, a grid of friction coefficients): the models differ only in
// numbers (a load direction, a friction factor, a unit weight), so their conic problems usually
// share one sparsity pattern, and the solver's symbolic analysis (the fill-reducing ordering of
// A W² Aᵀ and its pattern) is done once. Only the data are replaced (ConicSolver::update), which
// re-equilibrates: a reused solve runs the same iterations as a new solver on the same problem.
//
// When the pattern differs (a search over seismic directions on a planar wall alternates the
// planar LP with 3-D cones, for directions out of the plane), a new solver is built. The two most
// recently used are kept: one per formulation in such a search, and at most two solvers' memory.
#pragma once

#include "rbla/conic/solver.hpp"

#include <memory>
#include <vector>

namespace rbla::analysis {

class SolverReuse {
 public:
  /// A solver holding `problem` with `settings`: a kept one with its data replaced when the
  /// problem and the settings' structural fields match it, else a new one, kept in place of the
  /// one used least recently.
  conic::ConicSolver& solver_for(const conic::ConicProblem& problem, const conic::Settings& settings);

  /// Solvers built (each one symbolic analysis) and calls that reused a kept one.
  int built() const { return built_; }
  int reused() const { return reused_; }

 private:
  struct Kept {
    std::unique_ptr<conic::ConicSolver> solver;
    conic::Settings built_with;
  };
  static constexpr std::size_t kKept = 2;
  std::vector<Kept> kept_;  ///< the most recently used last
  int built_ = 0;
  int reused_ = 0;
};

}  // namespace rbla::analysis
