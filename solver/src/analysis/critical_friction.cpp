#include "analysis/critical_friction.hpp"

#include "analysis/text.hpp"
#include "analysis/search_analyses.hpp"
#include "model/errors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace rbla::analysis {
namespace {


/// The schema's largest friction coefficient: a scaled coefficient is held there, so that the
/// others can still grow (a keyed joint at mu = 50 would otherwise stop the bed joints at 0.3).
constexpr double kLargestFriction = 100.0;
/// A target counts as carried when alpha reaches it to this relative tolerance. The analyses are
/// exact to about 1e-8, and a target copied from an analysis's printed multiplier lies on the
/// plateau alpha reaches once friction no longer governs (rocking): there, pass or fail would
/// follow the solver's last digits, and a bracket built on them would not be the critical one.
constexpr double kCarriedTolerance = 1e-6;

/// The interfaces to scale: `scaled`, or all of them when it is empty.
std::vector<int> scaled_set(const model::Model& m, const std::vector<int>& scaled) {
  if (m.analysis.type != model::AnalysisType::LoadMultiplier) {
    throw model::ModelError("/analysis/type", "the critical friction is searched for a load_multiplier analysis");
  }
  if (m.interfaces.empty()) throw model::ModelError("/interfaces", "the model has no interface: no friction to scale");
  std::vector<int> set = scaled;
  if (set.empty()) {
    for (std::size_t k = 0; k < m.interfaces.size(); ++k) set.push_back(static_cast<int>(k));
  }
  double largest = 0.0;
  for (int k : set) {
    if (k < 0 || static_cast<std::size_t>(k) >= m.interfaces.size()) {
      throw model::ModelError("/interfaces", "interface index " + std::to_string(k) + " is out of range");
    }
    largest = std::max(largest, m.interfaces[k].friction);
  }
  // Scaling zero coefficients changes nothing: the search would have no parameter.
  if (!(largest > 0.0)) throw model::ModelError("/interfaces", "every interface chosen has zero friction: nothing to scale");
  return set;
}

std::optional<double> uniform_friction(const model::Model& m, const std::vector<int>& set) {
  const double first = m.interfaces[set.front()].friction;
  for (int k : set) {
    if (m.interfaces[k].friction != first) return std::nullopt;
  }
  return first;
}

/// Passes when the structure stands (alpha = 0 admissible) and, with a target, carries it.
ThresholdSample as_sample(const AnalysisResult& r, std::optional<double> target) {
  ThresholdSample s;
  const double goal = target ? *target - kCarriedTolerance * std::abs(*target) : 0.0;
  switch (r.verdict) {
    case Verdict::Collapse:
      s.value = *r.load_multiplier - goal;
      s.passes = *s.value >= 0.0;
      break;
    case Verdict::NoMechanism:
      s.value = std::numeric_limits<double>::infinity();
      s.passes = true;
      break;
    case Verdict::CannotStand: s.passes = false; break;
    case Verdict::SolverFailure:
    case Verdict::TimeLimit:
    case Verdict::IterationLimit:
    case Verdict::Cancelled:
      s.usable = false;
      s.why_unusable = r.verdict_text;
      break;
  }
  return s;
}

std::string asked(std::optional<double> target) {
  return target ? "to carry alpha = " + format(*target, 10) : std::string("to stand under its own weight");
}

/// The largest load multiplier any evaluation carried, for a search that no friction satisfied.
std::string largest_carried(const CriticalFriction& c) {
  std::optional<double> largest;
  for (const FrictionEvaluation& e : c.evaluations) {
    if (e.load_multiplier && (!largest || *e.load_multiplier > *largest)) largest = e.load_multiplier;
  }
  return largest ? "; the largest alpha carried is " + format(*largest, 10) : "";
}

/// The scaled coefficient of interface k at `factor`: held at the schema's limit.
double scaled_friction(double friction, double factor) { return std::min(friction * factor, kLargestFriction); }

/// Says how many scaled coefficients the factor would take past the schema's limit (held there).
std::string held(const CriticalFriction& c, double factor) {
  int count_held = 0;
  for (double mu : c.given_frictions) count_held += mu * factor > kLargestFriction ? 1 : 0;
  return count_held == 0 ? "" : " (" + count(count_held, "coefficient", "coefficients") + " held at " + format(kLargestFriction) + ")";
}

void conclude(CriticalFriction& c, const Threshold& t, bool associative) {
  c.outcome = t.outcome;
  c.stop = t.stop;
  c.factor_lower = t.lower;
  c.factor_upper = t.upper;
  c.certified = t.converged && associative;
  const std::string friction = c.uniform_friction && t.upper ? " (mu = " + format(*c.uniform_friction * *t.upper) + ")" : "";
  const std::string coefficients =
      c.scaled_interfaces.empty() ? "the friction coefficients"
                                  : "the friction coefficients of the " + std::to_string(c.scaled_interfaces.size()) +
                                        " chosen interface" + (c.scaled_interfaces.size() == 1 ? "" : "s");
  switch (t.outcome) {
    case ThresholdOutcome::Bracketed:
      c.verdict_text = "The structure needs " + coefficients + " times " + format(*t.upper) + friction + held(c, *t.upper) +
                       " " + asked(c.target_alpha) + (c.certified ? "; certified" : "; not certified") + ": " + t.stop + ".";
      break;
    case ThresholdOutcome::PassesAtMinimum:
      c.verdict_text = "The structure manages " + asked(c.target_alpha) + " even with " + coefficients + " times " +
                       format(*t.upper) + friction + ", the smallest factor tried: it hardly relies on that friction for it.";
      break;
    case ThresholdOutcome::FailsAtMaximum:
      c.verdict_text = "No friction up to mu = " + format(kLargestFriction) +
                       (c.scaled_interfaces.empty() ? " at every interface" : " at the chosen interfaces") +
                       " is enough " + asked(c.target_alpha) +
                       (c.scaled_interfaces.empty()
                            ? ": overturning or the geometry governs ("
                            : ": overturning, the geometry or the friction of the other interfaces governs (") +
                       t.stop + largest_carried(c) + ").";
      break;
    case ThresholdOutcome::Failed:
      c.verdict_text = "The search stopped: " + t.stop;
      break;
  }
}

}  // namespace

CriticalFriction find_critical_friction(const model::Model& model, std::optional<double> target_alpha,
                                        const AnalysisOptions& options, ThresholdSettings settings,
                                        const std::vector<int>& scaled) {
  const std::vector<int> set = scaled_set(model, scaled);
  check_bracket_tolerance(model, settings.tolerance);
  if (target_alpha && settings.tolerance < kCarriedTolerance) {
    throw model::ModelError("--tolerance", "with a target alpha the friction found carries it to within " +
                                               format(kCarriedTolerance) + " (relative), so its bracket is exact to "
                                               "no better: ask for a bracket of at least that");
  }
  const auto start = Clock::now();
  CriticalFriction c;
  c.target_alpha = target_alpha;
  if (!scaled.empty()) c.scaled_interfaces = set;
  c.uniform_friction = uniform_friction(model, set);
  // The range ends where every scaled coefficient has reached the schema's limit.
  double smallest = std::numeric_limits<double>::infinity();
  for (int k : set) {
    c.given_frictions.push_back(model.interfaces[k].friction);
    if (model.interfaces[k].friction > 0.0) smallest = std::min(smallest, model.interfaces[k].friction);
  }
  settings.max_x = std::min(settings.max_x, kLargestFriction / smallest);
  settings.name = "factor";

  double best_passing = std::numeric_limits<double>::infinity();
  // Each factor starts from the interior point of the nearest factor evaluated within a factor
  // of 2: the problems differ only in the friction coefficients, by less and less as the
  // bracket narrows. On the 1920-block facade (target alpha 0.2) the seven analyses took 152
  // interior-point iterations instead of 170; warm starts from further away cost more than cold.
  SearchAnalyses analyses(std::log(2.0));
  auto evaluate = [&](double factor) {
    const Eigen::VectorXd where = Eigen::VectorXd::Constant(1, std::log(factor));
    const auto evaluation_start = Clock::now();
    model::Model at_factor = model;
    for (int k : set) at_factor.interfaces[k].friction = scaled_friction(at_factor.interfaces[k].friction, factor);
    at_factor.analysis.check_dead_load = true;  // standing is what every test asks first
    AnalysisResult result = analyses.analyse_at(at_factor, options, where);
    const ThresholdSample sample = as_sample(result, target_alpha);
    c.evaluations.push_back({factor, result.verdict, result.load_multiplier, sample.passes, seconds_since(evaluation_start)});
    if ((sample.passes && factor < best_passing) || c.evaluations.size() == 1 ||
        (!std::isfinite(best_passing) && !sample.passes)) {
      if (sample.passes) best_passing = factor;
      c.model_at_critical = std::move(at_factor);
      c.at_critical = std::move(result);
    }
    return sample;
  };
  const Threshold t = find_threshold(evaluate, settings);
  conclude(c, t, model.analysis.friction_model == model::FrictionModel::Associative);
  c.seconds = seconds_since(start);
  c.symbolic_analyses = analyses.symbolic_analyses();
  return c;
}

}  // namespace rbla::analysis
