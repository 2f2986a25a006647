// `rbla worst-direction`, `rbla worst-settlement` and `rbla critical-friction`: searches over
// analyses of the model (analysis/worst_direction.hpp, analysis/worst_settlement.hpp,
// analysis/critical_friction.hpp).
#include "commands.hpp"

#include "analysis/critical_friction.hpp"
#include "analysis/support_groups.hpp"
#include "analysis/worst_direction.hpp"
#include "analysis/worst_settlement.hpp"
#include "io/critical_friction_json.hpp"
#include "io/worst_direction_json.hpp"
#include "io/worst_settlement_json.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace rbla::cli {
namespace {

/// How many symbolic analyses a search needed (its analyses share one solver while their conic
/// problems keep one shape).
std::string symbolic_text(int count) {
  return count == 1 ? " (one symbolic factorisation)" : " (" + std::to_string(count) + " symbolic factorisations)";
}

struct FrictionSearch {
  analysis::ThresholdSettings threshold;
  std::optional<double> target_alpha;
  std::vector<std::string> interface_names;  ///< --interfaces: ids or labels
  std::vector<std::string> block_names;      ///< --interfaces-of: the interfaces of these blocks
};

/// The chosen interfaces (empty: all); a name that picks nothing is an error naming its option.
std::vector<int> chosen_interfaces(const model::Model& model, const FrictionSearch& search) {
  if (search.interface_names.empty() && search.block_names.empty()) return {};
  std::vector<model::InputIssue> issues;
  auto check = [&issues](const char* option, const char* what, const std::vector<std::string>& unmatched) {
    for (const std::string& name : unmatched) issues.push_back({option, std::string("no ") + what + " has the id or label '" + name + "'"});
  };
  std::vector<std::string> unmatched_interfaces, unmatched_blocks;
  const std::vector<int> by_name = model.interfaces_named(search.interface_names, {}, unmatched_interfaces);
  const std::vector<int> by_block = model.interfaces_named({}, search.block_names, unmatched_blocks);
  check("--interfaces", "interface", unmatched_interfaces);
  check("--interfaces-of", "block", unmatched_blocks);
  if (issues.empty() && by_name.empty() && by_block.empty()) {
    issues.push_back({"--interfaces-of", "the blocks named touch no interface"});
  }
  if (!issues.empty()) throw model::ModelError(issues);
  std::vector<int> chosen = by_name;
  chosen.insert(chosen.end(), by_block.begin(), by_block.end());
  std::sort(chosen.begin(), chosen.end());
  chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
  return chosen;
}

analysis::AnalysisOptions analysis_options_of(const CommonOptions& options) {
  analysis::AnalysisOptions analysis_options;
  analysis_options.log = options.verbose ? &std::cerr : nullptr;
  analysis_options.threads = options.threads;
  return analysis_options;
}

int run_worst_direction(const CommonOptions& options, const analysis::RadialSearchSettings& settings) {
  const auto start = Clock::now();
  if (settings.initial_samples > settings.max_samples) {
    throw model::ModelError("--initial-directions", "must not exceed --max-directions (" +
                                                        std::to_string(settings.max_samples) + ")");
  }
  const bool stdout_taken = check_paths(options, {"mechanism.svg", "worst_direction.svg"});
  io::LoadedModel loaded;
  int exit_code = kSuccess;
  if (!load(options, loaded, exit_code)) return exit_code;
  progress(options, "searching the weakest horizontal direction of the seismic load");
  const analysis::WorstDirection w = analysis::find_worst_direction(loaded.model, analysis_options_of(options), settings);
  report_warnings(w.at_minimum.warnings, options);
  progress(options, std::to_string(w.evaluations.size()) + " directions in " + seconds_text(w.seconds) +
                        symbolic_text(w.symbolic_analyses) + "; " + w.stop);
  (stdout_taken ? std::cerr : std::cout) << shown(w.verdict_text) << "\n";
  ExtraOutput extra{"worst_direction.svg", [&w] { return io::worst_direction_svg(w); }, "worst_direction",
                    io::worst_direction_json(w, settings.tolerance)};
  const int code = write_analysis_outputs(options, w.model_at_minimum, w.at_minimum, loaded.timings, start, extra);
  return code != kSuccess ? code : exit_code_of(w.verdict);
}

constexpr double kDegree = 3.14159265358979323846 / 180.0;

/// The cone's half angle comes in degrees from the command line (the default is the analysis's).
struct SettlementSearch {
  double cone_angle_deg = analysis::WorstSettlementSettings{}.cone_angle / kDegree;
  analysis::ConeSearchSettings search;
  std::vector<std::string> candidate_groups;  ///< --candidate-group: block ids or labels, comma-separated
};

/// The blocks of each --candidate-group; a name that picks no block is an error naming the option.
std::vector<std::vector<int>> candidate_groups(const model::Model& model, const std::vector<std::string>& lists) {
  std::vector<std::vector<int>> groups;
  std::vector<model::InputIssue> issues;
  for (const std::string& list : lists) {
    std::vector<std::string> names, unmatched;
    std::size_t begin = 0;
    while (begin <= list.size()) {
      const std::size_t end = std::min(list.find(',', begin), list.size());
      if (end > begin) names.push_back(list.substr(begin, end - begin));
      begin = end + 1;
    }
    groups.push_back(model.blocks_named(names, unmatched));
    for (const std::string& name : unmatched) issues.push_back({"--candidate-group", "no block has the id or label '" + name + "'"});
  }
  if (!issues.empty()) throw model::ModelError(issues);
  return groups;
}

/// `rbla worst-settlement --candidate-group ...`: each group's search, the most harmful group's
/// analysis written with the ranking in worst_settlement.candidate_groups.
int run_support_groups(const CommonOptions& options, const SettlementSearch& settings, const io::LoadedModel& loaded,
                       const analysis::WorstSettlementSettings& search, Clock::time_point start, bool stdout_taken) {
  const analysis::SupportGroupRanking r = analysis::rank_support_groups(
      loaded.model, candidate_groups(loaded.model, settings.candidate_groups), "--candidate-group",
      analysis_options_of(options), search);
  const analysis::WorstSettlement& w = r.groups[static_cast<std::size_t>(r.most_harmful.value_or(0))].search;
  report_warnings(w.at_worst.warnings, options);
  progress(options, std::to_string(r.groups.size()) + " candidate groups in " + seconds_text(r.seconds));
  (stdout_taken ? std::cerr : std::cout) << shown(r.verdict_text) << "\n" << shown(w.verdict_text) << "\n";
  nlohmann::json section = io::worst_settlement_json(loaded.model, w, settings.search.tolerance);
  section["candidate_groups"] = io::candidate_groups_json(loaded.model, r);
  ExtraOutput extra{"worst_settlement.svg", [&w] { return io::worst_settlement_svg(w); }, "worst_settlement", section};
  const int code = write_analysis_outputs(options, w.model_at_worst, w.at_worst, loaded.timings, start, extra);
  return code != kSuccess ? code : exit_code_of(w.verdict);
}

int run_worst_settlement(const CommonOptions& options, const SettlementSearch& settings) {
  const auto start = Clock::now();
  const bool stdout_taken = check_paths(options, {"mechanism.svg", "worst_settlement.svg"});
  io::LoadedModel loaded;
  int exit_code = kSuccess;
  if (!load(options, loaded, exit_code)) return exit_code;
  progress(options, "searching the most harmful settlement direction within " +
                        std::to_string(static_cast<int>(std::lround(settings.cone_angle_deg))) + " degrees of gravity");
  analysis::WorstSettlementSettings search;
  search.cone_angle = settings.cone_angle_deg * kDegree;
  search.search = settings.search;
  if (!settings.candidate_groups.empty()) return run_support_groups(options, settings, loaded, search, start, stdout_taken);
  const analysis::WorstSettlement w = analysis::find_worst_settlement(loaded.model, analysis_options_of(options), search);
  report_warnings(w.at_worst.warnings, options);
  progress(options, std::to_string(w.evaluations.size()) + " directions in " + seconds_text(w.seconds) +
                        symbolic_text(w.symbolic_analyses) + "; " + w.stop);
  (stdout_taken ? std::cerr : std::cout) << shown(w.verdict_text) << "\n";
  ExtraOutput extra{"worst_settlement.svg", [&w] { return io::worst_settlement_svg(w); }, "worst_settlement",
                    io::worst_settlement_json(loaded.model, w, settings.search.tolerance)};
  const int code = write_analysis_outputs(options, w.model_at_worst, w.at_worst, loaded.timings, start, extra);
  return code != kSuccess ? code : exit_code_of(w.verdict);
}

int run_critical_friction(const CommonOptions& options, const FrictionSearch& search) {
  const auto start = Clock::now();
  const bool stdout_taken = check_paths(options, {"mechanism.svg", "critical_friction.svg"});
  io::LoadedModel loaded;
  int exit_code = kSuccess;
  if (!load(options, loaded, exit_code)) return exit_code;
  const std::vector<int> chosen = chosen_interfaces(loaded.model, search);
  progress(options, "searching the smallest friction factor");
  const analysis::CriticalFriction c = analysis::find_critical_friction(
      loaded.model, search.target_alpha, analysis_options_of(options), search.threshold, chosen);
  report_warnings(c.at_critical.warnings, options);
  progress(options, std::to_string(c.evaluations.size()) + " factors in " + seconds_text(c.seconds) +
                        symbolic_text(c.symbolic_analyses));
  (stdout_taken ? std::cerr : std::cout) << shown(c.verdict_text) << "\n";
  ExtraOutput extra{"critical_friction.svg", [&c] { return io::critical_friction_svg(c); }, "critical_friction",
                    io::critical_friction_json(loaded.model, c, search.threshold.tolerance)};
  const int code = write_analysis_outputs(options, c.model_at_critical, c.at_critical, loaded.timings, start, extra);
  if (code != kSuccess) return code;
  return c.outcome == analysis::ThresholdOutcome::Failed ? kSolverFailure : kSuccess;
}

}  // namespace

Command add_worst_direction(CLI::App& app, CommonOptions& options) {
  auto settings = std::make_shared<analysis::RadialSearchSettings>();
  CLI::App* worst = app.add_subcommand(
      "worst-direction", "Find the horizontal direction of the seismic load the structure carries least");
  worst->add_option("model", options.model_path, "Model JSON file ('-' for standard input)")->required();
  worst->add_option("-o,--output", options.output_path,
                    "Result JSON at the weakest direction, with a worst_direction section ('-' for standard output)");
  worst->add_option("--svg", options.svg_dir, "Folder for the mechanism and the alpha(theta) polar SVG pictures");
  worst->add_option("--tolerance", settings->tolerance,
                    "Stop when the certified bracket of the minimum is this narrow, relative")
      ->default_val(settings->tolerance)
      ->check(CLI::Range(1e-9, 0.5));
  worst->add_option("--initial-directions", settings->initial_samples, "Evenly spaced first directions")
      ->default_val(settings->initial_samples)
      ->check(CLI::Range(3, 360));
  worst->add_option("--max-directions", settings->max_samples, "Directions evaluated in all, at most")
      ->default_val(settings->max_samples)
      ->check(CLI::Range(3, 10000));
  worst->add_flag("-q,--quiet", options.quiet, "No progress or warnings on standard error");
  worst->add_flag("-v,--verbose", options.verbose, "Interior-point iteration logs and every warning");
  worst->add_option("--threads", options.threads, "Threads per conic solve, 1 or 2")->check(CLI::Range(1, 2));
  add_detail_option(worst, options.detail);
  add_input_limits(worst, options.limits);

  return {worst, [&options, settings] { return run_worst_direction(options, *settings); }};
}

Command add_worst_settlement(CLI::App& app, CommonOptions& options) {
  auto settings = std::make_shared<SettlementSearch>();
  CLI::App* worst = app.add_subcommand(
      "worst-settlement", "Find the settlement direction, within a cone around gravity, that leaves the largest "
                          "fraction of the initial reaction at collapse");
  worst->add_option("model", options.model_path, "Model JSON file ('-' for standard input)")->required();
  worst->add_option("-o,--output", options.output_path,
                    "Result JSON at the most harmful direction, with a worst_settlement section ('-' for standard "
                    "output)");
  worst->add_option("--svg", options.svg_dir, "Folder for the mechanism and the map of the directions tried");
  worst->add_option("--cone-angle", settings->cone_angle_deg, "Half angle of the cone of directions around gravity, degrees")
      ->default_val(settings->cone_angle_deg)
      ->check(CLI::Range(0.5, 80.0));
  worst->add_option("--tolerance", settings->search.tolerance,
                    "Stop when the certified bracket of the largest R/R0 is this narrow, relative")
      ->default_val(settings->search.tolerance)
      ->check(CLI::Range(1e-9, 0.5));
  worst->add_option("--max-directions", settings->search.max_samples, "Directions evaluated in all, at most")
      ->default_val(settings->search.max_samples)
      ->check(CLI::Range(7, 1000));
  worst->add_option("--candidate-group", settings->candidate_groups,
                    "A group of supports that may settle together (block ids or labels, comma-separated); "
                    "repeat for each candidate: each group's most harmful direction is searched with only it "
                    "settling, and the groups are ranked")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  worst->add_flag("-q,--quiet", options.quiet, "No progress or warnings on standard error");
  worst->add_flag("-v,--verbose", options.verbose, "Interior-point iteration logs and every warning");
  worst->add_option("--threads", options.threads, "Threads per conic solve, 1 or 2")->check(CLI::Range(1, 2));
  add_detail_option(worst, options.detail);
  add_input_limits(worst, options.limits);

  return {worst, [&options, settings] { return run_worst_settlement(options, *settings); }};
}

Command add_critical_friction(CLI::App& app, CommonOptions& options) {
  auto search = std::make_shared<FrictionSearch>();
  CLI::App* friction = app.add_subcommand(
      "critical-friction",
      "Find the smallest friction (all coefficients, or a chosen set, scaled together) to stand or carry a load multiplier");
  friction->add_option("model", options.model_path, "Model JSON file ('-' for standard input)")->required();
  friction->add_option("-o,--output", options.output_path,
                       "Result JSON at the critical friction, with a critical_friction section ('-' for standard output)");
  friction->add_option("--svg", options.svg_dir, "Folder for the mechanism and the alpha(mu) SVG pictures");
  friction->add_option("--target-alpha", search->target_alpha,
                       "Smallest friction that carries this load multiplier (default: that stands under its own weight)")
      ->check(CLI::Range(0.0, 1e6));
  friction->add_option("--interfaces", search->interface_names,
                       "Scale only these interfaces' friction: ids or CAD labels, comma-separated (default: all)")
      ->delimiter(',');
  friction->add_option("--interfaces-of", search->block_names,
                       "Scale only the friction of the interfaces touching these blocks: ids or labels, comma-separated")
      ->delimiter(',');
  friction->add_option("--tolerance", search->threshold.tolerance,
                       "Stop when the certified bracket of the factor is this narrow, relative")
      ->default_val(search->threshold.tolerance)
      ->check(CLI::Range(1e-9, 0.5));
  friction->add_flag("-q,--quiet", options.quiet, "No progress or warnings on standard error");
  friction->add_flag("-v,--verbose", options.verbose, "Interior-point iteration logs and every warning");
  friction->add_option("--threads", options.threads, "Threads per conic solve, 1 or 2")->check(CLI::Range(1, 2));
  add_detail_option(friction, options.detail);
  add_input_limits(friction, options.limits);

  return {friction, [&options, search] { return run_critical_friction(options, *search); }};
}

}  // namespace rbla::cli
