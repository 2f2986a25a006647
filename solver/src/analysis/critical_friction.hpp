// The smallest friction at which the structure stands under its own weight, or carries a given
// load multiplier: every interface's coefficient (or those of a chosen set) scaled by one factor
// s (docs/critical_friction.md).
//
// Why a bracket is certified: with associative friction, a larger s enlarges every scaled
// friction cone (each coefficient min(s mu, 100), held at the schema's limit) and leaves the
// others as they are, and so enlarges the set of admissible contact forces: whatever is carried
// at s is carried at any larger s. "Stands" and "alpha >= target" (to 1e-6 relative) are
// therefore monotone in s, every failing s is a lower and every passing s an upper bound of the
// critical factor (analysis/threshold_search.hpp). With non-associative friction this is not
// proven: the search runs the same way and says so.
#pragma once

#include "analysis/limit_analysis.hpp"
#include "analysis/threshold_search.hpp"

#include <optional>
#include <string>
#include <vector>

namespace rbla::analysis {

struct FrictionEvaluation {
  double factor = 0.0;  ///< s: every interface's friction coefficient times this
  Verdict verdict = Verdict::SolverFailure;
  std::optional<double> load_multiplier;
  bool passes = false;
  double seconds = 0.0;
};

struct CriticalFriction {
  /// What was asked: stand under the dead load (no target), or carry alpha >= *target_alpha.
  std::optional<double> target_alpha;
  ThresholdOutcome outcome = ThresholdOutcome::Failed;
  std::string verdict_text;            ///< one sentence for people
  std::optional<double> factor_lower;  ///< largest s that failed
  std::optional<double> factor_upper;  ///< smallest s that passed: the critical factor reported
  /// The interfaces scaled (indices into model.interfaces); empty: all of them.
  std::vector<int> scaled_interfaces;
  /// The coefficient the factor gives when every scaled interface had the same one; else empty.
  std::optional<double> uniform_friction;
  /// The scaled interfaces' coefficients as given; at factor s each is min(s mu, 100), the
  /// schema's limit.
  std::vector<double> given_frictions;
  bool certified = false;  ///< bracketed within the tolerance, associative friction
  std::string stop;
  std::vector<FrictionEvaluation> evaluations;  ///< in the order they ran
  model::Model model_at_critical;  ///< frictions scaled by factor_upper (or the last factor tried)
  AnalysisResult at_critical;      ///< the analysis there
  double seconds = 0.0;
  /// Conic solvers built, each with one symbolic analysis; the other analyses reused one
  /// (analysis/solver_reuse.hpp).
  int symbolic_analyses = 0;
};

/// Scales the interfaces in `scaled` (indices into model.interfaces), or every interface when it
/// is empty. Throws model::ModelError when the model is not a load-multiplier analysis, has no
/// interface, or `scaled` holds an index out of range or an interface without friction only.
CriticalFriction find_critical_friction(const model::Model& model, std::optional<double> target_alpha,
                                        const AnalysisOptions& options = {}, ThresholdSettings settings = {},
                                        const std::vector<int>& scaled = {});

}  // namespace rbla::analysis
