// rbla: the command-line program. Thin by design: every step is a library call the tests make too.
//
// Exit codes (also in README.md):
//   0  success (the verdict may be "cannot stand" or "no mechanism": those are answers)
//   1  usage error (unknown command or option)
//   2  invalid input (the message names the JSON pointer and what was expected), limits included
//   3  solver failure (numerical failure, time or iteration limit)
//   4  a file could not be read or written (the message names the path)
#include "analysis/limit_analysis.hpp"
#include "io/atomic_file.hpp"
#include "io/file_error.hpp"
#include "io/input_limits.hpp"
#include "io/load_model.hpp"
#include "io/model_reader.hpp"
#include "io/printable.hpp"
#include "io/problem_file.hpp"
#include "io/result_writer.hpp"
#include "io/svg_writer.hpp"
#include "io/sweep_io.hpp"
#include "io/critical_friction_json.hpp"
#include "io/worst_direction_json.hpp"
#include "io/warning_summary.hpp"
#include "model/errors.hpp"

#include <CLI/CLI.hpp>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>

namespace {

enum ExitCode : int {
  kSuccess = 0,
  kUsage = 1,
  kInvalidInput = 2,
  kSolverFailure = 3,
  kFileError = 4,
};

/// A whole message as printed: user text inside is escaped (io/printable.hpp) and very long
/// messages are cut.
std::string shown(const std::string& text) { return rbla::io::printable(text, 4000); }

struct CommonOptions {
  std::string model_path;
  std::string output_path;
  std::string svg_dir;
  std::string dump_problem_path;
  bool quiet = false;
  bool verbose = false;
  int threads = 2;
  rbla::io::InputLimits limits;
};

/// The folder --svg writes into and the two files in it.
std::filesystem::path svg_file(const CommonOptions& options, const char* name) {
  return std::filesystem::path(options.svg_dir) / name;
}


void progress(const CommonOptions& options, const std::string& line) {
  if (!options.quiet) std::cerr << "rbla: " << shown(line) << "\n";
}

std::string seconds_text(double seconds) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(3) << seconds << " s";
  return out.str();
}

/// Every warning printed goes through here: one line per kind with its count and worst instance
/// (io/warning_summary.hpp), or each warning with -v.
void report_warnings(const std::vector<rbla::model::Warning>& warnings, const CommonOptions& options) {
  if (options.quiet) return;
  for (const std::string& line : rbla::io::warning_lines(warnings, options.verbose)) {
    std::cerr << "rbla: warning " << shown(line) << "\n";
  }
}

int report_invalid(const rbla::model::ModelError& error) {
  std::cerr << "rbla: invalid input:\n";
  for (const auto& issue : error.issues()) {
    std::cerr << "  " << (issue.pointer.empty() ? "(document)" : rbla::io::printable(issue.pointer, 300)) << ": "
              << shown(issue.message) << "\n";
  }
  return kInvalidInput;
}

int report_file_error(const rbla::io::FileError& error) {
  std::cerr << "rbla: " << shown(error.what()) << "\n";
  return kFileError;
}

/// Loads the model with progress lines; returns false (after reporting) on invalid input.
bool load(const CommonOptions& options, rbla::io::LoadedModel& loaded, int& exit_code) {
  progress(options, "reading " + (options.model_path == "-" ? std::string("standard input") : options.model_path));
  try {
    loaded = rbla::io::load_model_file(options.model_path, options.limits);
  } catch (const rbla::model::ModelError& error) {
    exit_code = report_invalid(error);
    return false;
  } catch (const rbla::io::FileError& error) {
    exit_code = report_file_error(error);
    return false;
  }
  const auto& m = loaded.model;
  progress(options, "model: " + std::to_string(m.blocks.size()) + " blocks, " + std::to_string(m.interfaces.size()) +
                        " interfaces, " + std::to_string(m.num_contact_points()) + " contact points (read+validate " +
                        seconds_text(loaded.timings.read_seconds + loaded.timings.validate_seconds) + ", geometry " +
                        seconds_text(loaded.timings.geometry_seconds) + ", detection " +
                        seconds_text(loaded.timings.detect_seconds) + ")");
  report_warnings(m.warnings, options);
  return true;
}

int run_validate(const CommonOptions& options) {
  rbla::io::LoadedModel loaded;
  int exit_code = kSuccess;
  if (!load(options, loaded, exit_code)) return exit_code;
  std::cout << "valid: " << loaded.model.blocks.size() << " blocks, " << loaded.model.interfaces.size()
            << " interfaces, " << loaded.model.num_contact_points() << " contact points, "
            << loaded.model.warnings.size() << " warnings\n";
  return kSuccess;
}

int write_output(const std::string& path, const std::string& text) {
  try {
    rbla::io::write_file_atomically(path, text);
  } catch (const rbla::io::FileError& error) {
    return report_file_error(error);
  }
  return kSuccess;
}

/// What detection did, for `rbla info`: tolerances, the spread over accepted joints, near misses.
void print_detection(const rbla::model::Model& m, std::ostream& out) {
  const rbla::model::DetectionSummary& s = m.detection_summary;
  if (!s.ran) return;
  std::ostringstream line;
  line << std::setprecision(3);
  if (s.per_joint) {
    line << s.joint_tolerance * 100.0 << " % of each joint's size";
    if (s.distance_tolerances.count > 0) {
      line << " (" << rbla::model::length_text(s.distance_tolerances.min, m.units) << " to "
           << rbla::model::length_text(s.distance_tolerances.max, m.units) << " here)";
    }
  } else {
    line << rbla::model::length_text(s.fixed_distance, m.units) << " for every joint (set in the model)";
  }
  line << ", angle " << s.angle_tolerance_degrees << " deg; " << s.merged_faces << " split faces merged";
  out << "detection:       " << line.str() << "\n";
  if (s.gaps.count > 0) {
    std::ostringstream spread;
    spread << std::setprecision(3) << "gap " << rbla::model::length_text(s.gaps.min, m.units) << " / "
           << rbla::model::length_text(s.gaps.median, m.units) << " / " << rbla::model::length_text(s.gaps.max, m.units) << " (at most "
           << 100.0 * s.largest_gap_fraction << " % of its tolerance), angle " << s.angles.min << " / "
           << s.angles.median << " / " << s.angles.max << " deg";
    out << "accepted joints: " << spread.str() << " (min / median / max)\n";
  }
  out << "near misses:     " << s.near_misses_total;
  if (!m.near_misses.empty()) {
    const rbla::model::NearMiss& n = m.near_misses.front();
    std::ostringstream closest;
    closest << std::setprecision(3) << " (closest: '" << m.blocks[n.block_a].id << "' face " << n.face_a << " and '"
            << m.blocks[n.block_b].id << "' face " << n.face_b << ", " << rbla::model::length_text(n.distance, m.units)
            << " apart where " << rbla::model::length_text(n.distance_tolerance, m.units) << " is accepted, at "
            << n.angle_degrees << " deg; all listed by -o)";
    out << closest.str();
  }
  out << "\n";
}

/// Before any work: every output must be writable by the rules of io/atomic_file.hpp, none may be
/// the model, and no two may be one file. Throws io::FileError. Returns true when an output goes to
/// standard output: what would be printed there (the verdict) then goes to standard error, so
/// that `-o -` gives a clean JSON stream.
bool check_paths(const CommonOptions& options,
                 const std::vector<std::string>& svg_names = {"mechanism.svg", "convergence.svg"}) {
  std::vector<rbla::io::OutputTarget> outputs;
  if (!options.output_path.empty()) outputs.push_back(rbla::io::resolve_output(options.output_path));
  if (!options.dump_problem_path.empty()) outputs.push_back(rbla::io::resolve_output(options.dump_problem_path));
  if (!options.svg_dir.empty()) {
    for (auto& target : rbla::io::resolve_outputs_in_folder(options.svg_dir, svg_names)) {
      outputs.push_back(std::move(target));
    }
  }
  rbla::io::check_outputs(options.model_path, outputs);
  return std::any_of(outputs.begin(), outputs.end(), rbla::io::goes_to_standard_output);
}

int run_info(const CommonOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const bool stdout_taken = check_paths(options);
  rbla::io::LoadedModel loaded;
  int exit_code = kSuccess;
  if (!load(options, loaded, exit_code)) return exit_code;
  const rbla::model::Model& m = loaded.model;
  const nlohmann::json summary = rbla::io::model_summary_json(m);
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
      << "analysis:        " << rbla::model::to_string(m.analysis.type) << ", "
      << rbla::model::to_string(m.analysis.friction_model) << ", cone " << rbla::model::to_string(m.analysis.cone)
      << "\n"
      << "warnings:        " << m.warnings.size() << "\n";
  print_detection(m, out);
  out << "model stage:     " << seconds_text(loaded.timings.total_seconds) << " (read "
      << seconds_text(loaded.timings.read_seconds) << ", validate " << seconds_text(loaded.timings.validate_seconds)
      << ", geometry " << seconds_text(loaded.timings.geometry_seconds) << ", detection "
      << seconds_text(loaded.timings.detect_seconds) << ")\n";
  if (!options.output_path.empty()) {
    rbla::model::StageTimings timings = loaded.timings;
    timings.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const nlohmann::json result = rbla::io::model_only_result(m, timings, options.model_path);
    return write_output(options.output_path, result.dump(1) + "\n");
  }
  return kSuccess;
}

/// Answers (collapse, no mechanism, cannot stand) succeed; a solve that gave no answer does not.
int exit_code_of(rbla::analysis::Verdict verdict) {
  switch (verdict) {
    case rbla::analysis::Verdict::Collapse:
    case rbla::analysis::Verdict::NoMechanism:
    case rbla::analysis::Verdict::CannotStand: return kSuccess;
    case rbla::analysis::Verdict::SolverFailure:
    case rbla::analysis::Verdict::TimeLimit:
    case rbla::analysis::Verdict::IterationLimit:
    case rbla::analysis::Verdict::Cancelled: return kSolverFailure;
  }
  return kSolverFailure;
}

int run_solve(const CommonOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const bool stdout_taken = check_paths(options);
  rbla::io::LoadedModel loaded;
  int exit_code = kSuccess;
  if (!load(options, loaded, exit_code)) return exit_code;
  const rbla::model::Model& m = loaded.model;

  rbla::analysis::AnalysisOptions analysis_options;
  analysis_options.log = options.verbose ? &std::cerr : nullptr;
  if (!options.dump_problem_path.empty()) {
    analysis_options.problem_ready = [&](const rbla::conic::ConicProblem& problem) {
      rbla::io::write_problem_file(options.dump_problem_path, problem);
    };
  }
  analysis_options.threads = options.threads;
  progress(options, std::string("analysis: ") + rbla::model::to_string(m.analysis.type) + ", " +
                        rbla::model::to_string(m.analysis.friction_model) + " friction, cone " +
                        rbla::model::to_string(m.analysis.cone));
  rbla::analysis::AnalysisResult result;
  try {
    result = rbla::analysis::analyse(m, analysis_options);
  } catch (const rbla::model::ModelError& error) {
    return report_invalid(error);
  } catch (const rbla::conic::ConicSetupError& error) {
    std::cerr << "rbla: conic problem: " << error.what() << "\n";
    return kSolverFailure;
  }
  report_warnings(result.warnings, options);
  if (result.solver_ran) {
    progress(options, "solved in " + seconds_text(result.solve_seconds) + " (" +
                          std::to_string(result.solver_info.iterations) + " interior-point iterations" +
                          (result.non_associative.empty()
                               ? std::string()
                               : ", " + std::to_string(result.non_associative.size()) + " non-associative steps") +
                          "; assembly " + seconds_text(result.assemble_seconds) + ")");
  } else {
    progress(options, "no solve ran (assembly " + seconds_text(result.assemble_seconds) + ")");
  }
  (stdout_taken ? std::cerr : std::cout) << shown(result.verdict_text) << "\n";

  rbla::model::StageTimings timings = loaded.timings;
  const auto write_start = std::chrono::steady_clock::now();
  if (!options.svg_dir.empty()) {
    rbla::io::make_folder(options.svg_dir);
    const std::string mechanism = svg_file(options, "mechanism.svg").string();
    const std::string convergence = svg_file(options, "convergence.svg").string();
    const int svg_code = write_output(mechanism, rbla::io::mechanism_svg(m, result));
    if (svg_code != kSuccess) return svg_code;
    const int plot_code = write_output(convergence, rbla::io::convergence_svg(result));
    if (plot_code != kSuccess) return plot_code;
    progress(options, "wrote " + mechanism + " and " + convergence);
  }
  if (!options.output_path.empty()) {
    timings.write_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - write_start).count();
    timings.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const nlohmann::json json = rbla::io::analysis_result_json(m, result, timings, options.model_path);
    const int code = write_output(options.output_path, json.dump(1) + "\n");
    if (code != kSuccess) return code;
    if (options.output_path != "-") progress(options, "wrote " + options.output_path);
  }
  return exit_code_of(result.verdict);
}

struct SearchOptions {
  rbla::analysis::RadialSearchSettings settings;
  rbla::analysis::ThresholdSettings threshold;
  std::optional<double> target_alpha;
};

int run_worst_direction(const CommonOptions& options, const SearchOptions& search) {
  const auto start = std::chrono::steady_clock::now();
  const bool stdout_taken = check_paths(options, {"mechanism.svg", "worst_direction.svg"});
  rbla::io::LoadedModel loaded;
  int exit_code = kSuccess;
  if (!load(options, loaded, exit_code)) return exit_code;
  rbla::analysis::AnalysisOptions analysis_options;
  analysis_options.log = options.verbose ? &std::cerr : nullptr;
  analysis_options.threads = options.threads;
  progress(options, "searching the weakest horizontal direction of the seismic load");
  const rbla::analysis::WorstDirection w =
      rbla::analysis::find_worst_direction(loaded.model, analysis_options, search.settings);
  report_warnings(w.at_minimum.warnings, options);
  progress(options, std::to_string(w.evaluations.size()) + " directions in " + seconds_text(w.seconds) + "; " + w.stop);
  (stdout_taken ? std::cerr : std::cout) << shown(w.verdict_text) << "\n";

  rbla::model::StageTimings timings = loaded.timings;
  const auto write_start = std::chrono::steady_clock::now();
  if (!options.svg_dir.empty()) {
    rbla::io::make_folder(options.svg_dir);
    const std::string mechanism = svg_file(options, "mechanism.svg").string();
    const std::string polar = svg_file(options, "worst_direction.svg").string();
    const int svg_code = write_output(mechanism, rbla::io::mechanism_svg(w.model_at_minimum, w.at_minimum));
    if (svg_code != kSuccess) return svg_code;
    const int plot_code = write_output(polar, rbla::io::worst_direction_svg(w));
    if (plot_code != kSuccess) return plot_code;
    progress(options, "wrote " + mechanism + " and " + polar);
  }
  if (!options.output_path.empty()) {
    timings.write_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - write_start).count();
    timings.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    nlohmann::json json = rbla::io::analysis_result_json(w.model_at_minimum, w.at_minimum, timings, options.model_path);
    json["worst_direction"] = rbla::io::worst_direction_json(w, search.settings.tolerance);
    const int code = write_output(options.output_path, json.dump(1) + "\n");
    if (code != kSuccess) return code;
    if (options.output_path != "-") progress(options, "wrote " + options.output_path);
  }
  return exit_code_of(w.verdict);
}

int run_critical_friction(const CommonOptions& options, const SearchOptions& search) {
  const auto start = std::chrono::steady_clock::now();
  const bool stdout_taken = check_paths(options, {"mechanism.svg", "critical_friction.svg"});
  rbla::io::LoadedModel loaded;
  int exit_code = kSuccess;
  if (!load(options, loaded, exit_code)) return exit_code;
  rbla::analysis::AnalysisOptions analysis_options;
  analysis_options.log = options.verbose ? &std::cerr : nullptr;
  analysis_options.threads = options.threads;
  progress(options, "searching the smallest friction factor");
  const rbla::analysis::CriticalFriction c =
      rbla::analysis::find_critical_friction(loaded.model, search.target_alpha, analysis_options, search.threshold);
  report_warnings(c.at_critical.warnings, options);
  progress(options, std::to_string(c.evaluations.size()) + " factors in " + seconds_text(c.seconds));
  (stdout_taken ? std::cerr : std::cout) << shown(c.verdict_text) << "\n";

  rbla::model::StageTimings timings = loaded.timings;
  const auto write_start = std::chrono::steady_clock::now();
  if (!options.svg_dir.empty()) {
    rbla::io::make_folder(options.svg_dir);
    const std::string mechanism = svg_file(options, "mechanism.svg").string();
    const std::string curve = svg_file(options, "critical_friction.svg").string();
    const int svg_code = write_output(mechanism, rbla::io::mechanism_svg(c.model_at_critical, c.at_critical));
    if (svg_code != kSuccess) return svg_code;
    const int plot_code = write_output(curve, rbla::io::critical_friction_svg(c));
    if (plot_code != kSuccess) return plot_code;
    progress(options, "wrote " + mechanism + " and " + curve);
  }
  if (!options.output_path.empty()) {
    timings.write_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - write_start).count();
    timings.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    nlohmann::json json = rbla::io::analysis_result_json(c.model_at_critical, c.at_critical, timings, options.model_path);
    json["critical_friction"] = rbla::io::critical_friction_json(c, search.threshold.tolerance);
    const int code = write_output(options.output_path, json.dump(1) + "\n");
    if (code != kSuccess) return code;
    if (options.output_path != "-") progress(options, "wrote " + options.output_path);
  }
  return c.outcome == rbla::analysis::ThresholdOutcome::Failed ? kSolverFailure : kSuccess;
}

struct SweepOptions {
  std::vector<std::string> grid, random;  ///< NAME=LOW:HIGH:COUNT, NAME=LOW:HIGH
  int samples = 0;
  std::uint64_t seed = 1;
  std::string out_dir;
  int jobs = 1;
  int task = -1;  ///< -1: every point
  int tasks = 1;
  bool collect = false;
  std::string slurm_script;
  std::vector<std::string> command;  ///< the words of this command line, for the tasks it starts
};

/// Points in all, at most: a sweep is files on disk, one per point.
constexpr std::size_t kMaxSweepPoints = 100000;

std::vector<rbla::analysis::SweepAxis> sweep_axes(const SweepOptions& sweep) {
  if (sweep.grid.empty() == sweep.random.empty()) {
    throw rbla::model::ModelError("--grid/--random", "give the parameters either all with --grid or all with --random");
  }
  if (!sweep.random.empty() && sweep.samples < 1) throw rbla::model::ModelError("--samples", "--random needs --samples N");
  std::vector<rbla::analysis::SweepAxis> axes;
  for (const auto& text : sweep.grid) axes.push_back(rbla::io::parse_sweep_axis(text, true, "--grid"));
  for (const auto& text : sweep.random) axes.push_back(rbla::io::parse_sweep_axis(text, false, "--random"));
  double total = 1.0;
  for (const auto& axis : axes) total *= axis.count;
  if (!sweep.random.empty()) total = sweep.samples;
  if (total > static_cast<double>(kMaxSweepPoints)) {
    throw rbla::model::ModelError("--grid/--samples", "the sweep has " + std::to_string(static_cast<long long>(total)) +
                                                          " points; at most " + std::to_string(kMaxSweepPoints));
  }
  return axes;
}

/// Solves this task's points (every point when no task is given), one result file each.
int solve_sweep_points(const CommonOptions& options, const SweepOptions& sweep, const rbla::model::Model& m,
                       const std::vector<rbla::analysis::SweepAxis>& axes,
                       const std::vector<rbla::analysis::SweepPoint>& points) {
  rbla::analysis::AnalysisOptions analysis_options;
  analysis_options.threads = options.threads;
  int exit_code = kSuccess;
  for (const auto& point : points) {
    if (sweep.task >= 0 && point.index % sweep.tasks != sweep.task) continue;
    const auto start = std::chrono::steady_clock::now();
    const rbla::model::Model at = rbla::analysis::model_at(m, axes, point);
    const rbla::analysis::AnalysisResult result = rbla::analysis::analyse(at, analysis_options);
    rbla::model::StageTimings timings;
    timings.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    nlohmann::json json = rbla::io::analysis_result_json(at, result, timings, options.model_path);
    json["sweep_point"] = rbla::io::sweep_point_json(axes, point);
    const std::string path = (std::filesystem::path(sweep.out_dir) / rbla::io::point_file_name(point.index)).string();
    const int code = write_output(path, json.dump(1) + "\n");
    if (code != kSuccess) return code;
    if (exit_code_of(result.verdict) != kSuccess) exit_code = kSolverFailure;
    progress(options, "point " + std::to_string(point.index) + ": " + result.verdict_text);
  }
  return exit_code;
}

/// This command line for one task: this program by its absolute path, without the options that
/// choose how the sweep runs (each task gets its own).
std::vector<std::string> task_command(const std::vector<std::string>& command) {
  static const std::vector<std::pair<std::string, bool>> dropped = {
      {"--jobs", true}, {"--tasks", true}, {"--task", true}, {"--threads", true}, {"--slurm-script", true},
      {"--collect", false}, {"-q", false}, {"--quiet", false}};
  std::vector<std::string> words{std::filesystem::read_symlink("/proc/self/exe").string()};
  for (std::size_t i = 1; i < command.size(); ++i) {
    bool drop = false;
    for (const auto& [name, takes_value] : dropped) {
      if (command[i] == name) {
        drop = true;
        i += takes_value ? 1 : 0;
      } else if (takes_value && command[i].rfind(name + "=", 0) == 0) {
        drop = true;
      }
      if (drop) break;
    }
    if (!drop) words.push_back(command[i]);
  }
  return words;
}

/// The same sweep as `jobs` tasks in child processes of this program, run at once.
int run_sweep_tasks(const SweepOptions& sweep) {
  std::vector<pid_t> children;
  for (int k = 0; k < sweep.jobs; ++k) {
    std::vector<std::string> words = task_command(sweep.command);
    for (const std::string& extra : {std::string("-q"), std::string("--threads"), std::string("1"), std::string("--task"),
                                     std::to_string(k), std::string("--tasks"), std::to_string(sweep.jobs)}) {
      words.push_back(extra);
    }
    const std::string self = words.front();
    std::vector<char*> argv;
    for (auto& word : words) argv.push_back(word.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    if (posix_spawn(&pid, self.c_str(), nullptr, nullptr, argv.data(), environ) != 0) {
      std::cerr << "rbla: could not start the sweep's task " << k << "\n";
      return kSolverFailure;
    }
    children.push_back(pid);
  }
  int exit_code = kSuccess;
  for (pid_t pid : children) {
    int status = 0;
    if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) exit_code = kSolverFailure;
  }
  return exit_code;
}

/// summary.csv and sweep.svg from the points' result files; missing points are listed as such.
int collect_sweep(const SweepOptions& sweep, const rbla::model::Model& m,
                  const std::vector<rbla::analysis::SweepAxis>& axes,
                  const std::vector<rbla::analysis::SweepPoint>& points) {
  std::vector<rbla::io::SweepRow> rows;
  std::map<std::string, int> counts;
  for (const auto& point : points) {
    rows.push_back(rbla::io::read_sweep_row(
        (std::filesystem::path(sweep.out_dir) / rbla::io::point_file_name(point.index)).string(), point));
    ++counts[rows.back().status];
  }
  const std::string value_name =
      m.analysis.type == rbla::model::AnalysisType::Settlement ? "base_reaction" : "load_multiplier";
  const std::filesystem::path dir(sweep.out_dir);
  int code = write_output((dir / "summary.csv").string(), rbla::io::sweep_csv(axes, rows, value_name));
  if (code == kSuccess) code = write_output((dir / "sweep.svg").string(), rbla::io::sweep_svg(axes, rows, value_name));
  if (code != kSuccess) return code;
  std::string line = std::to_string(points.size()) + " points:";
  for (const auto& [status, n] : counts) line += " " + std::to_string(n) + " " + status + ",";
  line.back() = ';';
  std::cout << shown(line + " wrote " + (dir / "summary.csv").string() + " and " + (dir / "sweep.svg").string()) << "\n";
  const bool complete = counts.size() == counts.count("collapse") + counts.count("no_mechanism") + counts.count("cannot_stand");
  return complete ? kSuccess : kSolverFailure;
}

int run_sweep(const CommonOptions& options, SweepOptions sweep) {
  const auto axes = sweep_axes(sweep);
  if (sweep.task >= sweep.tasks) throw rbla::model::ModelError("--task", "must be below --tasks");
  if (options.model_path == "-" && (sweep.jobs > 1 || !sweep.slurm_script.empty() || sweep.task >= 0)) {
    throw rbla::model::ModelError("model", "a sweep run as several tasks reads the model from a file, not '-'");
  }
  if (!sweep.slurm_script.empty()) {
    if (sweep.task >= 0) throw rbla::model::ModelError("--task", "the Slurm script runs every task; give --tasks only");
    const int code = write_output(sweep.slurm_script, rbla::io::slurm_script(task_command(sweep.command), sweep.tasks));
    if (code == kSuccess) progress(options, "wrote " + sweep.slurm_script + ": sbatch it, then run this sweep with --collect");
    return code;
  }
  rbla::io::LoadedModel loaded;
  int exit_code = kSuccess;
  if (!load(options, loaded, exit_code)) return exit_code;
  rbla::analysis::check_sweep(loaded.model, axes);
  const auto points = sweep.random.empty() ? rbla::analysis::grid_points(axes)
                                           : rbla::analysis::random_points(axes, sweep.samples, sweep.seed);
  rbla::io::make_folder(sweep.out_dir);
  if (sweep.task >= 0) return solve_sweep_points(options, sweep, loaded.model, axes, points);
  if (!sweep.collect) {
    const int code = sweep.jobs > 1 ? run_sweep_tasks(sweep) : solve_sweep_points(options, sweep, loaded.model, axes, points);
    if (code == kFileError) return code;
  }
  return collect_sweep(sweep, loaded.model, axes, points);
}

/// --max-input-bytes, --max-depth, ... (io/input_limits.hpp): how much input a command accepts.
void add_input_limits(CLI::App* command, rbla::io::InputLimits& limits) {
  for (const rbla::io::InputLimitInfo& info : rbla::io::kInputLimits) {
    std::uint64_t& value = limits.*info.field;
    CLI::Option* option = command->add_option(info.option, value, std::string("Refuse a model with more ") +
                                                                      info.counts + " than this")
                              ->default_val(value)
                              ->group("Input limits");
    if (info.field == &rbla::io::InputLimits::max_bytes) option->transform(CLI::AsSizeValue(false));
    option->check(CLI::Range(std::uint64_t{1}, info.ceiling));
  }
}

}  // namespace

int main(int argc, char** argv) {
  // A reader that goes away (`rbla solve m.json -o - | head`) is a write error with a message,
  // not a silent death by SIGPIPE; an interrupted write leaves no temporary file behind.
  std::signal(SIGPIPE, SIG_IGN);
  rbla::io::remove_temporary_files_on_signals();
  CLI::App app{"rbla: rigid block limit analysis of masonry structures"};
  app.set_version_flag("--version", std::string("rbla ") + RBLA_VERSION);
  app.require_subcommand(1);
  CommonOptions options;

  CLI::App* solve = app.add_subcommand("solve", "Analyse a model and write the result JSON");
  solve->add_option("model", options.model_path, "Model JSON file ('-' for standard input)")->required();
  solve->add_option("-o,--output", options.output_path, "Result JSON file ('-' for standard output)");
  solve->add_option("--svg", options.svg_dir, "Folder for the mechanism and convergence SVG pictures");
  solve->add_option("--dump-problem", options.dump_problem_path,
                    "Write the conic problem for other solvers: CBF, or free MPS when the name ends in .mps (LP only)");
  solve->add_flag("-q,--quiet", options.quiet, "No progress or warnings on standard error");
  solve->add_flag("-v,--verbose", options.verbose,
                  "Interior-point iteration log and every warning on its own line on standard error");
  solve->add_option("--threads", options.threads,
                    "Threads per conic solve: 2 (default) splits large problems over two cores, 1 keeps to one")
      ->check(CLI::Range(1, 2));
  add_input_limits(solve, options.limits);

  CLI::App* validate = app.add_subcommand("validate", "Check a model against the schema and its geometry");
  validate->add_option("model", options.model_path, "Model JSON file ('-' for standard input)")->required();
  validate->add_flag("-q,--quiet", options.quiet, "No progress or warnings on standard error");
  validate->add_flag("-v,--verbose", options.verbose, "Every warning on its own line (default: one line per kind)");
  add_input_limits(validate, options.limits);

  CLI::App* info = app.add_subcommand("info", "Summarise a model: blocks, interfaces, contact points, warnings");
  info->add_option("model", options.model_path, "Model JSON file ('-' for standard input)")->required();
  info->add_option("-o,--output", options.output_path,
                   "Also write the summary as a result JSON with status model_only ('-' for standard output)");
  info->add_flag("-q,--quiet", options.quiet, "No progress or warnings on standard error");
  info->add_flag("-v,--verbose", options.verbose, "Every warning on its own line (default: one line per kind)");
  add_input_limits(info, options.limits);

  SearchOptions search;
  CLI::App* worst = app.add_subcommand(
      "worst-direction", "Find the horizontal direction of the seismic load the structure carries least");
  worst->add_option("model", options.model_path, "Model JSON file ('-' for standard input)")->required();
  worst->add_option("-o,--output", options.output_path,
                    "Result JSON at the weakest direction, with a worst_direction section ('-' for standard output)");
  worst->add_option("--svg", options.svg_dir, "Folder for the mechanism and the alpha(theta) polar SVG pictures");
  worst->add_option("--tolerance", search.settings.tolerance,
                    "Stop when the certified bracket of the minimum is this narrow, relative")
      ->default_val(search.settings.tolerance)
      ->check(CLI::Range(1e-9, 0.5));
  worst->add_option("--initial-directions", search.settings.initial_samples, "Evenly spaced first directions")
      ->default_val(search.settings.initial_samples)
      ->check(CLI::Range(3, 360));
  worst->add_option("--max-directions", search.settings.max_samples, "Directions evaluated in all, at most")
      ->default_val(search.settings.max_samples)
      ->check(CLI::Range(3, 10000));
  worst->add_flag("-q,--quiet", options.quiet, "No progress or warnings on standard error");
  worst->add_flag("-v,--verbose", options.verbose, "Interior-point iteration logs and every warning");
  worst->add_option("--threads", options.threads, "Threads per conic solve, 1 or 2")->check(CLI::Range(1, 2));
  add_input_limits(worst, options.limits);

  CLI::App* friction = app.add_subcommand(
      "critical-friction", "Find the smallest friction (all coefficients scaled together) to stand or carry a load multiplier");
  friction->add_option("model", options.model_path, "Model JSON file ('-' for standard input)")->required();
  friction->add_option("-o,--output", options.output_path,
                       "Result JSON at the critical friction, with a critical_friction section ('-' for standard output)");
  friction->add_option("--svg", options.svg_dir, "Folder for the mechanism and the alpha(mu) SVG pictures");
  friction->add_option("--target-alpha", search.target_alpha,
                       "Smallest friction that carries this load multiplier (default: that stands under its own weight)")
      ->check(CLI::Range(0.0, 1e6));
  friction->add_option("--tolerance", search.threshold.tolerance,
                       "Stop when the certified bracket of the factor is this narrow, relative")
      ->default_val(search.threshold.tolerance)
      ->check(CLI::Range(1e-9, 0.5));
  friction->add_flag("-q,--quiet", options.quiet, "No progress or warnings on standard error");
  friction->add_flag("-v,--verbose", options.verbose, "Interior-point iteration logs and every warning");
  friction->add_option("--threads", options.threads, "Threads per conic solve, 1 or 2")->check(CLI::Range(1, 2));
  add_input_limits(friction, options.limits);

  SweepOptions sweep_options;
  for (int i = 0; i < argc; ++i) sweep_options.command.emplace_back(argv[i]);
  CLI::App* sweep = app.add_subcommand("sweep", "Run the model over a grid or a random sample of parameters");
  sweep->add_option("model", options.model_path, "Model JSON file")->required();
  sweep->add_option("--out", sweep_options.out_dir, "Folder for the points' result files, summary.csv and sweep.svg")
      ->required();
  sweep->add_option("--grid", sweep_options.grid,
                    "NAME=LOW:HIGH:COUNT, repeatable: every combination (NAME: friction, friction_factor, "
                    "unit_weight_factor, seismic_angle, settlement_tilt, settlement_azimuth; angles in degrees)");
  sweep->add_option("--random", sweep_options.random, "NAME=LOW:HIGH, repeatable: uniform random values");
  sweep->add_option("--samples", sweep_options.samples, "Points of a --random sweep")->check(CLI::Range(1, 100000));
  sweep->add_option("--seed", sweep_options.seed, "Seed of a --random sweep (the same seed, the same points)");
  sweep->add_option("--jobs", sweep_options.jobs, "Processes on this machine (each solve then on one thread)")
      ->check(CLI::Range(1, 64));
  sweep->add_option("--task", sweep_options.task, "Solve only the points with index % tasks == task (for job arrays)")
      ->check(CLI::Range(0, 100000));
  sweep->add_option("--tasks", sweep_options.tasks, "Number of tasks the points are split into")
      ->check(CLI::Range(1, 100000));
  sweep->add_flag("--collect", sweep_options.collect, "Only write summary.csv and sweep.svg from the points' files");
  sweep->add_option("--slurm-script", sweep_options.slurm_script,
                    "Write a Slurm job-array script of --tasks tasks for this sweep instead of running it");
  sweep->add_flag("-q,--quiet", options.quiet, "No progress or warnings on standard error");
  sweep->add_option("--threads", options.threads, "Threads per conic solve, 1 or 2")->check(CLI::Range(1, 2));
  add_input_limits(sweep, options.limits);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kUsage;
  }

  try {
    if (*solve) return run_solve(options);
    if (*validate) return run_validate(options);
    if (*info) return run_info(options);
    if (*worst) return run_worst_direction(options, search);
    if (*friction) return run_critical_friction(options, search);
    if (*sweep) return run_sweep(options, sweep_options);
  } catch (const rbla::model::ModelError& error) {
    return report_invalid(error);
  } catch (const rbla::io::FileError& error) {
    return report_file_error(error);
  } catch (const std::bad_alloc&) {
    std::cerr << "rbla: out of memory\n";
    return kSolverFailure;
  } catch (const std::exception& error) {
    // Anything else ends the run with its reason, never with an abort.
    std::cerr << "rbla: " << shown(error.what()) << "\n";
    return kSolverFailure;
  }
  return kUsage;
}
