// `rbla solve`: one analysis of the model as it asks.
#include "commands.hpp"

#include "analysis/limit_analysis.hpp"
#include "analysis/text.hpp"
#include "io/problem_file.hpp"
#include "io/svg_writer.hpp"

#include <iostream>
#include <optional>
#include <string>
#include <utility>

namespace rbla::cli {
namespace {

/// --dump-problem: the conic problem, kept when the analysis has built it and written after the
/// solve, failed or not, so that an interrupted run leaves the file as it was, like every output.
class ProblemDump {
 public:
  explicit ProblemDump(std::string path) : path_(std::move(path)) {}
  void attach(analysis::AnalysisOptions& options) {
    if (path_.empty()) return;
    options.problem_ready = [this](const conic::ConicProblem& problem) {
      io::check_problem_file(path_, problem);  // an MPS of a conic problem: refused before the solve
      problem_ = problem;
    };
  }
  void write() const {
    if (problem_) io::write_problem_file(path_, *problem_);
  }

 private:
  std::string path_;
  std::optional<conic::ConicProblem> problem_;
};

/// The progress line after the analysis: how long the solves took and how many iterations.
std::string solve_summary(const analysis::AnalysisResult& result) {
  if (!result.solver_ran) return "no solve ran (assembly " + seconds_text(result.assemble_seconds) + ")";
  const bool stopped = result.verdict == analysis::Verdict::TimeLimit ||
                       result.verdict == analysis::Verdict::IterationLimit ||
                       result.verdict == analysis::Verdict::Cancelled;
  const std::string steps =
      result.non_associative.empty()
          ? std::string()
          : ", " + analysis::count(result.non_associative.size() - 1, "non-associative step", "non-associative steps");
  return std::string(stopped ? "stopped after " : "solved in ") + seconds_text(result.solve_seconds) + " (" +
         std::to_string(result.solver_info.iterations) + " interior-point iterations" + steps + "; assembly " +
         seconds_text(result.assemble_seconds) + ")";
}

int run_solve(const CommonOptions& options) {
  const auto start = Clock::now();
  const bool stdout_taken = check_paths(options);
  io::LoadedModel loaded;
  int exit_code = kSuccess;
  if (!load(options, loaded, exit_code)) return exit_code;
  const model::Model& m = loaded.model;

  analysis::AnalysisOptions analysis_options;
  analysis_options.log = options.verbose ? &std::cerr : nullptr;
  analysis_options.threads = options.threads;
  ProblemDump dump(options.dump_problem_path);
  dump.attach(analysis_options);
  progress(options, std::string("analysis: ") + model::to_string(m.analysis.type) + ", " +
                        model::to_string(m.analysis.friction_model) + " friction, cone " +
                        model::to_string(m.analysis.cone));
  analysis::AnalysisResult result;
  try {
    result = analysis::analyse(m, analysis_options);
  } catch (const model::ModelError& error) {
    return report_invalid(error);
  } catch (const conic::ConicResourceError&) {
    dump.write();
    throw;  // main ends the run: out of memory
  } catch (const conic::ConicSetupError& error) {
    std::cerr << "rbla: conic problem: " << error.what() << "\n";
    dump.write();
    return kSolverFailure;
  }
  dump.write();
  report_warnings(result.warnings, options);
  progress(options, solve_summary(result));
  (stdout_taken ? std::cerr : std::cout) << shown(result.verdict_text) << "\n";

  ExtraOutput extra;
  extra.picture = [&result] { return io::convergence_svg(result); };
  const int code = write_analysis_outputs(options, m, result, loaded.timings, start, extra);
  return code != kSuccess ? code : exit_code_of(result.verdict);
}

}  // namespace

Command add_solve(CLI::App& app, CommonOptions& options) {
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
  add_detail_option(solve, options.detail);
  add_input_limits(solve, options.limits);

  return {solve, [&options] { return run_solve(options); }};
}

}  // namespace rbla::cli
