// The horizontal direction of the seismic load that the structure carries least: the minimum of
// alpha(theta) over every direction theta of the horizontal plane (docs/worst_direction.md).
//
// Why the search can certify a global minimum: with associative friction the set S of horizontal
// seismic load vectors lambda = alpha d the structure carries (with its dead load) is convex,
// since the admissible contact forces form a convex set and the load enters the equilibrium
// equations linearly; alpha(theta) is the radial function of S. analysis/radial_search.hpp then
// brackets min alpha from the evaluated directions alone. The collapse mechanism at theta adds a
// supporting line of S: alpha_u(t) = D / (F . d(t)), with D the work the dead load absorbs and F
// the sum of block weights times their centroid velocities; its own best direction is along F,
// where alpha <= D / |F| <= alpha(theta) (a descent step). Neither holds for non-associative
// friction (S need not be convex): there the search reports the lowest alpha it evaluated,
// without a bracket.
#pragma once

#include "analysis/limit_analysis.hpp"
#include "analysis/radial_search.hpp"

#include <optional>
#include <string>
#include <vector>

namespace rbla::analysis {

struct DirectionEvaluation {
  double angle = 0.0;          ///< rad from `WorstDirection::axis_x` towards `axis_y`
  Vec3 direction = Vec3::Zero();  ///< unit, horizontal
  Verdict verdict = Verdict::SolverFailure;
  std::optional<double> load_multiplier;  ///< alpha along this direction, when Collapse
  int interior_point_iterations = 0;      ///< of the last conic solve
  double seconds = 0.0;                   ///< of the whole analysis along this direction
};

struct WorstDirection {
  /// Collapse: alpha_min found; NoMechanism: alpha unbounded along every direction; CannotStand or
  /// a failure: as the analysis along the direction that stopped the search said.
  Verdict verdict = Verdict::SolverFailure;
  std::string verdict_text;  ///< one sentence for people
  Vec3 axis_x = Vec3::UnitX(), axis_y = Vec3::UnitY();  ///< horizontal basis the angles use
  std::optional<double> alpha_min;   ///< the lowest alpha evaluated
  std::optional<double> angle;       ///< rad, where alpha_min was found
  std::optional<double> lower_bound; ///< certified: min alpha >= this (associative friction only)
  bool certified = false;            ///< lower bound within the tolerance of alpha_min
  std::string stop;                  ///< why the search stopped
  std::vector<DirectionEvaluation> evaluations;  ///< in the order they ran
  model::Model model_at_minimum;     ///< the model with the seismic direction at the minimum
  AnalysisResult at_minimum;         ///< the whole analysis there (or where the search stopped)
  double seconds = 0.0;
  /// Conic solvers built, each with one symbolic analysis; the other analyses reused one
  /// (analysis/solver_reuse.hpp).
  int symbolic_analyses = 0;
};

/// Searches the seismic direction of a load-multiplier analysis (model.analysis.type); the model's
/// own seismic direction is ignored. Throws model::ModelError when the model is not a seismic
/// load-multiplier analysis or has live point loads (they would turn with alpha, not with theta).
WorstDirection find_worst_direction(const model::Model& model, const AnalysisOptions& options = {},
                                    const RadialSearchSettings& settings = {});

}  // namespace rbla::analysis
