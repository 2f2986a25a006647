// `rbla sweep`: the model over a grid or a random sample of parameters (analysis/sweep.hpp), in
// this process, in child processes (--jobs), or as the tasks of a job array (--task, --tasks,
// --slurm-script). docs/sweeps.md.
#include "commands.hpp"

#include "analysis/limit_analysis.hpp"
#include "analysis/sweep.hpp"
#include "io/atomic_file.hpp"
#include "io/result_writer.hpp"
#include "io/sweep_io.hpp"

#include <spawn.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>

namespace rbla::cli {
namespace {

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

/// The parameter axes as the options give them; what does not parse is a usage error (exit 1).
/// Whether they suit the model is checked later, against the model (exit 2).
std::vector<analysis::SweepAxis> sweep_axes(const SweepOptions& sweep) {
  if (sweep.grid.empty() == sweep.random.empty()) {
    throw UsageError("--grid/--random: give the parameters either all with --grid or all with --random");
  }
  if (!sweep.random.empty() && sweep.samples < 1) throw UsageError("--samples: --random needs --samples N");
  std::vector<analysis::SweepAxis> axes;
  try {
    for (const auto& text : sweep.grid) axes.push_back(io::parse_sweep_axis(text, true, "--grid"));
    for (const auto& text : sweep.random) axes.push_back(io::parse_sweep_axis(text, false, "--random"));
  } catch (const model::ModelError& error) {
    throw UsageError(error.what());
  }
  double total = 1.0;
  for (const auto& axis : axes) total *= axis.count;
  if (!sweep.random.empty()) total = sweep.samples;
  if (total > static_cast<double>(kMaxSweepPoints)) {
    throw UsageError("--grid/--samples: the sweep has " + std::to_string(static_cast<long long>(total)) +
                     " points; at most " + std::to_string(kMaxSweepPoints));
  }
  if (sweep.task >= sweep.tasks) throw UsageError("--task: must be below --tasks");
  return axes;
}

/// Solves this task's points (every point when no task is given), one result file each.
int solve_sweep_points(const CommonOptions& options, const SweepOptions& sweep, const model::Model& m,
                       const std::vector<analysis::SweepAxis>& axes,
                       const std::vector<analysis::SweepPoint>& points) {
  analysis::AnalysisOptions analysis_options;
  analysis_options.threads = options.threads;
  // The points differ only in numbers: one symbolic analysis serves them all.
  analysis::SolverReuse solvers;
  analysis_options.reuse = &solvers;
  int exit_code = kSuccess;
  for (const auto& point : points) {
    if (sweep.task >= 0 && point.index % sweep.tasks != sweep.task) continue;
    const auto start = Clock::now();
    const model::Model at = analysis::model_at(m, axes, point);
    const analysis::AnalysisResult result = analysis::analyse(at, analysis_options);
    model::StageTimings timings;
    timings.total_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    nlohmann::json json = io::analysis_result_json(at, result, timings, options.model_path, options.detail);
    json["sweep_point"] = io::sweep_point_json(axes, point);
    const std::string path = (std::filesystem::path(sweep.out_dir) / io::point_file_name(point.index)).string();
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

/// The environment variable that tells a task which process started it (run_sweep_tasks).
constexpr const char* kParentVariable = "RBLA_SWEEP_PARENT";

/// A task started by run_sweep_tasks ends with its parent: a signal to the parent alone (kill, a
/// job scheduler's SIGTERM) would otherwise leave the tasks running to the end of the sweep.
/// Linux's parent-death signal; the check after it covers a parent that died just before.
void end_with_the_parent() {
  const char* parent = std::getenv(kParentVariable);
  if (parent == nullptr) return;
  ::prctl(PR_SET_PDEATHSIG, SIGTERM);
  if (std::to_string(::getppid()) != parent) std::raise(SIGTERM);
}

/// The same sweep as `jobs` tasks in child processes of this program, run at once.
int run_sweep_tasks(const SweepOptions& sweep) {
  std::vector<std::string> environment{std::string(kParentVariable) + "=" + std::to_string(::getpid())};
  for (char** e = environ; *e != nullptr; ++e) {
    if (std::string(*e).rfind(std::string(kParentVariable) + "=", 0) != 0) environment.emplace_back(*e);
  }
  std::vector<char*> envp;
  for (auto& entry : environment) envp.push_back(entry.data());
  envp.push_back(nullptr);
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
    if (posix_spawn(&pid, self.c_str(), nullptr, nullptr, argv.data(), envp.data()) != 0) {
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
int collect_sweep(const SweepOptions& sweep, const model::Model& m,
                  const std::vector<analysis::SweepAxis>& axes,
                  const std::vector<analysis::SweepPoint>& points) {
  std::vector<io::SweepRow> rows;
  std::map<std::string, int> counts;
  for (const auto& point : points) {
    rows.push_back(io::read_sweep_row(
        (std::filesystem::path(sweep.out_dir) / io::point_file_name(point.index)).string(), axes, point));
    ++counts[rows.back().status];
  }
  const std::string value_name =
      m.analysis.type == model::AnalysisType::Settlement ? "base_reaction" : "load_multiplier";
  const std::filesystem::path dir(sweep.out_dir);
  int code = write_output((dir / "summary.csv").string(), io::sweep_csv(axes, rows, value_name));
  if (code == kSuccess) code = write_output((dir / "sweep.svg").string(), io::sweep_svg(axes, rows, value_name));
  if (code != kSuccess) return code;
  std::string line = std::to_string(points.size()) + " points:";
  for (const auto& [status, n] : counts) line += " " + std::to_string(n) + " " + status + ",";
  line.back() = ';';
  std::cout << shown(line + " wrote " + (dir / "summary.csv").string() + " and " + (dir / "sweep.svg").string()) << "\n";
  if (counts.count("mismatched") > 0) {
    std::cerr << "rbla: " << counts["mismatched"] << " point file(s) in " << dir.string()
              << " hold other parameters than this sweep's points (left by another sweep?): their values are not "
                 "used; run their tasks again, or use a new --out\n";
  }
  const bool complete = counts.size() == counts.count("collapse") + counts.count("no_mechanism") + counts.count("cannot_stand");
  return complete ? kSuccess : kSolverFailure;
}

/// Every file the sweep may write (the Slurm script, the points' files, the summary and its
/// picture, and the folder itself while it does not exist) checked against the model and each
/// other before anything runs: a link in the folder, or a script named like the model, would
/// otherwise replace the model.
void check_sweep_outputs(const CommonOptions& options, const SweepOptions& sweep,
                         const std::vector<analysis::SweepPoint>& points) {
  std::vector<io::OutputTarget> outputs;
  if (!sweep.slurm_script.empty()) outputs.push_back(io::resolve_output(sweep.slurm_script));
  std::vector<std::string> names{"summary.csv", "sweep.svg"};
  for (const auto& point : points) names.push_back(io::point_file_name(point.index));
  for (auto& target : io::resolve_outputs_in_folder(sweep.out_dir, names)) outputs.push_back(std::move(target));
  struct stat info {};
  if (::stat(sweep.out_dir.c_str(), &info) != 0) outputs.push_back(io::resolve_output(sweep.out_dir));
  io::check_outputs(options.model_path, outputs);
}

/// Tasks read the model again, each on its own: from a regular file only (a pipe would be read
/// once, by the first).
void check_model_rereadable(const CommonOptions& options, const SweepOptions& sweep) {
  if (sweep.jobs <= 1 && sweep.slurm_script.empty() && sweep.task < 0) return;
  struct stat info {};
  if (options.model_path == "-" || (::stat(options.model_path.c_str(), &info) == 0 && !S_ISREG(info.st_mode))) {
    throw model::ModelError("model", "a sweep run as several tasks reads the model once per task: give a regular "
                                     "file, not '-' or a pipe");
  }
}

int run_sweep(const CommonOptions& options, SweepOptions sweep) {
  const auto axes = sweep_axes(sweep);
  check_model_rereadable(options, sweep);
  const auto points = sweep.random.empty() ? analysis::grid_points(axes)
                                           : analysis::random_points(axes, sweep.samples, sweep.seed);
  check_sweep_outputs(options, sweep, points);
  if (!sweep.slurm_script.empty()) {
    if (sweep.task >= 0) throw model::ModelError("--task", "the Slurm script runs every task; give --tasks only");
    const int code = write_output(sweep.slurm_script, io::slurm_script(task_command(sweep.command), sweep.tasks));
    if (code == kSuccess) progress(options, "wrote " + sweep.slurm_script + ": sbatch it, then run this sweep with --collect");
    return code;
  }
  io::LoadedModel loaded;
  int exit_code = kSuccess;
  if (!load(options, loaded, exit_code)) return exit_code;
  analysis::check_sweep(loaded.model, axes);
  io::make_folder(sweep.out_dir);
  if (sweep.task >= 0) {
    end_with_the_parent();
    return solve_sweep_points(options, sweep, loaded.model, axes, points);
  }
  if (!sweep.collect) {
    const int code = sweep.jobs > 1 ? run_sweep_tasks(sweep) : solve_sweep_points(options, sweep, loaded.model, axes, points);
    if (code == kFileError) return code;
  }
  return collect_sweep(sweep, loaded.model, axes, points);
}

}  // namespace

Command add_sweep(CLI::App& app, CommonOptions& options, std::vector<std::string> command_line) {
  auto sweep = std::make_shared<SweepOptions>();
  sweep->command = std::move(command_line);
  CLI::App* command = app.add_subcommand("sweep", "Run the model over a grid or a random sample of parameters");
  command->add_option("model", options.model_path, "Model JSON file")->required();
  command->add_option("--out", sweep->out_dir, "Folder for the points' result files, summary.csv and sweep.svg")
      ->required();
  command->add_option("--grid", sweep->grid,
                    "NAME=LOW:HIGH:COUNT, repeatable: every combination (NAME: friction, friction_factor, "
                    "unit_weight_factor, seismic_angle, settlement_tilt, settlement_azimuth; angles in degrees)");
  command->add_option("--random", sweep->random, "NAME=LOW:HIGH, repeatable: uniform random values");
  command->add_option("--samples", sweep->samples, "Points of a --random sweep")->check(CLI::Range(1, 100000));
  command->add_option("--seed", sweep->seed, "Seed of a --random sweep (the same seed, the same points)");
  command->add_option("--jobs", sweep->jobs, "Processes on this machine (each solve then on one thread)")
      ->check(CLI::Range(1, 64));
  command->add_option("--task", sweep->task, "Solve only the points with index % tasks == task (for job arrays)")
      ->check(CLI::Range(0, 100000));
  command->add_option("--tasks", sweep->tasks, "Number of tasks the points are split into")
      ->check(CLI::Range(1, 100000));
  command->add_flag("--collect", sweep->collect, "Only write summary.csv and sweep.svg from the points' files");
  command->add_option("--slurm-script", sweep->slurm_script,
                    "Write a Slurm job-array script of --tasks tasks for this sweep instead of running it");
  command->add_flag("-q,--quiet", options.quiet, "No progress or warnings on standard error");
  command->add_option("--threads", options.threads, "Threads per conic solve, 1 or 2")->check(CLI::Range(1, 2));
  add_detail_option(command, options.detail);
  add_input_limits(command, options.limits);

  return {command, [&options, sweep] { return run_sweep(options, *sweep); }};
}

}  // namespace rbla::cli
