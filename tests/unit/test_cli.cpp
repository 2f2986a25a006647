// The rbla command as a user runs it: exit codes, messages naming the field, no partial output.
#include <gtest/gtest.h>

#include "io/model_reader.hpp"
#include "io/schema_validation.hpp"
#include "support/cli_runner.hpp"

#include <nlohmann/json.hpp>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

using rbla::testing::RunResult;
RunResult run(const std::string& arguments) { return rbla::testing::run_rbla(arguments); }

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rbla_cli_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    std::ofstream(path) << text;
    return path.string();
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string read(const std::string& name) const {
    std::ifstream in(dir_ / name);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }

  static std::string box_model(const std::string& extra = "") {
    return R"({"schema_version": "1.0.0", "units": {"length": "m"}, )" + extra + R"("blocks": [
      {"id": "base", "role": "fixed",
       "vertices": [[-1,-1,-1],[2,-1,-1],[2,2,-1],[-1,2,-1],[-1,-1,0],[2,-1,0],[2,2,0],[-1,2,0]],
       "faces": [[0,3,2,1],[4,5,6,7],[0,1,5,4],[1,2,6,5],[2,3,7,6],[3,0,4,7]]},
      {"id": "B1",
       "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0],[0,0,2],[1,0,2],[1,1,2],[0,1,2]],
       "faces": [[0,3,2,1],[4,5,6,7],[0,1,5,4],[1,2,6,5],[2,3,7,6],[3,0,4,7]]}]})";
  }

  fs::path dir_;
};

}  // namespace

TEST_F(Cli, ValidateAcceptsAGoodModel) {
  const auto r = run("validate " + write("m.json", box_model()));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("valid: 2 blocks, 1 interfaces, 4 contact points"), std::string::npos) << r.output;
}

TEST_F(Cli, InfoWritesAModelOnlyResult) {
  const auto r = run("info " + write("m.json", box_model()) + " -o " + path("info.json"));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("contact points:  4"), std::string::npos) << r.output;
  const std::string text = read("info.json");
  EXPECT_NE(text.find("\"status\": \"model_only\""), std::string::npos) << text;
}

TEST_F(Cli, InfoSaysWhichTolerancesDetectionUsedAndWhatItMissed) {
  // B1 raised 50 mm: beyond the 30 mm a gap the same all over may close, a near miss.
  std::string model = box_model();
  const std::string bottom = "[0,0,0],[1,0,0],[1,1,0],[0,1,0]";
  model.replace(model.find(bottom), bottom.size(), "[0,0,0.05],[1,0,0.05],[1,1,0.05],[0,1,0.05]");
  const auto r = run("info " + write("m.json", model));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("detection:       3 % of each joint's size"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("angle 10 deg"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("near misses:     1 (closest: 'base' face 1 and 'B1' face 0, 0.05 m apart where 0.03 m "
                          "is accepted, at 0 deg"),
            std::string::npos)
      << r.output;
}

TEST_F(Cli, InvalidInputExitsWithTwoAndNamesThePointer) {
  std::string bad = box_model();
  bad.replace(bad.find("\"m\""), 3, "\"inch\"");
  const auto r = run("validate " + write("bad.json", bad));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("/units/length"), std::string::npos) << r.output;
}

TEST_F(Cli, MalformedJsonExitsWithTwo) {
  const auto r = run("validate " + write("bad.json", "{\"blocks\": [1, 2"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("malformed JSON"), std::string::npos) << r.output;
}

TEST_F(Cli, MissingFileIsAFileErrorNamingThePath) {
  const auto r = run("validate " + path("does_not_exist.json"));
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_NE(r.output.find("cannot read '" + path("does_not_exist.json") + "'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("No such file or directory"), std::string::npos) << r.output;
}

TEST_F(Cli, UsageErrorExitsWithOne) {
  EXPECT_EQ(run("frobnicate").exit_code, 1);
  EXPECT_EQ(run("solve").exit_code, 1);
  EXPECT_EQ(run("validate --no-such-flag x.json").exit_code, 1);
}

// Values CLI11's own checks let through: an empty path (read as "no output", so nothing was
// written and the exit was 0), NaN (a range check passes it) and a negative size limit (an
// unsigned option took -1 as 2^64 - 1, no limit).
TEST_F(Cli, EmptyNotANumberAndNegativeOptionValuesAreRefused) {
  const std::string model = write("m.json", box_model(R"("analysis": {"seismic": {"direction": [1, 0, 0]}}, )"));
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"solve " + model + " -o ''", "--output: an empty value"},
      {"solve " + model + " --svg ''", "--svg: an empty value"},
      {"critical-friction " + model + " --target-alpha nan", "--target-alpha: nan is not a number"},
      {"worst-direction " + model + " --tolerance -NaN", "--tolerance: -NaN is not a number"},
      {"solve " + model + " --max-input-bytes -1", "--max-input-bytes: must be positive"},
  };
  for (const auto& [arguments, words] : cases) {
    const auto r = run(arguments);
    EXPECT_EQ(r.exit_code, 1) << arguments << "\n" << r.output;
    EXPECT_NE(r.output.find(words), std::string::npos) << arguments << "\n" << r.output;
  }
  // More first directions than directions in all ran the first ones anyway.
  const auto r = run("worst-direction " + model + " --initial-directions 20 --max-directions 5");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--initial-directions: must not exceed --max-directions (5)"), std::string::npos) << r.output;
}

TEST_F(Cli, InvalidInputWritesNoOutputFile) {
  const auto r = run("info " + write("bad.json", "{}") + " -o " + path("out.json"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_FALSE(fs::exists(path("out.json")));
}

TEST_F(Cli, UnwritableOutputExitsWithFourAndLeavesNothing) {
  const auto r = run("info " + write("m.json", box_model()) + " -o " + path("no_such_dir/out.json"));
  EXPECT_EQ(r.exit_code, 4) << r.output;
  for (const auto& entry : fs::directory_iterator(dir_)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
  }
}

TEST_F(Cli, ReadsStandardInput) {
  const auto r = run("validate - < " + write("m.json", box_model()));
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

TEST_F(Cli, SolvePrintsTheVerdictAndWritesResultAndPictures) {
  const std::string model = write("m.json", box_model(R"("analysis": {"seismic": {"direction": [1, 0, 0]}}, )"));
  const auto r = run("solve " + model + " -o " + path("result.json") + " --svg " + path("pictures"));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  // One block 1 x 1 x 2 on a base: alpha = min(b/h, mu) = 0.5.
  EXPECT_NE(r.output.find("Collapse at load multiplier alpha = 0.5"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(path("result.json")));
  EXPECT_GT(fs::file_size(path("pictures/mechanism.svg")), 0u);
  EXPECT_GT(fs::file_size(path("pictures/convergence.svg")), 0u);
}

// --detail: the same analysis written with every interface's contact points, without them, or
// with block motions only. Each file validates against the result schema, says what it holds, and
// carries the same value, motions and cracked interfaces; only the interfaces' detail differs.
TEST_F(Cli, DetailLeavesOutContactPointsOrInterfacesAndNothingElse) {
  const std::string model = std::string(RBLA_SOURCE_DIR) + "/samples/wall_opening.json";
  std::map<std::string, nlohmann::json> results;
  for (const char* detail : {"points", "interfaces", "blocks"}) {
    const auto r = run("solve -q " + model + " -o " + path(detail) + " --detail " + detail);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    results[detail] = nlohmann::json::parse(read(detail));
    const auto issues = rbla::io::validate_against_schema(results[detail], rbla::io::SchemaKind::Result);
    EXPECT_TRUE(issues.empty()) << detail << ": " << issues.front().pointer << ": " << issues.front().message;
    EXPECT_EQ(results[detail]["detail"], detail);
  }
  const nlohmann::json& full = results["points"];
  ASSERT_TRUE(full.contains("interfaces"));
  EXPECT_TRUE(full["interfaces"][0].contains("points"));
  EXPECT_FALSE(results["interfaces"]["interfaces"][0].contains("points"));
  EXPECT_EQ(results["interfaces"]["interfaces"].size(), full["interfaces"].size());
  EXPECT_FALSE(results["blocks"].contains("interfaces"));
  for (const auto& [detail, result] : results) {
    EXPECT_EQ(result["load_multiplier"], full["load_multiplier"]) << detail;
    EXPECT_EQ(result["blocks"], full["blocks"]) << detail;
    EXPECT_EQ(result["cracked_interfaces"], full["cracked_interfaces"]) << detail;
  }
  const auto bad = run("solve -q " + model + " -o " + path("bad") + " --detail forces");
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_NE(bad.output.find("--detail"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(path("bad")));
}

TEST_F(Cli, CannotStandIsAnAnswerNotAnError) {
  std::string model = box_model();
  // Lift the block 1 m off the base: nothing holds it.
  for (const char* from : {"[0,0,0]", "[1,0,0]", "[1,1,0]", "[0,1,0]"}) {
    const auto at = model.find(from, model.find("\"B1\""));
    model.replace(at, std::string(from).size(), std::string(from).substr(0, std::string(from).size() - 2) + "1]");
  }
  const auto r = run("solve " + write("m.json", model) + " -o " + path("result.json"));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("Cannot stand as modelled: block 'B1' touches nothing"), std::string::npos) << r.output;
}

TEST_F(Cli, DumpProblemWritesAnMpsForThePlanarLp) {
  const auto r = run("solve -q " + write("m.json", box_model()) + " --dump-problem " + path("p.mps"));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const std::string text = read("p.mps");
  EXPECT_NE(text.find("ROWS"), std::string::npos);
  EXPECT_NE(text.find("ENDATA"), std::string::npos);
}

TEST_F(Cli, UnwritableProblemDumpIsAFileErrorNamingThePath) {
  const auto r = run("solve -q " + write("m.json", box_model()) + " --dump-problem " + path("no_such_dir/p.cbf"));
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_NE(r.output.find("cannot write '" + path("no_such_dir/p.cbf") + "': its folder"), std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("Collapse"), std::string::npos) << "refused before the analysis: " << r.output;
}

TEST_F(Cli, ThreadsOptionTakesOneOrTwo) {
  const std::string model = write("m.json", box_model());
  for (const char* threads : {"1", "2"}) {
    const auto r = run("solve " + model + " --threads " + threads + " -o " + path("r.json"));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("Collapse at load multiplier alpha = 0.5"), std::string::npos) << r.output;
  }
  const auto r = run("solve -q " + model + " --threads 3 -o " + path("r3.json"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("--threads"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("r3.json")));
}

TEST_F(Cli, WorstDirectionWritesAValidResultWithTheSearchAndItsPictures) {
  // A 1 x 1 x 2 block on a wider base tips at alpha = 0.5 / 1 (half its width over its
  // centroid's height) along the four edge normals, before it slides (default friction 0.6).
  const auto r = run("worst-direction -q " + write("m.json", box_model()) + " -o " + path("w.json") + " --svg " +
                     path("pictures"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("Weakest horizontal direction at"), std::string::npos) << r.output;
  const std::string text = read("w.json");
  EXPECT_TRUE(rbla::io::validate_result_text(text).empty()) << text.substr(0, 2000);
  const auto result = nlohmann::json::parse(text);
  const auto& w = result.at("worst_direction");
  EXPECT_NEAR(w.at("load_multiplier").get<double>(), 0.5, 0.5e-6);
  EXPECT_TRUE(w.at("certified").get<bool>());
  EXPECT_LE(w.at("lower_bound").get<double>(), 0.5 + 1e-9);
  EXPECT_EQ(w.at("num_evaluations").get<int>(), static_cast<int>(w.at("evaluations").size()));
  // The rest of the file is the analysis along the weakest direction.
  EXPECT_DOUBLE_EQ(result.at("load_multiplier").get<double>(), w.at("load_multiplier").get<double>());
  EXPECT_TRUE(fs::exists(path("pictures/mechanism.svg")));
  EXPECT_TRUE(fs::exists(path("pictures/worst_direction.svg")));
}

TEST_F(Cli, WorstDirectionRefusesASettlementModelNamingTheField) {
  std::string model = box_model(R"("analysis": {"type": "settlement"}, )");
  model.replace(model.find(R"("role": "fixed")"), 15, R"("role": "moving_support")");
  const auto r = run("worst-direction " + write("m.json", model) + " -o " + path("w.json"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("/analysis/type"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("w.json")));
}

TEST_F(Cli, WorstSettlementWritesAValidResultAtTheMostHarmfulDirection) {
  const std::string sample = std::string(RBLA_SOURCE_DIR) + "/samples/wall_settlement.json";
  const auto r = run("worst-settlement -q " + sample + " --cone-angle 20 -o " + path("w.json") + " --svg " +
                     path("pictures"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("Most harmful settlement direction"), std::string::npos) << r.output;
  const std::string text = read("w.json");
  EXPECT_TRUE(rbla::io::validate_result_text(text).empty()) << text.substr(0, 2000);
  const auto result = nlohmann::json::parse(text);
  const auto& w = result.at("worst_settlement");
  EXPECT_TRUE(w.at("certified").get<bool>());
  EXPECT_DOUBLE_EQ(w.at("cone_angle_deg").get<double>(), 20.0);
  EXPECT_LE(w.at("tilt_deg").get<double>(), 20.0 + 1e-9);
  EXPECT_GE(w.at("upper_bound").get<double>(), w.at("ratio").get<double>());
  EXPECT_EQ(w.at("num_evaluations").get<int>(), static_cast<int>(w.at("evaluations").size()));
  // The rest of the file is the settlement analysis along that direction.
  EXPECT_DOUBLE_EQ(result.at("base_reaction").at("at_collapse").get<double>(), w.at("base_reaction").get<double>());
  EXPECT_TRUE(fs::exists(path("pictures/worst_settlement.svg")));
}

TEST_F(Cli, WorstSettlementRanksCandidateGroupsOfSupports) {
  const std::string sample = std::string(RBLA_SOURCE_DIR) + "/samples/wall_settlement.json";
  const auto r = run("worst-settlement -q " + sample + " --candidate-group base_moving --candidate-group base_fixed -o " +
                     path("g.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("Most harmful of 2 candidate groups"), std::string::npos) << r.output;
  const std::string text = read("g.json");
  EXPECT_TRUE(rbla::io::validate_result_text(text).empty()) << text.substr(0, 2000);
  const auto result = nlohmann::json::parse(text);
  const auto& w = result.at("worst_settlement");
  const auto& groups = w.at("candidate_groups").at("groups");
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[0].at("supports"), nlohmann::json::array({"base_moving"}));
  int top = -1;
  for (int g = 0; g < 2; ++g) {
    if (groups[g].at("most_harmful").get<bool>()) top = g;
  }
  ASSERT_GE(top, 0);
  // The rest of the file is the most harmful group's search and analysis.
  EXPECT_DOUBLE_EQ(w.at("ratio").get<double>(), groups[top].at("ratio").get<double>());
  EXPECT_DOUBLE_EQ(result.at("base_reaction").at("at_collapse").get<double>(), groups[top].at("base_reaction").get<double>());
  if (w.at("candidate_groups").at("certain").get<bool>()) {
    EXPECT_LT(groups[1 - top].at("upper_bound").get<double>(), groups[top].at("ratio").get<double>());
  }
}

TEST_F(Cli, WorstSettlementNamesACandidateGroupItCannotUse) {
  const std::string sample = std::string(RBLA_SOURCE_DIR) + "/samples/wall_settlement.json";
  write("g.json", "not ours");
  const auto unknown = run("worst-settlement " + sample + " --candidate-group base_moving,no_such_pier -o " + path("g.json"));
  EXPECT_EQ(unknown.exit_code, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("--candidate-group"), std::string::npos) << unknown.output;
  EXPECT_NE(unknown.output.find("'no_such_pier'"), std::string::npos) << unknown.output;
  std::ifstream model_file(sample);
  std::string free_block;
  const nlohmann::json model = nlohmann::json::parse(model_file);
  for (const auto& block : model.at("blocks")) {
    if (block.value("role", "free") == "free") free_block = block.at("id").get<std::string>();
  }
  ASSERT_FALSE(free_block.empty());
  const auto not_support = run("worst-settlement " + sample + " --candidate-group " + free_block + " -o " + path("g.json"));
  EXPECT_EQ(not_support.exit_code, 2) << not_support.output;
  EXPECT_NE(not_support.output.find("is not a support"), std::string::npos) << not_support.output;
  const std::string text = read("g.json");
  EXPECT_EQ(text, "not ours");
}

TEST_F(Cli, WorstSettlementRefusesALoadMultiplierModelNamingTheField) {
  const auto r = run("worst-settlement " + write("m.json", box_model()) + " -o " + path("w.json"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("/analysis/type"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("w.json")));
}

TEST_F(Cli, CriticalFrictionScalesTheInterfacesOfChosenBlocks) {
  const auto r = run("critical-friction -q " + write("m.json", box_model()) + " --interfaces-of B1 --target-alpha 0.3" +
                     " --tolerance 1e-6 -o " + path("c.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string text = read("c.json");
  EXPECT_TRUE(rbla::io::validate_result_text(text).empty()) << text.substr(0, 2000);
  const auto c = nlohmann::json::parse(text).at("critical_friction");
  ASSERT_EQ(c.at("scaled_interfaces").size(), 1u);
  EXPECT_NEAR(c.at("friction").get<double>(), 0.3, 1e-6);
}

TEST_F(Cli, CriticalFrictionNamesAnInterfaceItCannotFind) {
  write("c.json", "not ours");
  const auto r = run("critical-friction " + write("m.json", box_model()) + " --interfaces I0,no_such_joint -o " +
                     path("c.json"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--interfaces"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("'no_such_joint'"), std::string::npos) << r.output;
  const std::string text = read("c.json");
  EXPECT_EQ(text, "not ours");  // the file that was there is left as it was
}

TEST_F(Cli, CriticalFrictionWritesAValidResultWithTheBracket) {
  // The same block carries alpha = min(mu, 0.5): alpha 0.3 needs mu = 0.3, the given 0.6 times 0.5.
  const auto r = run("critical-friction -q " + write("m.json", box_model()) + " --target-alpha 0.3 --tolerance 1e-6 -o " +
                     path("c.json") + " --svg " + path("pictures"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string text = read("c.json");
  EXPECT_TRUE(rbla::io::validate_result_text(text).empty()) << text.substr(0, 2000);
  const auto c = nlohmann::json::parse(text).at("critical_friction");
  EXPECT_EQ(c.at("outcome"), "bracketed");
  EXPECT_NEAR(c.at("friction").get<double>(), 0.3, 1e-6);
  EXPECT_LE(c.at("factor_lower").get<double>(), c.at("factor").get<double>());
  EXPECT_TRUE(fs::exists(path("pictures/critical_friction.svg")));
}
