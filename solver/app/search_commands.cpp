// `rbla worst-direction` and `rbla critical-friction`: searches over analyses of the model
// (analysis/worst_direction.hpp, analysis/critical_friction.hpp).
#include "commands.hpp"

#include "analysis/critical_friction.hpp"
#include "analysis/worst_direction.hpp"
#include "io/critical_friction_json.hpp"
#include "io/worst_direction_json.hpp"

#include <iostream>
#include <memory>
#include <optional>

namespace rbla::cli {
namespace {

struct FrictionSearch {
  analysis::ThresholdSettings threshold;
  std::optional<double> target_alpha;
};

analysis::AnalysisOptions analysis_options_of(const CommonOptions& options) {
  analysis::AnalysisOptions analysis_options;
  analysis_options.log = options.verbose ? &std::cerr : nullptr;
  analysis_options.threads = options.threads;
  return analysis_options;
}

int run_worst_direction(const CommonOptions& options, const analysis::RadialSearchSettings& settings) {
  const auto start = Clock::now();
  const bool stdout_taken = check_paths(options, {"mechanism.svg", "worst_direction.svg"});
  io::LoadedModel loaded;
  int exit_code = kSuccess;
  if (!load(options, loaded, exit_code)) return exit_code;
  progress(options, "searching the weakest horizontal direction of the seismic load");
  const analysis::WorstDirection w = analysis::find_worst_direction(loaded.model, analysis_options_of(options), settings);
  report_warnings(w.at_minimum.warnings, options);
  progress(options, std::to_string(w.evaluations.size()) + " directions in " + seconds_text(w.seconds) + "; " + w.stop);
  (stdout_taken ? std::cerr : std::cout) << shown(w.verdict_text) << "\n";
  ExtraOutput extra{"worst_direction.svg", [&w] { return io::worst_direction_svg(w); }, "worst_direction",
                    io::worst_direction_json(w, settings.tolerance)};
  const int code = write_analysis_outputs(options, w.model_at_minimum, w.at_minimum, loaded.timings, start, extra);
  return code != kSuccess ? code : exit_code_of(w.verdict);
}

int run_critical_friction(const CommonOptions& options, const FrictionSearch& search) {
  const auto start = Clock::now();
  const bool stdout_taken = check_paths(options, {"mechanism.svg", "critical_friction.svg"});
  io::LoadedModel loaded;
  int exit_code = kSuccess;
  if (!load(options, loaded, exit_code)) return exit_code;
  progress(options, "searching the smallest friction factor");
  const analysis::CriticalFriction c = analysis::find_critical_friction(loaded.model, search.target_alpha,
                                                                        analysis_options_of(options), search.threshold);
  report_warnings(c.at_critical.warnings, options);
  progress(options, std::to_string(c.evaluations.size()) + " factors in " + seconds_text(c.seconds));
  (stdout_taken ? std::cerr : std::cout) << shown(c.verdict_text) << "\n";
  ExtraOutput extra{"critical_friction.svg", [&c] { return io::critical_friction_svg(c); }, "critical_friction",
                    io::critical_friction_json(c, search.threshold.tolerance)};
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
  add_input_limits(worst, options.limits);

  return {worst, [&options, settings] { return run_worst_direction(options, *settings); }};
}

Command add_critical_friction(CLI::App& app, CommonOptions& options) {
  auto search = std::make_shared<FrictionSearch>();
  CLI::App* friction = app.add_subcommand(
      "critical-friction", "Find the smallest friction (all coefficients scaled together) to stand or carry a load multiplier");
  friction->add_option("model", options.model_path, "Model JSON file ('-' for standard input)")->required();
  friction->add_option("-o,--output", options.output_path,
                       "Result JSON at the critical friction, with a critical_friction section ('-' for standard output)");
  friction->add_option("--svg", options.svg_dir, "Folder for the mechanism and the alpha(mu) SVG pictures");
  friction->add_option("--target-alpha", search->target_alpha,
                       "Smallest friction that carries this load multiplier (default: that stands under its own weight)")
      ->check(CLI::Range(0.0, 1e6));
  friction->add_option("--tolerance", search->threshold.tolerance,
                       "Stop when the certified bracket of the factor is this narrow, relative")
      ->default_val(search->threshold.tolerance)
      ->check(CLI::Range(1e-9, 0.5));
  friction->add_flag("-q,--quiet", options.quiet, "No progress or warnings on standard error");
  friction->add_flag("-v,--verbose", options.verbose, "Interior-point iteration logs and every warning");
  friction->add_option("--threads", options.threads, "Threads per conic solve, 1 or 2")->check(CLI::Range(1, 2));
  add_input_limits(friction, options.limits);

  return {friction, [&options, search] { return run_critical_friction(options, *search); }};
}

}  // namespace rbla::cli
