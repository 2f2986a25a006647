#include "cli.hpp"

#include "io/atomic_file.hpp"
#include "io/printable.hpp"
#include "io/result_writer.hpp"
#include "io/svg_writer.hpp"
#include "io/warning_summary.hpp"

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace rbla::cli {

std::string shown(const std::string& text) { return io::printable(text, 4000); }

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

void report_warnings(const std::vector<model::Warning>& warnings, const CommonOptions& options) {
  if (options.quiet) return;
  for (const std::string& line : io::warning_lines(warnings, options.verbose)) {
    std::cerr << "rbla: warning " << shown(line) << "\n";
  }
}

int report_invalid(const model::ModelError& error) {
  std::cerr << "rbla: invalid input:\n";
  for (const auto& issue : error.issues()) {
    std::cerr << "  " << (issue.pointer.empty() ? "(document)" : io::printable(issue.pointer, 300)) << ": "
              << shown(issue.message) << "\n";
  }
  return kInvalidInput;
}

int report_file_error(const io::FileError& error) {
  std::cerr << "rbla: " << shown(error.what()) << "\n";
  return kFileError;
}

bool load(const CommonOptions& options, io::LoadedModel& loaded, int& exit_code) {
  progress(options, "reading " + (options.model_path == "-" ? std::string("standard input") : options.model_path));
  try {
    loaded = io::load_model_file(options.model_path, options.limits);
  } catch (const model::ModelError& error) {
    exit_code = report_invalid(error);
    return false;
  } catch (const io::FileError& error) {
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

int write_output(const std::string& path, const std::string& text) {
  try {
    io::write_file_atomically(path, text);
  } catch (const io::FileError& error) {
    return report_file_error(error);
  }
  return kSuccess;
}

bool check_paths(const CommonOptions& options, const std::vector<std::string>& svg_names) {
  std::vector<io::OutputTarget> outputs;
  if (!options.output_path.empty()) outputs.push_back(io::resolve_output(options.output_path));
  if (!options.dump_problem_path.empty()) outputs.push_back(io::resolve_output(options.dump_problem_path));
  if (!options.svg_dir.empty()) {
    for (auto& target : io::resolve_outputs_in_folder(options.svg_dir, svg_names)) {
      outputs.push_back(std::move(target));
    }
    // A folder still to be made is checked as the file it would displace (-o r.json --svg r.json);
    // one whose parents are missing too is made with them, and cannot be another output.
    std::error_code missing;
    if (!std::filesystem::exists(options.svg_dir, missing)) {
      try {
        outputs.push_back(io::resolve_output(options.svg_dir));
      } catch (const io::FileError&) {
      }
    }
  }
  io::check_outputs(options.model_path, outputs);
  return std::any_of(outputs.begin(), outputs.end(), io::goes_to_standard_output);
}

int exit_code_of(analysis::Verdict verdict) {
  switch (verdict) {
    case analysis::Verdict::Collapse:
    case analysis::Verdict::NoMechanism:
    case analysis::Verdict::CannotStand: return kSuccess;
    case analysis::Verdict::SolverFailure:
    case analysis::Verdict::TimeLimit:
    case analysis::Verdict::IterationLimit:
    case analysis::Verdict::Cancelled: return kSolverFailure;
  }
  return kSolverFailure;
}

void add_input_limits(CLI::App* command, io::InputLimits& limits) {
  // An unsigned option would take "-1" as 2^64 - 1: no limit at all.
  const CLI::Validator not_negative(
      [](std::string& text) { return text.find('-') == std::string::npos ? std::string() : "must be positive"; },
      "POSITIVE");
  for (const io::InputLimitInfo& info : io::kInputLimits) {
    std::uint64_t& value = limits.*info.field;
    CLI::Option* option = command->add_option(info.option, value, std::string("Refuse a model with more ") +
                                                                      info.counts + " than this")
                              ->default_val(value)
                              ->group("Input limits")
                              ->check(not_negative);
    if (info.field == &io::InputLimits::max_bytes) option->transform(CLI::AsSizeValue(false));
    option->check(CLI::Range(std::uint64_t{1}, info.ceiling));
  }
}

std::string refused_option_value(const CLI::App& command) {
  for (const CLI::Option* option : command.get_options()) {
    if (!option->nonpositional() || option->count() == 0 || option->get_type_size() == 0) continue;
    for (const std::string& value : option->results()) {
      std::string word = value;
      if (!word.empty() && (word[0] == '+' || word[0] == '-')) word.erase(0, 1);
      std::transform(word.begin(), word.end(), word.begin(), [](unsigned char c) { return std::tolower(c); });
      if (value.empty()) return option->get_name() + ": an empty value; leave the option out instead";
      if (word == "nan") return option->get_name() + ": " + value + " is not a number";
    }
  }
  return "";
}

void add_detail_option(CLI::App* command, io::ResultDetail& detail) {
  command
      ->add_option_function<std::string>(
          "--detail", [&detail](const std::string& name) { io::parse_detail(name, detail); },
          "How much of the mechanism the result holds: points (default: every interface with its contact points), "
          "interfaces (without their contact points), blocks (block motions and the cracked interfaces' ids)")
      ->check(CLI::IsMember({"points", "interfaces", "blocks"}))
      ->default_str("points");
}

int write_analysis_outputs(const CommonOptions& options, const model::Model& model,
                           const analysis::AnalysisResult& result, model::StageTimings timings,
                           Clock::time_point start, const ExtraOutput& extra) {
  const auto write_start = Clock::now();
  if (!options.svg_dir.empty()) {
    io::make_folder(options.svg_dir);
    const std::string mechanism = svg_file(options, "mechanism.svg").string();
    const std::string second = svg_file(options, extra.picture_name).string();
    const int svg_code = write_output(mechanism, io::mechanism_svg(model, result));
    if (svg_code != kSuccess) return svg_code;
    const int plot_code = write_output(second, extra.picture());
    if (plot_code != kSuccess) return plot_code;
    progress(options, "wrote " + mechanism + " and " + second);
  }
  if (options.output_path.empty()) return kSuccess;
  timings.write_seconds = std::chrono::duration<double>(Clock::now() - write_start).count();
  timings.total_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  nlohmann::json json = io::analysis_result_json(model, result, timings, options.model_path, options.detail);
  if (!extra.section.empty()) json[extra.section] = extra.section_json;
  const int code = write_output(options.output_path, json.dump(1) + "\n");
  if (code == kSuccess && options.output_path != "-") progress(options, "wrote " + options.output_path);
  return code;
}

}  // namespace rbla::cli
