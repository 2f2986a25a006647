// Parameter studies (analysis/sweep.hpp, io/sweep_io.hpp): the points of grids and seeded random
// samples, the model at a point, the axes as typed, and the Slurm job array run locally.
#include "analysis/sweep.hpp"
#include "io/load_model.hpp"
#include "io/model_reader.hpp"
#include "io/sweep_io.hpp"
#include "model/errors.hpp"
#include "support/cli_runner.hpp"
#include "support/model_builder.hpp"

#include <gtest/gtest.h>

#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <vector>
#include <thread>
#include <chrono>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

extern char** environ;

namespace {

namespace fs = std::filesystem;
using rbla::analysis::SweepAxis;
using rbla::analysis::SweepParameter;

rbla::model::Model box_on_base(const std::string& analysis_type = "load_multiplier") {
  using namespace rbla::testing;
  json model = model_with(json::array({box_block("base", -1, -1, -1, 2, 2, 0, analysis_type == "settlement" ? "moving_support" : "fixed"),
                                       box_block("B", 0, 0, 0, 1, 1, 2)}));
  model["analysis"] = {{"type", analysis_type}};
  if (analysis_type != "settlement") model["analysis"]["seismic"] = {{"direction", {1.0, 0.0, 0.0}}};
  return rbla::io::load_model_text(model.dump()).model;
}

TEST(Sweep, GridIsEveryCombinationWithTheLastAxisFastest) {
  const std::vector<SweepAxis> axes{{SweepParameter::Friction, 0.2, 0.6, 3}, {SweepParameter::SeismicAngle, 0, 90, 2}};
  const auto points = rbla::analysis::grid_points(axes);
  ASSERT_EQ(points.size(), 6u);
  EXPECT_DOUBLE_EQ(points[0].values[0], 0.2);
  EXPECT_DOUBLE_EQ(points[1].values[1], 90.0);
  EXPECT_DOUBLE_EQ(points[2].values[0], 0.4);
  EXPECT_DOUBLE_EQ(points[5].values[0], 0.6);
  EXPECT_EQ(points[5].index, 5);
}

TEST(Sweep, RandomSamplesAreReproducibleAndInRange) {
  const std::vector<SweepAxis> axes{{SweepParameter::Friction, 0.3, 0.7, 1}};
  const auto a = rbla::analysis::random_points(axes, 1000, 42), b = rbla::analysis::random_points(axes, 1000, 42);
  const auto c = rbla::analysis::random_points(axes, 1000, 43);
  double mean = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].values, b[i].values);
    EXPECT_GE(a[i].values[0], 0.3);
    EXPECT_LT(a[i].values[0], 0.7);
    mean += a[i].values[0] / a.size();
  }
  EXPECT_NE(a[0].values, c[0].values);
  EXPECT_NEAR(mean, 0.5, 0.02);  // uniform: 0.5 +- 3 standard errors (0.115 / sqrt(1000) each)
}

TEST(Sweep, ModelAtAPointSetsFrictionDirectionsAndWeights) {
  const auto m = box_on_base();
  const std::vector<SweepAxis> axes{{SweepParameter::Friction, 0, 0, 1}, {SweepParameter::SeismicAngle, 0, 0, 1},
                                    {SweepParameter::UnitWeightFactor, 0, 0, 1}};
  const auto at = rbla::analysis::model_at(m, axes, {0, {0.35, 90.0, 2.0}});
  for (const auto& contact : at.interfaces) EXPECT_DOUBLE_EQ(contact.friction, 0.35);
  EXPECT_NEAR(at.analysis.seismic_direction->y(), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(at.blocks[1].unit_weight, 2.0 * m.blocks[1].unit_weight);
  const auto settling = box_on_base("settlement");
  const std::vector<SweepAxis> tilt{{SweepParameter::SettlementTilt, 0, 0, 1}, {SweepParameter::SettlementAzimuth, 0, 0, 1}};
  const auto tilted = rbla::analysis::model_at(settling, tilt, {0, {30.0, 90.0}});
  EXPECT_NEAR(tilted.analysis.settlement_direction.z(), -std::cos(30.0 * M_PI / 180.0), 1e-12);
  EXPECT_NEAR(tilted.analysis.settlement_direction.y(), 0.5, 1e-12);
}

TEST(Sweep, ParametersThatDoNotApplyAreRefusedBeforeAnythingRuns) {
  const auto m = box_on_base();
  EXPECT_THROW(rbla::analysis::check_sweep(m, {{SweepParameter::SettlementTilt, 0, 10, 3}}), rbla::model::ModelError);
  EXPECT_THROW(rbla::analysis::check_sweep(m, {{SweepParameter::Friction, 0.0, 0.5, 3}}), rbla::model::ModelError);
  EXPECT_NO_THROW(rbla::analysis::check_sweep(m, {{SweepParameter::Friction, 0.1, 0.5, 3}}));
  EXPECT_THROW(rbla::analysis::check_sweep(m, {{SweepParameter::UnitWeightFactor, 0.0, 1.0, 2}}), rbla::model::ModelError);
  EXPECT_THROW(rbla::analysis::check_sweep(m, {{SweepParameter::UnitWeightFactor, 1e-300, 1e300, 3}}), rbla::model::ModelError);
  EXPECT_NO_THROW(rbla::analysis::check_sweep(m, {{SweepParameter::UnitWeightFactor, 0.5, 2.0, 3}}));
  // A forced planar formulation cannot follow a load turned out of its plane: refused before the
  // first point runs (it failed at the second point, without a summary).
  auto planar = m;
  planar.analysis.formulation = rbla::model::Formulation::Planar;
  EXPECT_THROW(rbla::analysis::check_sweep(planar, {{SweepParameter::SeismicAngle, 0, 90, 3}}), rbla::model::ModelError);
  EXPECT_NO_THROW(rbla::analysis::check_sweep(planar, {{SweepParameter::Friction, 0.1, 0.5, 3}}));
  EXPECT_THROW(rbla::io::parse_sweep_axis("friction=0.1:0.5", true, "--grid"), rbla::model::ModelError);
  EXPECT_THROW(rbla::io::parse_sweep_axis("mu=0.1:0.5:3", true, "--grid"), rbla::model::ModelError);
  EXPECT_THROW(rbla::io::parse_sweep_axis("friction=0.1:x:3", true, "--grid"), rbla::model::ModelError);
  EXPECT_THROW(rbla::io::parse_sweep_axis("friction=0.1:0.5:2.5", true, "--grid"), rbla::model::ModelError);
  const auto axis = rbla::io::parse_sweep_axis("seismic_angle=0:180:7", true, "--grid");
  EXPECT_EQ(axis.parameter, SweepParameter::SeismicAngle);
  EXPECT_EQ(axis.count, 7);
}

// Options that do not parse are usage errors (exit 1, as README says for option values); they
// were exit 2, the code for an invalid model.
TEST(Sweep, MalformedSweepOptionsAreUsageErrors) {
  const std::string model = std::string(RBLA_SOURCE_DIR) + "/samples/wall_opening.json";
  const fs::path dir = fs::temp_directory_path() / ("rbla_sweep_usage_" + std::to_string(::getpid()));
  for (const char* options : {"--grid friction=0.1:x:3", "--grid mu=0.1:0.5:3", "--grid friction=0.1:0.5",
                                     "--random friction=0.1:0.5", "--grid friction=0.1:0.5:2 --tasks 2 --task 2",
                                     "--grid friction=0.1:0.5:1000 --grid friction_factor=0.5:1:1000"}) {
    const auto r = rbla::testing::run_rbla("sweep -q " + model + " --out " + dir.string() + " " + std::string(options));
    EXPECT_EQ(r.exit_code, 1) << options << "\n" << r.output;
    EXPECT_NE(r.output.find("rbla: --"), std::string::npos) << "names the option: " << r.output;
    EXPECT_FALSE(fs::exists(dir)) << "nothing made";
  }
}

std::string read(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(Sweep, TheSlurmArrayRunLocallyGivesTheSameSummaryAsOneProcess) {
  const fs::path dir = fs::temp_directory_path() / ("rbla_sweep_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string model = std::string(RBLA_SOURCE_DIR) + "/samples/block.json";
  const std::string axes = " --grid friction=0.2:0.8:4 --grid seismic_angle=0:90:2";
  auto r = rbla::testing::run_rbla("sweep -q " + model + " --out " + (dir / "one").string() + axes);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = rbla::testing::run_rbla("sweep " + model + " --out " + (dir / "array").string() + axes + " --tasks 3 --slurm-script " +
                              (dir / "job.sh").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string script = read(dir / "job.sh");
  EXPECT_NE(script.find("#SBATCH --array=0-2"), std::string::npos) << script;
  for (int task = 0; task < 3; ++task) {
    const std::string run = "SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " bash " + (dir / "job.sh").string() + " 2>&1";
    ASSERT_EQ(std::system(run.c_str()), 0) << run;
  }
  r = rbla::testing::run_rbla("sweep -q " + model + " --out " + (dir / "array").string() + axes + " --collect");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("8 points: 8 collapse"), std::string::npos) << r.output;
  // Same points, statuses and values (the seconds differ).
  auto without_seconds = [](const std::string& csv) {
    std::string out, line;
    std::istringstream in(csv);
    while (std::getline(in, line)) out += line.substr(0, line.rfind(',')) + "\n";
    return out;
  };
  EXPECT_EQ(without_seconds(read(dir / "one" / "summary.csv")), without_seconds(read(dir / "array" / "summary.csv")));
  // samples/block.json is 1 x 1 x 2: along x and along y alpha = min(mu, b/h) = min(mu, 0.5).
  std::istringstream rows(read(dir / "one" / "summary.csv"));
  std::string row;
  std::getline(rows, row);
  EXPECT_EQ(row, "index,friction,seismic_angle,status,load_multiplier,seconds");
  int checked = 0;
  while (std::getline(rows, row)) {
    std::vector<std::string> cells;
    std::istringstream in(row);
    for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 6u) << row;
    EXPECT_NEAR(std::stod(cells[4]), std::min(std::stod(cells[1]), 0.5), 1e-6) << row;
    ++checked;
  }
  EXPECT_EQ(checked, 8);
  EXPECT_TRUE(rbla::io::validate_result_text(read(dir / "array" / "point_000005.json")).empty());
  fs::remove_all(dir);
}

TEST(Sweep, CollectListsMissingPointsAndFails) {
  const fs::path dir = fs::temp_directory_path() / ("rbla_sweep_missing_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string model = std::string(RBLA_SOURCE_DIR) + "/samples/block.json";
  const auto r = rbla::testing::run_rbla("sweep -q " + model + " --out " + dir.string() + " --grid friction=0.2:0.8:3 --collect");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("3 missing"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

// Another sweep's point files left in --out are not taken for this sweep's: the points of seed 8
// whose files come from seed 7 are listed as mismatched, without a value (they had seed 7's
// values under seed 8's parameters).
TEST(Sweep, CollectRefusesPointFilesOfAnotherSweep) {
  const fs::path dir = fs::temp_directory_path() / ("rbla_sweep_stale_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string model = std::string(RBLA_SOURCE_DIR) + "/samples/block.json";
  const std::string sweep = "sweep -q " + model + " --out " + dir.string() + " --random friction=0.1:0.5 --samples 4";
  auto r = rbla::testing::run_rbla(sweep + " --seed 7");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = rbla::testing::run_rbla(sweep + " --seed 8 --task 0 --tasks 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = rbla::testing::run_rbla(sweep + " --seed 8 --collect");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("2 collapse"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("2 mismatched"), std::string::npos) << r.output;
  const std::string csv = read(dir / "summary.csv");
  EXPECT_NE(csv.find(",mismatched,,"), std::string::npos) << csv;
  fs::remove_all(dir);
}

// No file the sweep writes may be the model: a Slurm script named like it, or a point file that
// is a link to it, replaced the model with exit 0. Tasks read the model again, so a pipe is
// refused when the sweep runs as several.
TEST(Sweep, NoOutputOfTheSweepReplacesTheModel) {
  const fs::path dir = fs::temp_directory_path() / ("rbla_sweep_model_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "points");
  const fs::path model = dir / "model.json";
  fs::copy_file(std::string(RBLA_SOURCE_DIR) + "/samples/block.json", model);
  const std::string original = read(model);
  fs::create_symlink(model, dir / "points" / "point_000001.json");
  const std::string sweep = "sweep -q " + model.string() + " --grid friction=0.2:0.8:2 --out ";
  auto r = rbla::testing::run_rbla(sweep + (dir / "points").string());
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_NE(r.output.find("it is the model being read"), std::string::npos) << r.output;
  r = rbla::testing::run_rbla(sweep + (dir / "other").string() + " --tasks 2 --slurm-script " + model.string());
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_EQ(read(model), original);
  EXPECT_FALSE(fs::exists(dir / "other")) << "refused before anything was made";
  // A FIFO nobody writes into: the tasks hung reading it; refused before it is opened.
  const fs::path fifo = dir / "fifo.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  r = rbla::testing::run_rbla("sweep -q " + fifo.string() + " --grid friction=0.2:0.8:2 --jobs 2 --out " +
                              (dir / "piped").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("give a regular file"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

/// The processes whose command line holds `word` (other than this one).
int processes_with(const std::string& word) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos || std::stoi(name) == ::getpid()) continue;
    std::string cmdline = read(entry.path() / "cmdline");
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    if (cmdline.find(word) != std::string::npos) ++count;
  }
  return count;
}

// A signal to the sweep's parent alone (kill PID, a scheduler's SIGTERM) ends its tasks too: they
// ran on to the end of the sweep, writing its files, after the parent had gone.
TEST(Sweep, TheTasksEndWithTheirParent) {
  const fs::path dir = fs::temp_directory_path() / ("rbla_sweep_parent_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string model = std::string(RBLA_SOURCE_DIR) + "/samples/wall_opening.json";
  std::vector<std::string> words = {RBLA_BINARY, "sweep", "-q", model, "--out", dir.string(),
                                    "--grid", "friction=0.3:0.8:20000", "--jobs", "2"};
  std::vector<char*> argv;
  for (auto& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  pid_t parent = 0;
  ASSERT_EQ(posix_spawn(&parent, RBLA_BINARY, nullptr, nullptr, argv.data(), environ), 0);
  // Waits (at most a minute: a bound, not a timing) until the tasks are solving points.
  for (int k = 0; k < 600 && !fs::exists(dir / "point_000001.json"); ++k) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  ASSERT_EQ(processes_with(dir.string()), 3) << "the parent and its two tasks";
  ::kill(parent, SIGTERM);
  int status = 0;
  ASSERT_EQ(::waitpid(parent, &status, 0), parent);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM);
  int left = 3;
  for (int k = 0; k < 300 && (left = processes_with(dir.string())) > 0; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(left, 0) << "tasks still running after their parent ended";
  for (const auto& entry : fs::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
  }
  fs::remove_all(dir);
}

}  // namespace
