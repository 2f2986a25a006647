#include "analysis/limit_analysis.hpp"

#include "analysis/connectivity.hpp"
#include "analysis/formulation.hpp"
#include "analysis/initial_reaction.hpp"
#include "analysis/mechanism.hpp"
#include "analysis/non_associative.hpp"
#include "analysis/settlement_bound.hpp"
#include "analysis/sensitivities.hpp"
#include "analysis/solve_steps.hpp"
#include "model/errors.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

namespace rbla::analysis {

const char* to_string(Verdict verdict) {
  switch (verdict) {
    case Verdict::Collapse: return "collapse";
    case Verdict::NoMechanism: return "no_mechanism";
    case Verdict::CannotStand: return "cannot_stand";
    case Verdict::SolverFailure: return "solver_failure";
    case Verdict::TimeLimit: return "time_limit";
    case Verdict::IterationLimit: return "iteration_limit";
    case Verdict::Cancelled: return "cancelled";
  }
  return "?";
}

const char* to_string(ContactState state) {
  switch (state) {
    case ContactState::Closed: return "closed";
    case ContactState::Opening: return "opening";
    case ContactState::Sliding: return "sliding";
    case ContactState::OpeningSliding: return "opening_sliding";
  }
  return "?";
}

const char* to_string(InterfaceState state) {
  switch (state) {
    case InterfaceState::Closed: return "closed";
    case InterfaceState::Opening: return "opening";
    case InterfaceState::Sliding: return "sliding";
    case InterfaceState::OpeningSliding: return "opening_sliding";
    case InterfaceState::Hinge: return "hinge";
  }
  return "?";
}

namespace {

Verdict verdict_of(conic::SolveStatus status, bool settlement) {
  switch (status) {
    case conic::SolveStatus::Solved:
    case conic::SolveStatus::SolvedInaccurate: return Verdict::Collapse;
    case conic::SolveStatus::PrimalInfeasible: return Verdict::CannotStand;
    // Minimising a reaction that is >= 0 cannot be unbounded: that would be a solver failure.
    case conic::SolveStatus::DualInfeasible: return settlement ? Verdict::SolverFailure : Verdict::NoMechanism;
    case conic::SolveStatus::IterationLimit: return Verdict::IterationLimit;
    case conic::SolveStatus::TimeLimit: return Verdict::TimeLimit;
    case conic::SolveStatus::NumericalFailure: return Verdict::SolverFailure;
    case conic::SolveStatus::Cancelled: return Verdict::Cancelled;
  }
  return Verdict::SolverFailure;
}

// The loss of base reaction at collapse needs the reaction before settlement; see
// initial_reaction.hpp for the definition used and why one is needed.
void record_initial_reaction(const model::Model& m, AnalysisResult& result) {
  const InitialReaction initial = initial_base_reaction(m, m.analysis.settlement_direction);
  if (!initial.value) {
    result.warnings.push_back({"initial_reaction_undefined",
                               "the base reaction before settlement (and so its loss) is not reported: " +
                                   initial.why_not,
                               "/analysis"});
    return;
  }
  result.initial_base_reaction = *initial.value;
  result.initial_base_lifts = initial.base_lifts;
  const double at_collapse = result.base_reaction.value_or(0.0);
  // R at collapse is the smallest admissible reaction; the rigid-body estimate ignores the joints
  // inside the structure, so it can fall below it when the structure could not carry that state.
  if (*initial.value < at_collapse - 1e-6 * std::max(1.0, std::abs(at_collapse))) {
    result.warnings.push_back({"initial_reaction_below_collapse",
                               "the base reaction before settlement, estimated with the structure as one rigid "
                               "body on elastic ground, is below the reaction at collapse: the joints cannot "
                               "carry that initial state, and the reported loss is negative",
                               "/analysis"});
  }
}

/// The falling blocks by id (the first ten) and, for a structure held up only by its live load,
/// the push it needs. A verdict of the connectivity check has its own sentence.
std::string cannot_stand_text(const model::Model& m, const AnalysisResult& result) {
  if (result.connectivity.num_falling_blocks() > 0) return unsupported_verdict_text(m, result.connectivity);
  std::vector<int> falling;
  for (std::size_t b = 0; b < result.mechanism.blocks.size(); ++b) {
    if (result.mechanism.blocks[b].moving && !m.blocks[b].is_support()) falling.push_back(static_cast<int>(b));
  }
  std::string text = "Cannot stand under dead load alone";
  if (result.minimum_load_multiplier) {
    text += " (only a live load of at least alpha = " + format(*result.minimum_load_multiplier) + " holds it up)";
  }
  text += ": " + count(falling.size(), "block falls", "blocks fall");
  if (!falling.empty()) text += ": " + quoted_block_ids(m, falling, 10);
  return text + ".";
}

/// For a non-associative analysis, what its value is (a certified collapse state, or not) and the
/// associative bound that every non-associative collapse state obeys
/// (AnalysisResult::non_associative_bound); empty for associative ones.
std::string non_associative_clause(const model::Model& m, const AnalysisResult& result) {
  if (!result.non_associative_bound) return "";
  const bool settlement = result.base_reaction.has_value();
  const std::string bound = settlement ? "R below the associative " +
                                             format(*result.non_associative_bound / m.units.force_to_kN) + " " +
                                             m.units.force_name
                                       : "alpha above the associative " + format(*result.non_associative_bound);
  if (result.non_associative_converged) {
    return "non-associative: a certified collapse state, others may exist; none has " + bound;
  }
  return "non-associative, not certified: the scheme stopped before a state passed the fixed-point test; no "
         "non-associative collapse state has " + bound;
}

/// Said of a non-associative analysis whose associative problem has no mechanism. The scheme
/// starts from the associative mechanism, and without dilatancy a block held only by friction
/// between supports (wedged, clamped) can slide at any load, even under its own weight: a block
/// wedged between a fixed wall and a fixed pier has no associative mechanism, while sliding down
/// with a clamping force of W / (2 mu) on each side is a non-associative collapse state at 0.
constexpr const char* kNoAssociativeMechanism =
    "That is with associative friction; for non-associative friction it is not certified: the scheme starts "
    "from the associative mechanism and there is none, while blocks held only by friction between supports "
    "(wedged, clamped) may slide at any load, even under their own weight.";

/// The warning that goes with kNoAssociativeMechanism.
void warn_no_associative_mechanism(AnalysisResult& result) {
  if (result.friction_model != model::FrictionModel::NonAssociative || result.verdict != Verdict::NoMechanism) return;
  result.warnings.push_back({"non_associative_not_run",
                             "the associative problem has no mechanism, so the non-associative scheme did not run; "
                             "no mechanism is certified for non-associative friction",
                             "/analysis/friction_model"});
}

void write_verdict_text(const model::Model& m, AnalysisResult& result) {
  const std::string force_unit = m.units.force_name;
  std::size_t falling = 0;
  for (const auto& motion : result.mechanism.blocks) falling += motion.moving ? 1 : 0;
  const std::size_t cracked = result.mechanism.cracked_interfaces.size();
  const std::string non_associative = non_associative_clause(m, result);
  switch (result.verdict) {
    case Verdict::Collapse:
      if (result.base_reaction) {
        std::string loss;
        if (result.initial_base_reaction) {
          const double r0 = *result.initial_base_reaction;
          loss = " (before settlement " + format(r0 / m.units.force_to_kN) + " " + force_unit + ", loss " +
                 format((r0 - *result.base_reaction) / m.units.force_to_kN) + " " + force_unit;
          if (r0 > 0) loss += " = " + format(100.0 * (r0 - *result.base_reaction) / r0, 3) + " %";
          loss += ")";
        }
        if (!non_associative.empty()) loss += "; " + non_associative;
        result.verdict_text = "Collapse under settlement: base reaction at collapse R = " +
                              format(*result.base_reaction / m.units.force_to_kN) + " " + force_unit + loss + "; " +
                              count(cracked, "interface cracks", "interfaces crack") + ".";
      } else {
        result.verdict_text = "Collapse at load multiplier alpha = " + format(result.load_multiplier.value_or(0.0)) +
                              (non_associative.empty() ? "" : " (" + non_associative + ")") + "; " +
                              count(falling, "block moves", "blocks move") + ", " +
                              count(cracked, "interface cracks", "interfaces crack") + ".";
      }
      break;
    case Verdict::NoMechanism:
      result.verdict_text = result.type == model::AnalysisType::Settlement
                                ? no_settlement_collapse_text(m, result)
                                : "No mechanism: the live load can grow without bound (alpha unbounded).";
      if (result.friction_model == model::FrictionModel::NonAssociative) {
        result.verdict_text += " " + std::string(kNoAssociativeMechanism);
      }
      break;
    case Verdict::CannotStand:
      result.verdict_text = cannot_stand_text(m, result);
      break;
    case Verdict::SolverFailure:
      result.verdict_text = "No answer: the conic solver failed (" +
                            std::string(conic::to_string(result.solver_info.status)) + ").";
      break;
    case Verdict::TimeLimit: result.verdict_text = "No answer: the time limit ran out."; break;
    case Verdict::IterationLimit: result.verdict_text = "No answer: the iteration limit ran out."; break;
    case Verdict::Cancelled: result.verdict_text = "Cancelled before an answer."; break;
  }
}

// The admissible multipliers form an interval [alpha_min, alpha_max] (the problem is convex).
// Maximising alpha answers "collapse at alpha_max" (or "no mechanism" when alpha_max is
// unbounded) only if alpha = 0 is in it: a block resting off-centre on a narrow post can be held
// by a push of 0.59 to 0.6 of its weight and by nothing less, and one leaning away from a wall
// by any push of at least 0.2. So alpha_min is found with the same solver (objective reversed, symbolic analysis kept);
// above the threshold the structure cannot stand under its dead load, and the dual of that solve
// (a mechanism on which the dead load does positive work) names the falling blocks.
// analysis.check_dead_load = false skips this solve.
bool stands_only_when_pushed(const model::Model& m, const model::AnalysisRequest& request,
                             const Formulation& formulation, conic::ConicSolver& solver,
                             double alpha_max, double time_left, AnalysisResult& result) {
  if (!request.check_dead_load || time_left <= 0.0) return false;
  const auto start = Clock::now();
  const Eigen::VectorXd c_max = solver.problem().c;
  solver.update_c(-c_max);
  conic::Settings& settings = solver.settings();
  const conic::Settings saved = settings;
  // Only alpha_min against the threshold below matters: a gap of a tenth of it is enough. An
  // unbounded alpha_max (no mechanism under the live load) leaves the absolute floor.
  const double threshold = std::max(1e-5, std::isfinite(alpha_max) ? 1e-3 * alpha_max : 0.0);
  settings.tol_gap_rel = settings.tol_gap_abs = 0.1 * threshold;
  settings.time_limit_seconds = std::max(time_left, 1e-6);
  const conic::Solution low = solver.solve();
  settings = saved;
  solver.update_c(c_max);
  result.solve_seconds += seconds_since(start);
  if (!conic::has_solution(low.info.status)) return false;
  const double alpha_min = multiplier_value(formulation, low.x);
  // Ten times the solve's accuracy and a visible share of alpha_max: 1e-5 absolute or 1e-3 of
  // alpha_max.
  if (!(alpha_min > threshold)) return false;
  read_certificate(m, formulation, low, result);
  result.minimum_load_multiplier = alpha_min;
  result.warnings.push_back({"stands_only_when_pushed",
                             "the structure is in equilibrium only for load multipliers from " +
                                 format(alpha_min) + " up: without the live load it cannot stand",
                             ""});
  return true;
}

// analysis.pyramid_bracket: solves the other pyramid (same faces) and records both values. In a
// planar scene both pyramids are the exact two-edge cone, so the value is the bracket.
void bracket_pyramids(const model::Model& m, const model::AnalysisRequest& request,
                      const FormulationOptions& options_used, double value, double time_left,
                      const AnalysisOptions& options, AnalysisResult& result) {
  if (request.cone == model::ConeKind::Exact || request.friction_model != model::FrictionModel::Associative) {
    result.warnings.push_back({"pyramid_bracket_not_computed",
                               "the pyramid bracket needs a pyramid cone and associative friction",
                               "/analysis/pyramid_bracket"});
    return;
  }
  const bool inscribed = request.cone == model::ConeKind::PyramidInscribed;
  if (result.planar) {
    result.accuracy.pyramid_bracket = std::make_pair(value, value);
    return;
  }
  FormulationOptions other = options_used;
  other.cone = inscribed ? model::ConeKind::PyramidCircumscribed : model::ConeKind::PyramidInscribed;
  const auto start = Clock::now();
  const Formulation formulation = build_formulation(m, other);
  result.assemble_seconds += seconds_since(start);
  const auto solve_start = Clock::now();
  conic::ConicSolver solver(formulation.problem, solver_settings(request, options, time_left));
  const conic::Solution solution = solver.solve();
  result.solve_seconds += seconds_since(solve_start);
  if (solution.info.status != conic::SolveStatus::Solved &&
      solution.info.status != conic::SolveStatus::SolvedInaccurate) {
    result.warnings.push_back({"pyramid_bracket_not_computed",
                               std::string("the other pyramid's solve ended with ") +
                                   conic::to_string(solution.info.status),
                               "/analysis/pyramid_bracket"});
    return;
  }
  const double other_value = multiplier_value(formulation, solution.x);
  result.accuracy.pyramid_bracket =
      inscribed ? std::make_pair(value, other_value) : std::make_pair(other_value, value);
}

/// Planar or 3-D, as the request and the scene allow (detect_planar).
FormulationOptions choose_formulation(const model::Model& m, AnalysisResult& result) {
  const model::AnalysisRequest& request = m.analysis;
  const PlanarFrame frame = detect_planar(m);
  if (request.formulation == model::Formulation::Planar && !frame.planar) {
    throw model::ModelError("/analysis/formulation", "the scene is not planar: " + frame.reason);
  }
  result.planar = request.formulation == model::Formulation::Planar ||
                  (request.formulation == model::Formulation::Auto && frame.planar);
  result.planar_axis = result.planar ? frame.axis : -1;
  if (result.planar && request.cone != model::ConeKind::Exact) {
    result.warnings.push_back({"pyramid_not_needed",
                               "the scene is planar: its friction cone has exactly two edges, so the pyramid "
                               "setting changes nothing",
                               "/analysis/cone"});
  }
  FormulationOptions formulation_options;
  formulation_options.cone = request.cone;
  formulation_options.pyramid_faces = request.pyramid_faces;
  formulation_options.planar = result.planar;
  formulation_options.frame = frame;
  return formulation_options;
}

AnalysisResult empty_result(const model::AnalysisRequest& request) {
  AnalysisResult result;
  result.type = request.type;
  result.friction_model = request.friction_model;
  result.cone = request.cone;
  result.pyramid_faces = request.cone == model::ConeKind::Exact ? 0 : request.pyramid_faces;
  result.settlement_direction = request.settlement_direction;
  return result;
}

/// Blocks with no load that keep an arbitrary motion larger than any loaded block's
/// (analysis/unloaded_blocks.hpp): they set the mechanism's scale, so the picture and the count of
/// moving blocks may mislead.
void warn_arbitrary_blocks(const model::Model& m, AnalysisResult& result) {
  const std::vector<int>& blocks = result.mechanism.arbitrary_blocks;
  if (blocks.empty()) return;
  const bool one = blocks.size() == 1;
  result.warnings.push_back(
      {"unloaded_block_motion",
       count(blocks.size(), "block", "blocks") + " with no load (" + quoted_block_ids(m, blocks, 3) + ") " +
           (one ? "moves" : "move") +
           " more than any loaded block in the mechanism, by an arbitrary amount: any amount of that motion "
           "gives a mechanism of the same value, and no smaller motion compatible with the contacts was "
           "found; the mechanism's scale and its count of moving blocks are set by " + (one ? "it" : "them"),
       "/blocks/" + std::to_string(blocks.front())});
}

/// The value of a collapse, in the field its analysis reports it in.
void record_value(const model::Model& m, const Formulation& formulation, double value, AnalysisResult& result) {
  if (formulation.settlement) {
    result.base_reaction = value;
    record_initial_reaction(m, result);
  } else {
    result.load_multiplier = value;
  }
}

/// The connectivity check (connectivity.hpp), before any solve: a group of free blocks joined to
/// no support that carries dead load decides the verdict; one that carries none is only a warning.
bool unsupported_blocks_fall(const model::Model& m, AnalysisResult& result) {
  result.connectivity = check_connectivity(m);
  for (const UnsupportedGroup& group : result.connectivity.groups) {
    if (group.carries_dead_load) continue;
    result.warnings.push_back({"unsupported_unloaded_blocks",
                               count(group.blocks.size(), "block", "blocks") + " from '" +
                                   m.blocks[group.blocks.front()].id +
                                   "' on are joined to no support; they carry no dead load, so only a live load "
                                   "on them can move them",
                               "/blocks/" + std::to_string(group.blocks.front())});
  }
  if (result.connectivity.num_falling_blocks() == 0) return false;
  result.verdict = Verdict::CannotStand;
  falling_groups_mechanism(m, result.connectivity, result.mechanism);
  return true;
}

/// The verdict of the first solve, completed: the certificate of a structure that cannot stand,
/// or the dead-load check of a load multiplier whether the live load finds a collapse or none.
/// Returns true when the answer is a collapse the strategies may refine.
bool settle_verdict(const model::Model& m, const Formulation& formulation, conic::ConicSolver& solver,
                    const conic::Solution& solution, const Deadline& deadline, AnalysisResult& result) {
  if (result.verdict == Verdict::CannotStand) {
    read_certificate(m, formulation, solution, result);
    return false;
  }
  const bool bounded = result.verdict == Verdict::Collapse;
  if ((bounded || result.verdict == Verdict::NoMechanism) && !formulation.settlement) {
    const double alpha_max =
        bounded ? multiplier_value(formulation, solution.x) : std::numeric_limits<double>::infinity();
    if (stands_only_when_pushed(m, m.analysis, formulation, solver, alpha_max, deadline.left(), result)) {
      result.verdict = Verdict::CannotStand;
      return false;
    }
  }
  return bounded;
}

/// The gap at which a search keeps the iterate for the next analysis (as the non-associative
/// steps do): early enough to sit well inside the cone, late enough to carry the structure of
/// the solution.
constexpr double kSearchSnapshotGap = 1e-2;

/// Starts `solver` from a search's previous point when it fits this problem.
void warm_start_from(const conic::Iterate* point, const conic::ConicProblem& problem, conic::ConicSolver& solver) {
  if (!point || point->empty()) return;
  if (point->x.size() != problem.A.cols() || point->y.size() != problem.A.rows()) return;
  solver.set_warm_start(point->x, point->y, point->z);
}

}  // namespace

// The pipeline (STYLE.md, "analysis as a pipeline"): formulation, the connectivity check, the
// associative solve, its verdict (with the dead-load check for a load multiplier), then the
// strategies that refine a collapse (pyramid bracket, non-associative scheme), and the sentence
// for people.
AnalysisResult analyse(const model::Model& m, const AnalysisOptions& options) {
  const Deadline deadline{Clock::now(), m.analysis.time_limit_seconds};
  const model::AnalysisRequest& request = m.analysis;
  AnalysisResult result = empty_result(request);

  FormulationOptions formulation_options = choose_formulation(m, result);
  formulation_options.pattern_for_every_direction = options.reuse != nullptr;
  const Formulation formulation = build_formulation(m, formulation_options);
  result.warnings.insert(result.warnings.end(), formulation.warnings.begin(), formulation.warnings.end());
  record_size(formulation, result);
  result.assemble_seconds = seconds_since(deadline.start);
  if (options.problem_ready) options.problem_ready(formulation.problem);
  if (unsupported_blocks_fall(m, result)) {
    write_verdict_text(m, result);
    return result;
  }

  if (deadline.left() <= 0.0) {
    result.verdict = Verdict::TimeLimit;
    write_verdict_text(m, result);
    return result;
  }
  const auto solve_start = Clock::now();
  conic::Settings settings = solver_settings(request, options, deadline.left());
  if (options.warm_start) settings.snapshot_gap_rel = kSearchSnapshotGap;
  if (request.friction_model == model::FrictionModel::NonAssociative && request.non_associative_warm_start)
    settings.snapshot_gap_rel = kNonAssociativeSnapshotGap;
  SolverReuse own;
  conic::ConicSolver& solver = (options.reuse ? *options.reuse : own).solver_for(formulation.problem, settings);
  solver.set_progress_callback(options.progress);
  warm_start_from(options.warm_start, formulation.problem, solver);
  conic::Solution solution = solver.solve();
  if (options.warm_start && !solution.snapshot.empty()) *options.warm_start = solution.snapshot;
  result.solve_seconds += seconds_since(solve_start);
  result.solver_ran = true;
  result.solver_info = solution.info;
  result.interior_point_history = solution.info.history;
  result.verdict = verdict_of(solution.info.status, formulation.settlement);
  if (solution.info.status == conic::SolveStatus::SolvedInaccurate) {
    result.warnings.push_back({"inaccurate_solution",
                               "the conic solver met only its reduced tolerances (relative gap " +
                                   format(solution.info.gap_rel, 3) + ")",
                               ""});
  }

  const bool no_settlement_mechanism =
      settlement_forms_no_mechanism(m, options, formulation_options, formulation, solution, deadline, result);
  if (no_settlement_mechanism) record_initial_reaction(m, result);
  if (!no_settlement_mechanism && settle_verdict(m, formulation, solver, solution, deadline, result)) {
    read_solution(m, formulation, solution, true, result);
    double value = multiplier_value(formulation, solution.x);
    if (request.pyramid_bracket) {
      bracket_pyramids(m, request, formulation_options, value, deadline.left(), options, result);
    }
    if (request.friction_model == model::FrictionModel::NonAssociative) {
      run_non_associative(m, formulation, solver, solution, deadline, value, result);
    }
    if (result.verdict == Verdict::Collapse) {
      record_value(m, formulation, value, result);
      result.sensitivities = collapse_sensitivities(m, result);
    }
  }
  warn_arbitrary_blocks(m, result);
  warn_no_associative_mechanism(result);
  write_verdict_text(m, result);
  return result;
}

}  // namespace rbla::analysis
