// Non-associative friction (no dilatancy at sliding joints) as a strategy around the conic solve:
// the iterative scheme of Gilbert, Casapulla & Ahmed (2006), extended to cones by Portioli et al.
// (2014). It starts from a solved associative analysis.
#pragma once

#include "analysis/analysis_result.hpp"
#include "analysis/formulation.hpp"
#include "analysis/limit_analysis.hpp"
#include "analysis/solve_steps.hpp"
#include "model/model.hpp"
#include "rbla/conic/solver.hpp"

namespace rbla::analysis {

/// Runs the scheme from the associative solution `associative` of `formulation` (built with
/// `formulation_options`). On return `value` is the non-associative alpha (or base reaction, kN)
/// and `result` holds its mechanism, history, warnings and verdict; when no step completes,
/// `value` and the associative mechanism are left as they were.
void run_non_associative(const model::Model& m, const Formulation& formulation,
                         const FormulationOptions& formulation_options, const conic::Solution& associative,
                         const Deadline& deadline, const AnalysisOptions& options, double& value,
                         AnalysisResult& result);

}  // namespace rbla::analysis
