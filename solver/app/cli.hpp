// What every rbla command shares: the common options, the exit codes, how progress, warnings
// and errors are printed, loading the model, and writing outputs by the rules of
// io/atomic_file.hpp. The commands themselves are in commands.hpp.
//
// Exit codes (also in README.md):
//   0  success (the verdict may be "cannot stand" or "no mechanism": those are answers)
//   1  usage error (unknown command or option)
//   2  invalid input (the message names the JSON pointer and what was expected), limits included
//   3  solver failure (numerical failure, time or iteration limit)
//   4  a file could not be read or written (the message names the path)
#pragma once

#include "analysis/analysis_result.hpp"
#include "io/file_error.hpp"
#include "io/input_limits.hpp"
#include "io/load_model.hpp"
#include "io/result_writer.hpp"
#include "model/errors.hpp"
#include "model/stage_timings.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace rbla::cli {

enum ExitCode : int {
  kSuccess = 0,
  kUsage = 1,
  kInvalidInput = 2,
  kSolverFailure = 3,
  kFileError = 4,
};

using Clock = std::chrono::steady_clock;

/// An option's value that parses but that the command cannot use (a malformed --grid, --task
/// beyond --tasks): main reports it as a usage error, exit 1, like CLI11's own range checks.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A whole message as printed: user text inside is escaped (io/printable.hpp) and very long
/// messages are cut.
std::string shown(const std::string& text);

struct CommonOptions {
  std::string model_path;
  std::string output_path;
  std::string svg_dir;
  std::string dump_problem_path;
  bool quiet = false;
  bool verbose = false;
  int threads = 2;
  io::ResultDetail detail = io::ResultDetail::Points;
  io::InputLimits limits;
};

/// A file in the folder --svg writes into.
std::filesystem::path svg_file(const CommonOptions& options, const char* name);
void progress(const CommonOptions& options, const std::string& line);
std::string seconds_text(double seconds);
/// Every warning printed goes through here: one line per kind with its count and worst instance
/// (io/warning_summary.hpp), or each warning with -v.
void report_warnings(const std::vector<model::Warning>& warnings, const CommonOptions& options);
int report_invalid(const model::ModelError& error);
int report_file_error(const io::FileError& error);
/// Loads the model with progress lines; returns false (after reporting) on invalid input.
bool load(const CommonOptions& options, io::LoadedModel& loaded, int& exit_code);
int write_output(const std::string& path, const std::string& text);
/// Before any work: every output must be writable by the rules of io/atomic_file.hpp, none may be
/// the model, and no two may be one file. Throws io::FileError. Returns true when an output goes to
/// standard output: what would be printed there (the verdict) then goes to standard error, so
/// that `-o -` gives a clean JSON stream.
bool check_paths(const CommonOptions& options,
                 const std::vector<std::string>& svg_names = {"mechanism.svg", "convergence.svg"});
/// Answers (collapse, no mechanism, cannot stand) succeed; a solve that gave no answer does not.
int exit_code_of(analysis::Verdict verdict);
/// --max-input-bytes, --max-depth, ... (io/input_limits.hpp): how much input a command accepts.
void add_input_limits(CLI::App* command, io::InputLimits& limits);
/// --detail points|interfaces|blocks: how much of the mechanism the result JSON holds.
void add_detail_option(CLI::App* command, io::ResultDetail& detail);

/// What CLI11's own checks let through, refused with a message naming the option: an empty value
/// (`-o ''` would mean "no output" and be silently ignored) and NaN (comparisons with it are
/// false, so a range check passes it). Empty when every value given is fine.
std::string refused_option_value(const CLI::App& command);

/// What a command writes besides mechanism.svg and the analysis' result: a second picture in
/// --svg and, when `section` is named, a section added to the result JSON.
struct ExtraOutput {
  const char* picture_name = "convergence.svg";
  std::function<std::string()> picture;  ///< called only when --svg is given
  std::string section;
  nlohmann::json section_json;
};

/// mechanism.svg and the extra picture in --svg, then the result JSON in -o, with the stage
/// timings of the whole run from `start`.
int write_analysis_outputs(const CommonOptions& options, const model::Model& model,
                           const analysis::AnalysisResult& result, model::StageTimings timings,
                           Clock::time_point start, const ExtraOutput& extra);

}  // namespace rbla::cli
