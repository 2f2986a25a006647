// `rbla validate` and `rbla info`: the model stage alone.
#include "commands.hpp"

#include "io/result_writer.hpp"

#include <iomanip>
#include <iostream>
#include <sstream>

namespace rbla::cli {
namespace {

int run_validate(const CommonOptions& options) {
  io::LoadedModel loaded;
  int exit_code = kSuccess;
  if (!load(options, loaded, exit_code)) return exit_code;
  std::cout << "valid: " << loaded.model.blocks.size() << " blocks, " << loaded.model.interfaces.size()
            << " interfaces, " << loaded.model.num_contact_points() << " contact points, "
            << loaded.model.warnings.size() << " warnings\n";
  return kSuccess;
}

/// What detection did, for `rbla info`: tolerances, the spread over accepted joints, near misses.
void print_detection(const model::Model& m, std::ostream& out) {
  const model::DetectionSummary& s = m.detection_summary;
  if (!s.ran) return;
  std::ostringstream line;
  line << std::setprecision(3);
  if (s.per_joint) {
    line << s.joint_tolerance * 100.0 << " % of each joint's size";
    if (s.distance_tolerances.count > 0) {
      line << " (" << model::length_text(s.distance_tolerances.min, m.units) << " to "
           << model::length_text(s.distance_tolerances.max, m.units) << " here)";
    }
    line << ", faces at most " << model::length_text(s.clearance_limit, m.units) << " apart at their nearest";
  } else {
    line << model::length_text(s.fixed_distance, m.units) << " for every joint (set in the model)";
  }
  line << ", angle " << s.angle_tolerance_degrees << " deg; " << s.merged_faces << " split faces merged";
  out << "detection:       " << line.str() << "\n";
  if (s.gaps.count > 0) {
    std::ostringstream spread;
    spread << std::setprecision(3) << "gap " << model::length_text(s.gaps.min, m.units) << " / "
           << model::length_text(s.gaps.median, m.units) << " / " << model::length_text(s.gaps.max, m.units) << " (at most "
           << 100.0 * s.largest_gap_fraction << " % of its tolerance), angle " << s.angles.min << " / "
           << s.angles.median << " / " << s.angles.max << " deg";
    out << "accepted joints: " << spread.str() << " (min / median / max)\n";
  }
  out << "near misses:     " << s.near_misses_total;
  if (!m.near_misses.empty()) {
    const model::NearMiss& n = m.near_misses.front();
    std::ostringstream closest;
    closest << std::setprecision(3) << " (closest: '" << m.blocks[n.block_a].id << "' face " << n.face_a << " and '"
            << m.blocks[n.block_b].id << "' face " << n.face_b << ", " << model::length_text(n.distance, m.units)
            << " apart where " << model::length_text(n.distance_tolerance, m.units) << " is accepted, at "
            << n.angle_degrees << " deg; all listed by -o)";
    out << closest.str();
  }
  out << "\n";
}

int run_info(const CommonOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const bool stdout_taken = check_paths(options);
  io::LoadedModel loaded;
  int exit_code = kSuccess;
  if (!load(options, loaded, exit_code)) return exit_code;
  const model::Model& m = loaded.model;
  const nlohmann::json summary = io::model_summary_json(m);
  const auto& box = summary["bounding_box"];
  std::ostream& out = stdout_taken ? std::cerr : std::cout;
  out << "title:           " << (m.title.empty() ? "(none)" : shown(m.title)) << "\n"
      << "units:           length " << m.units.length_name << ", force " << m.units.force_name << ", unit weight "
      << m.units.unit_weight_name << ", gravity " << m.gravity_axis << "\n"
      << "blocks:          " << summary["num_blocks"] << " (free " << summary["num_free_blocks"] << ", fixed "
      << summary["num_fixed_blocks"] << ", moving supports " << summary["num_moving_blocks"] << ")\n"
      << "interfaces:      " << summary["num_interfaces"] << " (detected " << summary["num_detected_interfaces"]
      << ")\n"
      << "contact points:  " << summary["num_contact_points"] << "\n"
      << "bounding box:    " << box["min"].dump() << " .. " << box["max"].dump() << " " << m.units.length_name << "\n"
      << "total weight:    " << summary["total_weight"].get<double>() << " " << m.units.force_name
      << " (free blocks)\n"
      << "analysis:        " << model::to_string(m.analysis.type) << ", "
      << model::to_string(m.analysis.friction_model) << ", cone " << model::to_string(m.analysis.cone)
      << "\n"
      << "warnings:        " << m.warnings.size() << "\n";
  print_detection(m, out);
  out << "model stage:     " << seconds_text(loaded.timings.total_seconds) << " (read "
      << seconds_text(loaded.timings.read_seconds) << ", validate " << seconds_text(loaded.timings.validate_seconds)
      << ", geometry " << seconds_text(loaded.timings.geometry_seconds) << ", detection "
      << seconds_text(loaded.timings.detect_seconds) << ")\n";
  if (!options.output_path.empty()) {
    model::StageTimings timings = loaded.timings;
    timings.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const nlohmann::json result = io::model_only_result(m, timings, options.model_path);
    return write_output(options.output_path, result.dump(1) + "\n");
  }
  return kSuccess;
}

}  // namespace

Command add_validate(CLI::App& app, CommonOptions& options) {
  CLI::App* validate = app.add_subcommand("validate", "Check a model against the schema and its geometry");
  validate->add_option("model", options.model_path, "Model JSON file ('-' for standard input)")->required();
  validate->add_flag("-q,--quiet", options.quiet, "No progress or warnings on standard error");
  validate->add_flag("-v,--verbose", options.verbose, "Every warning on its own line (default: one line per kind)");
  add_input_limits(validate, options.limits);

  return {validate, [&options] { return run_validate(options); }};
}

Command add_info(CLI::App& app, CommonOptions& options) {
  CLI::App* info = app.add_subcommand("info", "Summarise a model: blocks, interfaces, contact points, warnings");
  info->add_option("model", options.model_path, "Model JSON file ('-' for standard input)")->required();
  info->add_option("-o,--output", options.output_path,
                   "Also write the summary as a result JSON with status model_only ('-' for standard output)");
  info->add_flag("-q,--quiet", options.quiet, "No progress or warnings on standard error");
  info->add_flag("-v,--verbose", options.verbose, "Every warning on its own line (default: one line per kind)");
  add_input_limits(info, options.limits);
  return {info, [&options] { return run_info(options); }};
}

}  // namespace rbla::cli
