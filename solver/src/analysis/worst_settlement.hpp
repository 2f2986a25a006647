// The most harmful direction of settlement of the moving supports within a cone around gravity
// (docs/worst_settlement.md).
//
// Harm: the fraction R / R0 of the supports' initial reaction R0 (analysis/initial_reaction.hpp)
// that is still there when the mechanism forms at the base reaction R. Near 1, the structure
// collapses as soon as the supports begin to give way; near 0, they must shed almost all of
// their load first. The most harmful direction is the one with the largest R / R0.
//
// Why the search can certify it: the free blocks' equilibrium and friction cones do not involve
// the settlement direction d, so the contact forces they admit form one convex set S, and
// R(d) = min over S of G . d, with G the force of the structure on the moving supports: a minimum
// of linear functions of d, concave and positively homogeneous, with the optimal G* a
// supergradient (R(d') <= G* . d' for every d', since G* is admissible). R0(d) = w . d is linear
// (the initial pressure does not depend on d). So R / R0 is the ratio analysis/cone_search.hpp
// maximises with a certified bracket. With non-associative friction R is not such a minimum: the
// search runs the same way and claims no bound.
#pragma once

#include "analysis/cone_search.hpp"
#include "analysis/limit_analysis.hpp"
#include "model/angles.hpp"

#include <optional>
#include <string>
#include <vector>

namespace rbla::analysis {

struct SettlementEvaluation {
  Vec3 direction = Vec3::Zero();  ///< unit settlement direction
  double tilt = 0.0;              ///< rad from gravity
  double azimuth = 0.0;           ///< rad, of its horizontal part, from axis_x towards axis_y
  Verdict verdict = Verdict::SolverFailure;
  std::optional<double> base_reaction;  ///< kN, R at collapse
  double initial_reaction = 0.0;        ///< kN, R0 along this direction
  std::optional<double> ratio;          ///< R / R0
  int interior_point_iterations = 0;    ///< of the last conic solve
  double seconds = 0.0;                 ///< of the whole analysis along this direction
};

struct WorstSettlementSettings {
  double cone_angle = model::radians(30.0);  ///< rad, half angle around gravity
  ConeSearchSettings search;
};

struct WorstSettlement {
  /// Collapse: the most harmful direction found; otherwise what the analysis that stopped the
  /// search said (CannotStand, a failure).
  Verdict verdict = Verdict::SolverFailure;
  std::string verdict_text;  ///< one sentence for people
  double cone_angle = 0.0;   ///< rad
  Vec3 axis_x = Vec3::UnitX(), axis_y = Vec3::UnitY();  ///< horizontal basis the azimuths use
  Vec3 initial_reaction_vector = Vec3::Zero();  ///< kN: R0(d) = this . d
  std::optional<double> ratio;                  ///< the largest R / R0 evaluated
  std::optional<int> worst;                     ///< index into evaluations where it was found
  std::optional<double> upper_bound;            ///< certified: max R / R0 <= this (associative)
  bool certified = false;                       ///< upper bound within the tolerance of ratio
  std::string stop;                             ///< why the search stopped
  std::vector<SettlementEvaluation> evaluations;  ///< in the order they ran
  model::Model model_at_worst;  ///< the model with the settlement direction there
  AnalysisResult at_worst;      ///< the whole analysis there (or where the search stopped)
  double seconds = 0.0;
  /// Conic solvers built, each with one symbolic analysis; the other analyses reused one
  /// (analysis/solver_reuse.hpp).
  int symbolic_analyses = 0;
};

/// Searches the settlement direction of a settlement analysis; the model's own direction is
/// ignored. Throws model::ModelError when the model is not a settlement analysis, when R0 is not
/// defined for it (the reason named), or when R0 is not positive over the whole cone.
WorstSettlement find_worst_settlement(const model::Model& model, const AnalysisOptions& options = {},
                                      const WorstSettlementSettings& settings = {});

/// kN: the force the structure exerts on the moving supports in a settlement result's contact
/// forces (its component along the settlement direction is the base reaction).
Vec3 force_on_moving_supports(const model::Model& model, const AnalysisResult& result);

}  // namespace rbla::analysis
