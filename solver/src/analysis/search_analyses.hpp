// The analyses of one search (weakest direction, critical friction, most harmful settlement):
// models that differ only in numbers, each placed at a point of the search's parameter space.
// Each analysis starts from the interior point of the nearest model already analysed within
// `reach` (analysis/warm_starts.hpp) and runs on the search's kept conic solver, whose symbolic
// factorisation serves every model of one sparsity pattern (analysis/solver_reuse.hpp).
#pragma once

#include "analysis/limit_analysis.hpp"
#include "analysis/solver_reuse.hpp"
#include "analysis/text.hpp"
#include "analysis/warm_starts.hpp"
#include "model/errors.hpp"

#include <algorithm>
#include <utility>

namespace rbla::analysis {

/// A search's bracket is only as exact as its analyses, which stop at the model's relative duality
/// gap and residuals (analysis.tolerances): a bracket asked narrower than ten times those would be
/// certified on digits the analyses do not give. Refused, saying which tolerance to lower.
inline void check_bracket_tolerance(const model::Model& m, double tolerance) {
  constexpr double kDigitsOfMargin = 10.0;
  const double analyses = std::max(m.analysis.tol_relative_gap, m.analysis.tol_feasibility);
  if (tolerance >= kDigitsOfMargin * analyses) return;
  throw model::ModelError("/analysis/tolerances",
                          "a bracket of " + format(tolerance) + " (relative, --tolerance) is narrower than ten times "
                          "the analyses' own tolerance (" + format(analyses) + "): its ends would not be exact to "
                          "it; set relative_gap and feasibility here to at most " +
                              format(tolerance / kDigitsOfMargin) + ", or ask for a wider bracket");
}

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
