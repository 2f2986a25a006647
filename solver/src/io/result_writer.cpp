#include "io/result_writer.hpp"

#include "io/detection_json.hpp"
#include "io/json_values.hpp"
#include "io/sensitivities_json.hpp"
#include "io/warning_summary.hpp"

#include <algorithm>

namespace rbla::io {

using nlohmann::json;

namespace {


/// The result schema's `solver.status` names (conic::to_string gives the log's wording instead).
const char* status_name(conic::SolveStatus status) {
  switch (status) {
    case conic::SolveStatus::Solved: return "solved";
    case conic::SolveStatus::SolvedInaccurate: return "solved_inaccurate";
    case conic::SolveStatus::PrimalInfeasible: return "primal_infeasible";
    case conic::SolveStatus::DualInfeasible: return "dual_infeasible";
    case conic::SolveStatus::IterationLimit: return "iteration_limit";
    case conic::SolveStatus::TimeLimit: return "time_limit";
    case conic::SolveStatus::NumericalFailure: return "numerical_failure";
    case conic::SolveStatus::Cancelled: return "cancelled";
  }
  return "numerical_failure";
}

}  // namespace

json model_summary_json(const model::Model& model) {
  std::size_t free_blocks = 0, fixed_blocks = 0, moving_blocks = 0, detected = 0;
  double total_weight = 0.0;
  for (const auto& block : model.blocks) {
    switch (block.role) {
      case model::BlockRole::Free:
        ++free_blocks;
        total_weight += block.weight();
        break;
      case model::BlockRole::Fixed: ++fixed_blocks; break;
      case model::BlockRole::MovingSupport: ++moving_blocks; break;
    }
  }
  for (const auto& contact : model.interfaces) detected += contact.detected ? 1 : 0;
  const model::BoundingBox box = model.bounding_box();
  const double l = model.units.length_to_m;
  return json{{"num_blocks", model.blocks.size()},
              {"num_free_blocks", free_blocks},
              {"num_fixed_blocks", fixed_blocks},
              {"num_moving_blocks", moving_blocks},
              {"num_interfaces", model.interfaces.size()},
              {"num_contact_points", model.num_contact_points()},
              {"num_detected_interfaces", detected},
              {"bounding_box", {{"min", vec3_json(box.min / l)}, {"max", vec3_json(box.max / l)}}},
              {"total_weight", total_weight / model.units.force_to_kN}};
}

namespace {

json warning_json(const model::Warning& warning) {
  json entry{{"code", warning.code}, {"message", warning.message}};
  if (!warning.pointer.empty()) entry["pointer"] = warning.pointer;
  return entry;
}

}  // namespace

json warnings_json(const std::vector<model::Warning>& warnings) {
  json list = json::array();
  for (const std::size_t i : listed_warnings(warnings)) list.push_back(warning_json(warnings[i]));
  return list;
}

json warning_summary_json(const std::vector<model::Warning>& warnings) {
  const std::vector<std::size_t> listed = listed_warnings(warnings);
  json summary = json::array();
  for (const WarningKind& kind : summarise_warnings(warnings)) {
    const auto written = std::count_if(listed.begin(), listed.end(),
                                       [&](std::size_t i) { return warnings[i].code == kind.code; });
    summary.push_back({{"code", kind.code}, {"count", kind.count}, {"listed", written}});
  }
  return summary;
}

json model_only_result(const model::Model& model, const model::StageTimings& timings, const std::string& source) {
  json result{{"schema_version", "1.11.0"},
              {"rbla_version", RBLA_VERSION},
              {"status", "model_only"},
              {"verdict", "Model read and checked; no analysis was run."},
              {"units", {{"length", model.units.length_name}, {"force", model.units.force_name}}},
              {"model_summary", model_summary_json(model)},
              {"warnings", warnings_json(model.warnings)},
              {"timings",
               {{"read_seconds", timings.read_seconds},
                {"validate_seconds", timings.validate_seconds},
                {"geometry_seconds", timings.geometry_seconds},
                {"detect_seconds", timings.detect_seconds},
                {"total_seconds", timings.total_seconds}}}};
  if (!model.warnings.empty()) result["warning_summary"] = warning_summary_json(model.warnings);
  json source_info = json::object();
  if (!source.empty() && source != "-") source_info["source"] = source;
  if (!model.title.empty()) source_info["title"] = model.title;
  if (!source_info.empty()) result["model"] = source_info;
  if (model.detection_summary.ran) result["detection"] = detection_json(model);
  return result;
}

}  // namespace rbla::io

namespace rbla::io {

namespace {

const char* axis_name(int axis) { return axis == 0 ? "x" : axis == 1 ? "y" : "z"; }

/// Numbers the solver reports as -1e-13 for a force that is zero: the schema says >= 0.
double non_negative(double value) { return value < 0.0 ? 0.0 : value; }

json timings_json(const model::StageTimings& timings, const analysis::AnalysisResult& result) {
  return json{{"read_seconds", timings.read_seconds},       {"validate_seconds", timings.validate_seconds},
              {"geometry_seconds", timings.geometry_seconds}, {"detect_seconds", timings.detect_seconds},
              {"assemble_seconds", result.assemble_seconds},  {"solve_seconds", result.solve_seconds},
              {"mechanism_seconds", result.mechanism_seconds}, {"write_seconds", timings.write_seconds},
              {"total_seconds", timings.total_seconds}};
}

/// Near misses of interface detection listed with a connectivity verdict (the count is given).
constexpr std::size_t kMaxNearMissesListed = 100;

json connectivity_json(const model::Model& model, const analysis::Connectivity& connectivity) {
  const double l = model.units.length_to_m;
  json groups = json::array();
  std::size_t unsupported = 0;
  for (const analysis::UnsupportedGroup& group : connectivity.groups) {
    json ids = json::array();
    for (int b : group.blocks) ids.push_back(model.blocks[b].id);
    unsupported += group.blocks.size();
    groups.push_back({{"blocks", ids},
                      {"touches_nothing", group.touches_nothing},
                      {"carries_dead_load", group.carries_dead_load}});
  }
  json misses = json::array();
  for (std::size_t k = 0; k < connectivity.near_misses_at_groups.size() && k < kMaxNearMissesListed; ++k) {
    const model::NearMiss& miss = model.near_misses[connectivity.near_misses_at_groups[k]];
    misses.push_back({{"blocks", {model.blocks[miss.block_a].id, model.blocks[miss.block_b].id}},
                      {"faces", {miss.face_a, miss.face_b}},
                      {"distance", miss.distance / l},
                      {"angle_degrees", miss.angle_degrees},
                      {"overlap_area", miss.overlap_area / (l * l)}});
  }
  return json{{"num_unsupported_blocks", unsupported},
              {"unsupported_groups", groups},
              {"num_near_misses", connectivity.num_near_misses},
              {"num_near_misses_at_unsupported", connectivity.near_misses_at_groups.size()},
              {"near_misses", misses}};
}

/// The `analysis` section: what was solved.
json analysis_settings_json(const analysis::AnalysisResult& result) {
  json analysis{{"type", model::to_string(result.type)},
                {"friction_model", model::to_string(result.friction_model)},
                {"cone", model::to_string(result.cone)},
                {"formulation", result.planar ? "planar" : "3d"}};
  if (result.cone != model::ConeKind::Exact) analysis["pyramid_faces"] = result.pyramid_faces;
  if (result.planar) analysis["planar_axis"] = axis_name(result.planar_axis);
  return analysis;
}

/// The `solver` section: the conic solver's outcome and the problem's size.
json solver_json(const analysis::AnalysisResult& result) {
  const conic::Info& info = result.solver_info;
  return json{{"name", "rbla conic interior point (" + info.backend + ")"},
              {"version", RBLA_VERSION},
              {"status", status_name(info.status)},
              {"iterations", info.iterations},
              {"primal_objective", info.primal_objective},
              {"dual_objective", info.dual_objective},
              {"num_variables", result.size.num_variables},
              {"num_equality_rows", result.size.num_equality_rows},
              {"num_cones", result.size.num_cones},
              {"num_nonzeros", result.size.num_nonzeros}};
}

json interior_point_history_json(const analysis::AnalysisResult& result) {
  json ipm = json::array();
  for (const auto& row : result.interior_point_history) {
    ipm.push_back({{"iteration", row.iteration},
                   {"primal_objective", row.primal_objective},
                   {"dual_objective", row.dual_objective},
                   {"relative_gap", row.gap_rel},
                   {"primal_residual", row.res_primal},
                   {"dual_residual", row.res_dual},
                   {"step", row.step},
                   {"mu", row.mu}});
  }
  return ipm;
}

/// The non-associative scheme's steps and outcome, added to the `convergence` section. Values are
/// load multipliers, or base reactions in the model's force unit under settlement.
void add_non_associative_convergence(const model::Model& model, const analysis::AnalysisResult& result,
                                     json& convergence) {
  const double f = model.units.force_to_kN;
  json steps = json::array();
  const double value_unit = result.type == model::AnalysisType::Settlement ? f : 1.0;
  for (const auto& step : result.non_associative) {
    // The analysis numbers the first (associative) solve 0; the schema counts solves from 1.
    steps.push_back({{"iteration", step.iteration + 1},
                     {"load_multiplier", non_negative(step.value / value_unit)},
                     {"max_normal_force_change", step.max_normal_force_change / f},
                     {"dilatancy", step.dilatancy},
                     {"shift_change", step.shift_change},
                     {"interior_point_iterations", step.interior_point_iterations},
                     {"seconds", step.seconds}});
  }
  convergence["non_associative"] = steps;
  convergence["non_associative_converged"] = result.non_associative_converged;
  if (!result.non_associative_stop.empty()) convergence["non_associative_stop"] = result.non_associative_stop;
  convergence["non_associative_checks"] = result.non_associative_checks;
  if (result.non_associative_checks > 0) convergence["non_associative_gap"] = result.non_associative_gap;
  if (result.non_associative_range) {
    convergence["non_associative_range"] = {{"low", non_negative(result.non_associative_range->first / value_unit)},
                                            {"high", non_negative(result.non_associative_range->second / value_unit)}};
  }
  if (result.non_associative_pointwise) {
    convergence["non_associative_pointwise"] = *result.non_associative_pointwise;
    if (!*result.non_associative_pointwise) {
      convergence["non_associative_open_force"] = result.non_associative_open_force;
      convergence["non_associative_friction_shortfall"] = result.non_associative_friction_shortfall;
    }
  }
  if (result.non_associative_bound) {
    convergence["non_associative_bound"] = non_negative(*result.non_associative_bound / value_unit);
  }
  json runs = json::array();
  for (std::size_t k = 0; k < result.non_associative_trajectories.size(); ++k) {
    const analysis::NonAssociativeTrajectory& t = result.non_associative_trajectories[k];
    json run{{"run", k + 1},
                    {"test_schedule", {{"when_close", t.schedule.when_close}, {"at_most", t.schedule.at_most}}},
                    {"value", non_negative(t.value / value_unit)},
                    {"certified", t.converged},
                    {"reported", static_cast<int>(k) == result.non_associative_reported},
                    {"steps", t.steps},
                    {"checks", t.checks},
                    {"seconds", t.seconds},
                    {"step_iterations", t.step_iterations},
                    {"test_iterations", t.test_iterations}};
    if (t.pointwise) run["pointwise"] = *t.pointwise;
    runs.push_back(run);
  }
  if (!runs.empty()) convergence["non_associative_trajectories"] = runs;
}

/// The `base_reaction` section of a settlement analysis (model force units).
json base_reaction_json(const model::Model& model, const analysis::AnalysisResult& result) {
  const double f = model.units.force_to_kN;
  json moving = json::array();
  for (const auto& block : model.blocks) {
    if (block.role == model::BlockRole::MovingSupport) moving.push_back(block.id);
  }
  const model::Vec3& d = result.settlement_direction;
  json out{{"at_collapse", non_negative(*result.base_reaction / f)},
           // + 0.0 turns a negated zero (-0.0, from flipping gravity) into 0.
           {"direction", {d.x() + 0.0, d.y() + 0.0, d.z() + 0.0}},
           {"moving_blocks", moving}};
  if (result.initial_base_reaction) {
    // The loss is the difference of the two values as written (both clamped at 0 alike).
    const double initial = non_negative(*result.initial_base_reaction / f);
    out["initial"] = initial;
    out["loss"] = initial - non_negative(*result.base_reaction / f);
    out["initial_base_lifts"] = result.initial_base_lifts;
  }
  return out;
}

/// The `mechanism` section: how the displacements are normalised and the scale to draw them at.
json mechanism_json(const model::Model& model, const analysis::AnalysisResult& result) {
  const double l = model.units.length_to_m;
  const bool settlement = result.mechanism.normalisation == analysis::Normalisation::UnitSettlement;
  const model::BoundingBox box = model.bounding_box();
  // Drawn at 5 % of the model's size for the largest vertex displacement (which is 1 unit).
  double largest = 0.0;
  for (const auto& block : result.mechanism.blocks) {
    if (block.moving) largest = std::max(largest, block.translation.norm() / l);
  }
  const double scale = 0.05 * box.diagonal() / l / std::max(largest, 1.0);
  return json{{"normalisation", settlement ? "unit_settlement" : "max_translation"},
              {"scale_note", settlement ? "the moving supports settle by 1 length unit"
                                        : "the largest vertex displacement of a free block is 1 length unit"},
              {"displacement_scale", scale}};
}

/// The `blocks` section: every block's virtual displacement (model length units, rad).
json block_motions_json(const model::Model& model, const analysis::AnalysisResult& result) {
  const double l = model.units.length_to_m;
  json blocks = json::array();
  for (std::size_t b = 0; b < model.blocks.size(); ++b) {
    const auto& motion = result.mechanism.blocks[b];
    const model::Vec3 t = motion.translation / l;
    json entry{{"id", model.blocks[b].id},
               {"role", model::to_string(model.blocks[b].role)},
               {"translation", {t.x(), t.y(), t.z()}},
               {"rotation", {motion.rotation.x(), motion.rotation.y(), motion.rotation.z()}}};
    if (result.verdict == analysis::Verdict::CannotStand) entry["falling"] = motion.moving;
    blocks.push_back(std::move(entry));
  }
  return blocks;
}

/// One interface of the `interfaces` section, its contact points with their states and, when the
/// forces are known (a collapse), their forces (model force units).
json interface_json(const model::Model& model, const model::ContactInterface& c, const analysis::InterfaceResult& r,
                    bool forces_known, bool with_points) {
  const double l = model.units.length_to_m;
  const double f = model.units.force_to_kN;
  json entry{{"id", c.id},
             {"blocks", {model.blocks[c.block_a].id, model.blocks[c.block_b].id}},
             {"normal", {c.normal.x(), c.normal.y(), c.normal.z()}},
             {"tangents", {{c.tangent1.x(), c.tangent1.y(), c.tangent1.z()}, {c.tangent2.x(), c.tangent2.y(), c.tangent2.z()}}},
             {"area", c.area / (l * l)},
             {"state", analysis::to_string(r.state)},
             {"cracked", r.cracked}};
  if (!c.label.empty()) entry["label"] = c.label;
  if (forces_known) entry["resultant"] = {{"normal_force", r.normal_force / f}, {"shear_force", r.shear_force / f}};
  if (!with_points) return entry;
  json points = json::array();
  for (const auto& p : r.points) {
    json point{{"position", {p.position.x() / l, p.position.y() / l, p.position.z() / l}},
               {"relative_velocity", {p.relative_velocity.x() / l, p.relative_velocity.y() / l, p.relative_velocity.z() / l}},
               {"state", analysis::to_string(p.state)}};
    if (forces_known) {
      point["normal_force"] = non_negative(p.normal_force / f);
      point["shear_force"] = {p.shear1 / f, p.shear2 / f};
    }
    points.push_back(std::move(point));
  }
  entry["points"] = points;
  return entry;
}

/// The mechanism's sections: `mechanism`, `blocks`, `interfaces` (unless `detail` is Blocks) and
/// `cracked_interfaces`.
void add_mechanism(const model::Model& model, const analysis::AnalysisResult& result, ResultDetail detail,
                   json& out) {
  out["mechanism"] = mechanism_json(model, result);
  out["blocks"] = block_motions_json(model, result);
  json interfaces = json::array();
  json cracked = json::array();
  const bool forces_known = result.verdict == analysis::Verdict::Collapse;
  for (std::size_t i = 0; i < model.interfaces.size(); ++i) {
    const model::ContactInterface& c = model.interfaces[i];
    const analysis::InterfaceResult& r = result.mechanism.interfaces[i];
    if (detail != ResultDetail::Blocks) {
      interfaces.push_back(interface_json(model, c, r, forces_known, detail == ResultDetail::Points));
    }
    if (r.cracked) cracked.push_back(c.id);
  }
  if (detail != ResultDetail::Blocks) out["interfaces"] = interfaces;
  out["cracked_interfaces"] = cracked;
}

/// The `work_balance`, `accuracy` and (when computed) `sensitivities` sections of a collapse.
void add_collapse_checks(const model::Model& model, const analysis::AnalysisResult& result, json& out) {
  const double l = model.units.length_to_m;
  const double f = model.units.force_to_kN;
  const bool settlement = result.type == model::AnalysisType::Settlement;
  const double work_unit = f * l;  // kN m per (user force x user length)
  out["work_balance"] = {{"external_work_live", result.work.live_work / work_unit},
                         {"external_work_dead", result.work.dead_work / work_unit},
                         {"dissipation", result.work.dissipation / work_unit},
                         {"kinematic_value", settlement ? result.work.kinematic_value / f : result.work.kinematic_value},
                         {"relative_error", result.work.relative_error}};
  out["accuracy"] = {{"relative_gap", result.accuracy.relative_gap},
                     {"primal_residual", result.accuracy.primal_residual},
                     {"dual_residual", result.accuracy.dual_residual},
                     {"equilibrium_residual", result.accuracy.equilibrium_residual / f}};
  if (result.accuracy.pyramid_bracket) {
    // alpha is dimensionless; a base reaction is a force in model units.
    const double unit = result.base_reaction ? f : 1.0;
    out["accuracy"]["pyramid_bracket"] = {
        {"inscribed", non_negative(result.accuracy.pyramid_bracket->first / unit)},
        {"circumscribed", non_negative(result.accuracy.pyramid_bracket->second / unit)}};
  }
  if (result.sensitivities) out["sensitivities"] = sensitivities_json(model, *result.sensitivities);
}

}  // namespace

const char* to_string(ResultDetail detail) {
  switch (detail) {
    case ResultDetail::Points: return "points";
    case ResultDetail::Interfaces: return "interfaces";
    case ResultDetail::Blocks: return "blocks";
  }
  return "?";
}

bool parse_detail(const std::string& name, ResultDetail& detail) {
  for (const ResultDetail d : {ResultDetail::Points, ResultDetail::Interfaces, ResultDetail::Blocks}) {
    if (name == to_string(d)) {
      detail = d;
      return true;
    }
  }
  return false;
}

json analysis_result_json(const model::Model& model, const analysis::AnalysisResult& result,
                          const model::StageTimings& timings, const std::string& source, ResultDetail detail) {
  using analysis::Verdict;
  json out = model_only_result(model, timings, source);
  out["detail"] = to_string(detail);
  out["status"] = analysis::to_string(result.verdict);
  out["verdict"] = result.verdict_text;
  out["timings"] = timings_json(timings, result);
  out["analysis"] = analysis_settings_json(result);
  if (result.connectivity.checked) out["connectivity"] = connectivity_json(model, result.connectivity);
  if (result.solver_ran) out["solver"] = solver_json(result);

  json convergence{{"interior_point", interior_point_history_json(result)}};
  // The scheme starts from a collapse state of the associative analysis; with no mechanism, or
  // none that can stand, it did not run and has nothing to report.
  if (result.friction_model == model::FrictionModel::NonAssociative && !result.non_associative.empty()) {
    add_non_associative_convergence(model, result, convergence);
  }
  out["convergence"] = convergence;

  if (result.load_multiplier) out["load_multiplier"] = non_negative(*result.load_multiplier);
  if (result.minimum_load_multiplier) out["minimum_load_multiplier"] = non_negative(*result.minimum_load_multiplier);
  if (result.base_reaction) out["base_reaction"] = base_reaction_json(model, result);
  const bool has_mechanism = result.verdict == Verdict::Collapse || result.verdict == Verdict::CannotStand;
  if (has_mechanism && !result.mechanism.blocks.empty()) add_mechanism(model, result, detail, out);
  if (result.verdict == Verdict::Collapse) add_collapse_checks(model, result, out);

  std::vector<model::Warning> warnings = model.warnings;
  warnings.insert(warnings.end(), result.warnings.begin(), result.warnings.end());
  out["warnings"] = warnings_json(warnings);
  if (!warnings.empty()) out["warning_summary"] = warning_summary_json(warnings);
  return out;
}

}  // namespace rbla::io
