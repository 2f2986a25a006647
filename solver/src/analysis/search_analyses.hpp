// The analyses of one search (weakest direction, critical friction, most harmful settlement):
// models that differ only in numbers, each placed at a point of the search's parameter space.
// Each analysis starts from the interior point of the nearest model already analysed within
// `reach` (analysis/warm_starts.hpp) and runs on the search's kept conic solver, whose symbolic
// factorisation serves every model of one sparsity pattern (analysis/solver_reuse.hpp).
#pragma once

#include "analysis/limit_analysis.hpp"
#include "analysis/solver_reuse.hpp"
#include "analysis/warm_starts.hpp"

#include <utility>

namespace rbla::analysis {

class SearchAnalyses {
 public:
  explicit SearchAnalyses(double reach) : points_(reach) {}

  /// analyse(model, options) started near `where` and on the kept solver; keeps its point.
  AnalysisResult analyse_at(const model::Model& model, const AnalysisOptions& options, const Eigen::VectorXd& where) {
    conic::Iterate start = points_.nearest(where);
    AnalysisOptions near = options;
    near.warm_start = &start;
    near.reuse = &solvers_;
    AnalysisResult result = analyse(model, near);
    points_.keep(where, std::move(start));
    return result;
  }

  /// Conic solvers built so far, each with one symbolic analysis.
  int symbolic_analyses() const { return solvers_.built(); }

 private:
  WarmStarts points_;
  SolverReuse solvers_;
};

}  // namespace rbla::analysis
