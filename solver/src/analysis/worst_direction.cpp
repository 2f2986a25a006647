#include "analysis/worst_direction.hpp"

#include "analysis/text.hpp"
#include "analysis/search_analyses.hpp"
#include "model/errors.hpp"
#include "model/angles.hpp"

#include <cmath>
#include <limits>
#include <tuple>

namespace rbla::analysis {
namespace {

using rbla::model::kPi;

void check_request(const model::Model& m) {
  if (m.analysis.type != model::AnalysisType::LoadMultiplier) {
    throw model::ModelError("/analysis/type", "the worst direction is searched for a load_multiplier analysis");
  }
  if (!m.live_loads.empty()) {
    throw model::ModelError("/loads/live", "the worst direction turns the seismic load only; live point loads "
                                           "would be scaled by alpha without turning: remove them for this search");
  }
}

/// The supporting line the mechanism gives (associative friction): alpha_u(t) = D / (F . d(t)).
void add_mechanism_bound(const model::Model& m, const AnalysisResult& r, const WorstDirection& w,
                         RadialSample& sample) {
  if (r.verdict != Verdict::Collapse || r.friction_model != model::FrictionModel::Associative) return;
  Vec3 f = Vec3::Zero();
  for (std::size_t b = 0; b < m.blocks.size() && b < r.mechanism.blocks.size(); ++b) {
    f += m.blocks[b].weight() * r.mechanism.blocks[b].translation;
  }
  const double fx = f.dot(w.axis_x), fy = f.dot(w.axis_y);
  const double absorbed = r.work.dissipation - r.work.dead_work;
  if (std::hypot(fx, fy) <= 0.0 || absorbed < 0.0) return;
  sample.bound_angle = std::atan2(fy, fx);
  sample.bound_radius = absorbed / std::hypot(fx, fy);
}

RadialSample as_sample(const AnalysisResult& r) {
  RadialSample sample;
  switch (r.verdict) {
    case Verdict::Collapse:
      sample.radius = r.load_multiplier.value_or(std::numeric_limits<double>::quiet_NaN());
      break;
    case Verdict::NoMechanism: sample.radius = std::numeric_limits<double>::infinity(); break;
    case Verdict::CannotStand:
    case Verdict::SolverFailure:
    case Verdict::TimeLimit:
    case Verdict::IterationLimit:
    case Verdict::Cancelled:
      sample.usable = false;
      sample.why_unusable = r.verdict_text;
      break;
  }
  if (sample.usable && std::isnan(sample.radius)) {
    sample.usable = false;
    sample.why_unusable = "the analysis reported a collapse without a load multiplier";
  }
  return sample;
}

void conclude(WorstDirection& w, const RadialMinimum& search, const RadialSearchSettings& settings) {
  w.stop = search.stop;
  if (search.failed) {
    w.verdict = w.evaluations.back().verdict;
    w.verdict_text = "The search stopped at " + format(model::degrees(w.evaluations.back().angle)) +
                     " degrees: " + search.stop;
    return;
  }
  if (search.best < 0) {
    w.verdict = Verdict::NoMechanism;
    w.verdict_text = "No collapse along any horizontal direction tried (" + search.stop + ").";
    return;
  }
  const RadialSample& best = search.samples[search.best];
  w.verdict = Verdict::Collapse;
  w.alpha_min = best.radius;
  w.angle = best.angle;
  w.lower_bound = search.lower_bound;
  w.certified = search.converged && settings.convex;
  w.verdict_text = "Weakest horizontal direction at " + format(model::degrees(best.angle)) +
                   " degrees: collapse at load multiplier alpha = " + format(best.radius) +
                   (w.certified ? ", the global minimum to within " + format(settings.tolerance * 100.0) + " %"
                                : std::string(", not certified as the global minimum (") + search.stop + ")") +
                   ".";
}

}  // namespace

WorstDirection find_worst_direction(const model::Model& model, const AnalysisOptions& options,
                                    const RadialSearchSettings& settings) {
  check_request(model);
  check_bracket_tolerance(model, settings.tolerance);
  const auto start = Clock::now();
  WorstDirection w;
  std::tie(w.axis_x, w.axis_y) = model.horizontal_axes();
  RadialSearchSettings search_settings = settings;
  search_settings.convex = model.analysis.friction_model == model::FrictionModel::Associative;

  double best_radius = std::numeric_limits<double>::infinity();
  // Each direction starts from the interior point of the nearest one evaluated within 30 degrees,
  // on the search's kept solver (analysis/search_analyses.hpp).
  SearchAnalyses analyses(2.0 * std::sin(kPi / 12.0));
  auto evaluate = [&](double angle) {
    const auto evaluation_start = Clock::now();
    model::Model turned = model;
    turned.analysis.seismic_direction = std::cos(angle) * w.axis_x + std::sin(angle) * w.axis_y;
    // Whether alpha = 0 is admissible does not depend on the direction: checked once.
    turned.analysis.check_dead_load = model.analysis.check_dead_load && w.evaluations.empty();
    const Eigen::VectorXd where = Eigen::Vector2d(std::cos(angle), std::sin(angle));
    AnalysisResult result = analyses.analyse_at(turned, options, where);
    RadialSample sample = as_sample(result);
    add_mechanism_bound(turned, result, w, sample);
    w.evaluations.push_back({angle, *turned.analysis.seismic_direction, result.verdict, result.load_multiplier,
                             result.solver_info.iterations, seconds_since(evaluation_start)});
    const bool keep = !sample.usable || (sample.radius < best_radius) || w.evaluations.size() == 1;
    if (keep) {
      if (sample.usable) best_radius = sample.radius;
      w.model_at_minimum = std::move(turned);
      w.at_minimum = std::move(result);
    }
    return sample;
  };
  const RadialMinimum search = minimise_radius(evaluate, search_settings);
  conclude(w, search, search_settings);
  w.seconds = seconds_since(start);
  w.symbolic_analyses = analyses.symbolic_analyses();
  return w;
}

}  // namespace rbla::analysis
