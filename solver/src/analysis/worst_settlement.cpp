#include "analysis/worst_settlement.hpp"

#include "analysis/initial_reaction.hpp"
#include "analysis/text.hpp"
#include "analysis/search_analyses.hpp"
#include "model/errors.hpp"
#include "model/angles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace rbla::analysis {
namespace {

using rbla::model::kPi;

using rbla::model::degrees;

void check_request(const model::Model& m) {
  if (m.analysis.type != model::AnalysisType::Settlement) {
    throw model::ModelError("/analysis/type", "the worst settlement direction is searched for a settlement analysis");
  }
}

/// w with R0(d) = w . d: R0 is linear in d (the initial base pressure does not depend on it), so
/// its values along the three axes are w's components.
Vec3 initial_reaction_vector(const model::Model& m) {
  Vec3 w = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    const InitialReaction r = initial_base_reaction(m, Vec3::Unit(k));
    if (!r.value) {
      throw model::ModelError("/analysis", "the worst settlement direction compares the reaction at collapse with the "
                                           "reaction before settlement, which this model does not define: " +
                                               r.why_not);
    }
    w[k] = *r.value;
  }
  return w;
}

/// Refuses a cone over part of which the supports carry nothing before settlement (R0 <= 0).
void check_cone(const DirectionCone& cone) {
  if (smallest_on_cone(cone) > 0.0) return;
  if (cone.w.norm() == 0.0) {
    throw model::ModelError("/blocks", "the moving supports carry nothing before settlement (R0 = 0 along every "
                                       "direction), so no fraction R / R0 is defined");
  }
  const Vec3 a = cone.axis.normalized();
  const double off_axis = std::acos(std::clamp(cone.w.normalized().dot(a), -1.0, 1.0));
  const double widest = 90.0 - degrees(off_axis);
  throw model::ModelError("--cone-angle", "the reaction before settlement is not positive along every direction of "
                                          "the cone; it is for half angles below " +
                                              format(std::max(0.0, widest)) + " degrees");
}

/// Tilt from gravity and azimuth of the horizontal part, in the model's horizontal axes.
void place(const model::Model& m, const Vec3& axis_x, const Vec3& axis_y, SettlementEvaluation& e) {
  e.tilt = std::acos(std::clamp(e.direction.dot(m.gravity.normalized()), -1.0, 1.0));
  const double x = e.direction.dot(axis_x), y = e.direction.dot(axis_y);
  e.azimuth = std::hypot(x, y) > 1e-12 ? std::atan2(y, x) : 0.0;
  if (e.azimuth < 0.0) e.azimuth += 2.0 * kPi;
}

ConeSample as_sample(const model::Model& m, const AnalysisResult& r, double initial) {
  ConeSample sample;
  // Settling along d forms no mechanism (settlement_bound.hpp): the analysis still found a state
  // of S, with G . d <= 0. Its plane is a cut like any other; its value G . d / R0 is at most 0,
  // and at least R(d) / R0, the least harmful there is.
  const bool no_mechanism = r.verdict == Verdict::NoMechanism && !r.mechanism.interfaces.empty();
  if (!no_mechanism && (r.verdict != Verdict::Collapse || !r.base_reaction)) {
    sample.usable = false;
    sample.why_unusable = r.verdict_text;
    return sample;
  }
  // The ratio is R / R0, and R(d') <= G* . d': a cut on R itself (cone_search divides by w . d).
  // With non-associative friction the same plane only guides the search.
  sample.supergradient = force_on_moving_supports(m, r);
  sample.ratio = no_mechanism ? sample.supergradient->dot(m.analysis.settlement_direction) / initial
                              : *r.base_reaction / initial;
  return sample;
}

std::string direction_words(const SettlementEvaluation& e) {
  return "tilted " + format(degrees(e.tilt)) + " degrees from gravity" +
         (e.tilt > 1e-9 ? " towards azimuth " + format(degrees(e.azimuth)) + " degrees" : std::string());
}

void conclude(const model::Model& m, WorstSettlement& w, const ConeMaximum& search,
              const ConeSearchSettings& settings) {
  w.stop = search.stop;
  if (search.best >= 0) {
    const SettlementEvaluation& best = w.evaluations[search.best];
    w.worst = search.best;
    w.ratio = best.ratio;
    w.upper_bound = search.upper_bound;
    w.certified = search.converged && settings.concave && !search.failed;
  }
  if (search.failed || search.best < 0) {
    const SettlementEvaluation& last = w.evaluations.back();
    w.verdict = last.verdict == Verdict::Collapse ? Verdict::SolverFailure : last.verdict;
    w.verdict_text = "The search stopped at the direction " + direction_words(last) + ": " + search.stop +
                     (w.worst ? "; the most harmful direction before it was " +
                                    direction_words(w.evaluations[*w.worst]) + " (R / R0 = " + format(*w.ratio) + ")"
                              : std::string()) +
                     ".";
    return;
  }
  const SettlementEvaluation& best = w.evaluations[*w.worst];
  w.verdict = Verdict::Collapse;
  w.verdict_text = "Most harmful settlement direction " + direction_words(best) + ": collapse at R = " +
                   format(*best.base_reaction / m.units.force_to_kN) + " " + m.units.force_name + ", " +
                   format(100.0 * *best.ratio) +
                   " % of the reaction before settlement" +
                   (w.certified ? ", the largest fraction over the cone to within " + format(settings.tolerance * 100.0) + " %"
                                : std::string(", not certified as the largest (") + search.stop + ")") +
                   ".";
  // Every admissible state, the true initial one included, has a reaction of at least R along
  // d; an estimate below it is one the joints cannot carry (the analysis warns about it). Beyond
  // the analyses' accuracy: a structure on one moving support has R = R0, and R/R0 = 1 + 2e-16.
  if (*best.ratio > 1.0 + 1e-6) {
    w.verdict_text += " Above 1: along this direction the reaction estimated before settlement (one rigid body on "
                      "elastic ground) is below the smallest the joints can carry, so the estimate, not the "
                      "structure, fails there; the margin before collapse along it is not known.";
  }
}

}  // namespace

Vec3 force_on_moving_supports(const model::Model& m, const AnalysisResult& r) {
  Vec3 g = Vec3::Zero();
  for (std::size_t k = 0; k < m.interfaces.size() && k < r.mechanism.interfaces.size(); ++k) {
    const model::ContactInterface& contact = m.interfaces[k];
    const bool on_b = m.blocks[contact.block_b].role == model::BlockRole::MovingSupport;
    const bool on_a = m.blocks[contact.block_a].role == model::BlockRole::MovingSupport;
    if (on_a == on_b) continue;  // not a support joint (or between two moving supports: internal)
    // The interface force acts on block_b along +normal, on block_a opposite.
    for (const PointResult& p : r.mechanism.interfaces[k].points) {
      const Vec3 f = p.normal_force * contact.normal + p.shear1 * contact.tangent1 + p.shear2 * contact.tangent2;
      g += on_b ? f : Vec3(-f);
    }
  }
  return g;
}

WorstSettlement find_worst_settlement(const model::Model& model, const AnalysisOptions& options,
                                      const WorstSettlementSettings& settings) {
  check_request(model);
  check_bracket_tolerance(model, settings.search.tolerance);
  const auto start = Clock::now();
  WorstSettlement w;
  w.cone_angle = settings.cone_angle;
  std::tie(w.axis_x, w.axis_y) = model.horizontal_axes();
  w.initial_reaction_vector = initial_reaction_vector(model);
  DirectionCone cone;
  cone.axis = model.gravity.normalized();
  cone.half_angle = settings.cone_angle;
  cone.w = w.initial_reaction_vector;
  check_cone(cone);
  ConeSearchSettings search_settings = settings.search;
  const bool associative = model.analysis.friction_model == model::FrictionModel::Associative;
  search_settings.concave = associative;

  double best_ratio = -std::numeric_limits<double>::infinity();
  // Each direction starts from the interior point of the nearest one evaluated within 15 degrees,
  // on the search's kept solver (analysis/search_analyses.hpp).
  SearchAnalyses analyses(2.0 * std::sin(kPi / 24.0));
  auto evaluate = [&](const Eigen::Vector3d& direction) {
    const auto evaluation_start = Clock::now();
    model::Model turned = model;
    turned.analysis.settlement_direction = direction;
    // Whether the structure stands at all does not depend on the direction: checked once.
    turned.analysis.check_dead_load = model.analysis.check_dead_load && w.evaluations.empty();
    AnalysisResult result = analyses.analyse_at(turned, options, direction);
    SettlementEvaluation e;
    e.direction = direction;
    place(model, w.axis_x, w.axis_y, e);
    e.verdict = result.verdict;
    e.base_reaction = result.base_reaction;
    e.initial_reaction = w.initial_reaction_vector.dot(direction);
    const ConeSample sample = as_sample(turned, result, e.initial_reaction);
    if (sample.usable) e.ratio = sample.ratio;
    e.interior_point_iterations = result.solver_info.iterations;
    e.seconds = seconds_since(evaluation_start);
    w.evaluations.push_back(e);
    if (!sample.usable || sample.ratio > best_ratio || w.evaluations.size() == 1) {
      if (sample.usable) best_ratio = sample.ratio;
      w.model_at_worst = std::move(turned);
      w.at_worst = std::move(result);
    }
    return sample;
  };
  const ConeMaximum search = find_cone_maximum(evaluate, cone, search_settings);
  conclude(model, w, search, search_settings);
  w.seconds = seconds_since(start);
  w.symbolic_analyses = analyses.symbolic_analyses();
  return w;
}

}  // namespace rbla::analysis
