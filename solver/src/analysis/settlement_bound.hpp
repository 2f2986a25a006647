// Settlement along a direction the structure does not need the ground along.
//
// The settlement problem minimises R, the reaction of the moving supports along the settlement
// direction d, over the admissible states S (docs/method.md): R = G . d for the force G the
// structure exerts on the supports, and R >= 0, since the ground only pushes. Where some state
// of S has G . d <= 0 the minimum sits on that bound: R = 0, and the dual's supports do not move
// at all (the reduced cost of R is its whole cost, 1, against about 1e-11 at a collapse on the
// bench scenes and samples). Where every state of S has G . d < 0 the problem is infeasible,
// although S is not empty. Neither is a collapse: the reaction along d can drop to 0 with the
// structure in equilibrium, so settling along d forms no mechanism. Read as one they said
// "Collapse ... R = 3e-9 kN, loss 100 %" and "Cannot stand under dead load alone" for a flat
// arch that stands (found by the search review; tests/validation).
#pragma once

#include "analysis/analysis_result.hpp"
#include "analysis/formulation.hpp"
#include "analysis/limit_analysis.hpp"
#include "analysis/solve_steps.hpp"
#include "model/model.hpp"
#include "rbla/conic/solver.hpp"

namespace rbla::analysis {

/// The reduced cost of R (c_R - A_R^T y, against c_R = 1) above which R = 0 is taken as held by
/// its bound rather than reached by a collapse.
inline constexpr double kSettlementBoundCost = 1e-3;

/// Whether a solved settlement problem has R = 0 on its bound (see above).
bool reaction_on_its_bound(const Formulation& f, const conic::Solution& solution);

/// Makes the verdict of the settlement problem `f` (built with `used`) NoMechanism where settling
/// along d forms none: R = 0 on its bound, or an infeasible problem whose structure stands with
/// the moving supports held (the same problem along -d is then feasible). `result` then holds a
/// state of S (its forces give the searches' cutting planes, G . d' >= R(d') for every d') and
/// `settlement_pushes_back` says which case it was. Returns true when it changed the verdict.
bool settlement_forms_no_mechanism(const model::Model& m, const AnalysisOptions& options,
                                   const FormulationOptions& used, const Formulation& f,
                                   const conic::Solution& solution, const Deadline& deadline,
                                   AnalysisResult& result);

/// The verdict sentence when settling along d forms no mechanism (result.verdict NoMechanism).
std::string no_settlement_collapse_text(const model::Model& m, const AnalysisResult& result);

}  // namespace rbla::analysis
