// `rbla solve`: one analysis of the model as it asks.
#include "commands.hpp"

#include "analysis/limit_analysis.hpp"
#include "analysis/text.hpp"
#include "io/problem_file.hpp"
#include "io/svg_writer.hpp"

#include <iostream>
#include <optional>

namespace rbla::cli {
namespace {

int run_solve(const CommonOptions& options) {
  const auto start = Clock::now();
  const bool stdout_taken = check_paths(options);
  io::LoadedModel loaded;
  int exit_code = kSuccess;
  if (!load(options, loaded, exit_code)) return exit_code;
  const model::Model& m = loaded.model;

  analysis::AnalysisOptions analysis_options;
  analysis_options.log = options.verbose ? &std::cerr : nullptr;
  // Kept and written after the solve, failed or not: an interrupted run leaves the file as it
  // was, like every other output.
  std::optional<conic::ConicProblem> to_dump;
  if (!options.dump_problem_path.empty()) {
    analysis_options.problem_ready = [&](const conic::ConicProblem& problem) {
      io::check_problem_file(options.dump_problem_path, problem);
      to_dump = problem;
    };
  }
  const auto write_dump = [&] {
    if (to_dump) io::write_problem_file(options.dump_problem_path, *to_dump);
  };
  analysis_options.threads = options.threads;
  progress(options, std::string("analysis: ") + model::to_string(m.analysis.type) + ", " +
                        model::to_string(m.analysis.friction_model) + " friction, cone " +
                        model::to_string(m.analysis.cone));
  analysis::AnalysisResult result;
  try {
    result = analysis::analyse(m, analysis_options);
  } catch (const model::ModelError& error) {
    return report_invalid(error);
  } catch (const conic::ConicResourceError&) {
    write_dump();
    throw;  // main ends the run: out of memory
  } catch (const conic::ConicSetupError& error) {
    std::cerr << "rbla: conic problem: " << error.what() << "\n";
    write_dump();
    return kSolverFailure;
  }
  write_dump();
  report_warnings(result.warnings, options);
  if (result.solver_ran) {
    const bool stopped = result.verdict == analysis::Verdict::TimeLimit ||
                         result.verdict == analysis::Verdict::IterationLimit ||
                         result.verdict == analysis::Verdict::Cancelled;
    progress(options, std::string(stopped ? "stopped after " : "solved in ") + seconds_text(result.solve_seconds) + " (" +
                          std::to_string(result.solver_info.iterations) + " interior-point iterations" +
                          (result.non_associative.empty()
                               ? std::string()
                               : ", " + analysis::count(result.non_associative.size() - 1, "non-associative step",
                                                        "non-associative steps")) +
                          "; assembly " + seconds_text(result.assemble_seconds) + ")");
  } else {
    progress(options, "no solve ran (assembly " + seconds_text(result.assemble_seconds) + ")");
  }
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
  add_input_limits(solve, options.limits);

  return {solve, [&options] { return run_solve(options); }};
}

}  // namespace rbla::cli
