#include "analysis/solver_reuse.hpp"

#include <algorithm>

namespace rbla::analysis {

namespace {

/// The settings a ConicSolver reads at construction only (rbla/conic/settings.hpp): a solver
/// built with other values cannot stand in for a new one.
bool same_structure(const conic::Settings& a, const conic::Settings& b) {
  return a.ordering == b.ordering && a.memory_limit_bytes == b.memory_limit_bytes && a.threads == b.threads &&
         a.blas_threads == b.blas_threads && a.split_min_rows == b.split_min_rows &&
         a.dense_columns == b.dense_columns && a.dense_column_min_nnz == b.dense_column_min_nnz &&
         a.dense_column_ratio == b.dense_column_ratio && a.dense_column_max == b.dense_column_max &&
         a.equilibrate == b.equilibrate && a.equilibrate_max_iter == b.equilibrate_max_iter &&
         a.equilibrate_min_scaling == b.equilibrate_min_scaling &&
         a.equilibrate_max_scaling == b.equilibrate_max_scaling;
}

}  // namespace

conic::ConicSolver& SolverReuse::solver_for(const conic::ConicProblem& problem, const conic::Settings& settings) {
  for (auto it = kept_.begin(); it != kept_.end(); ++it) {
    if (!same_structure(it->built_with, settings) || !conic::same_shape(it->solver->problem(), problem)) continue;
    std::rotate(it, it + 1, kept_.end());  // now the most recently used
    conic::ConicSolver& solver = *kept_.back().solver;
    solver.settings() = settings;
    solver.update(problem);
    ++reused_;
    return solver;
  }
  // The one used least recently goes first: never more than kKept solvers in memory at once.
  if (kept_.size() >= kKept) kept_.erase(kept_.begin());
  kept_.push_back({std::make_unique<conic::ConicSolver>(problem, settings), settings});
  ++built_;
  return *kept_.back().solver;
}

}  // namespace rbla::analysis
