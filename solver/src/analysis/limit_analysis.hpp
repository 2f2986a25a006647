// Rigid block limit analysis of a prepared model: the conic solve (or, for non-associative
// friction, the iterative scheme), the verdict, and the collapse mechanism from the dual.
#pragma once

#include "analysis/analysis_result.hpp"
#include "analysis/solver_reuse.hpp"
#include "model/model.hpp"
#include "rbla/conic/solver.hpp"

#include <functional>
#include <iosfwd>
#include <string>

namespace rbla::analysis {

struct AnalysisOptions {
  /// Interior-point iteration log of every conic solve (null: silent).
  std::ostream* log = nullptr;
  /// Called once per interior-point iteration; returning false cancels the analysis.
  conic::ProgressCallback progress;
  /// Called once with the first conic problem, before it is solved (`rbla solve --dump-problem`
  /// writes it for other solvers: io/problem_file.hpp). What it throws ends the analysis.
  std::function<void(const conic::ConicProblem&)> problem_ready;
  /// Threads of each conic solve, 1 or 2 (conic::Settings::threads).
  int threads = 2;
  /// A searching caller's memory between analyses of nearby models (the same scene with another
  /// direction or friction): when set, the first conic solve starts from the point `warm_start`
  /// holds if its dimensions match, and leaves there the point it passed at a relative gap of
  /// 1e-2 (ConicSolver::set_warm_start, Skajaa, Andersen & Ye 2013).
  conic::Iterate* warm_start = nullptr;
  /// A searching caller's conic solver between analyses: when set, an analysis whose conic
  /// problem has the kept solver's shape reuses its symbolic analysis (analysis/solver_reuse.hpp).
  SolverReuse* reuse = nullptr;
};

/// Runs the analysis the model requests (model.analysis). Throws model::ModelError only for
/// requests the scene cannot meet (a planar formulation forced on a 3-D scene); every solve
/// outcome, including failures, is a Verdict in the result.
AnalysisResult analyse(const model::Model& model, const AnalysisOptions& options = {});

}  // namespace rbla::analysis
