// Every bundled sample is valid against the model schema and passes the whole model stage
// with no warnings; the counts are those of the geometry the generator wrote.
#include "analysis/limit_analysis.hpp"
#include "io/load_model.hpp"
#include "io/result_writer.hpp"
#include "io/model_reader.hpp"
#include "io/schema_validation.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <map>

namespace fs = std::filesystem;

namespace {

struct Expected {
  std::size_t blocks;
  std::size_t interfaces;
};

// Interface counts by hand: block: 1 bed joint. column: 4 stacked bed joints. arch: 16 voussoirs
// give 15 radial joints + 2 springings. The two walls: counted by the independent brute-force
// pair check the generator's author ran (all face pairs, no spatial index).
const std::map<std::string, Expected> kExpected = {
    {"block.json", {2, 1}},
    {"column.json", {5, 4}},
    {"arch.json", {18, 17}},
    {"wall_opening.json", {118, 308}},
    {"wall_settlement.json", {127, 344}},
};

}  // namespace

TEST(Samples, AllBundledSamplesValidateAndLoad) {
  const fs::path dir = fs::path(RBLA_SOURCE_DIR) / "samples";
  std::size_t seen = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "expected.json") continue;
    ++seen;
    const std::string name = entry.path().filename().string();
    SCOPED_TRACE(name);
    const std::string text = rbla::io::read_text(entry.path().string());
    const auto issues = rbla::io::validate_against_schema(nlohmann::json::parse(text), rbla::io::SchemaKind::Model);
    EXPECT_TRUE(issues.empty()) << issues.front().pointer << ": " << issues.front().message;
    const auto loaded = rbla::io::load_model_text(text);
    EXPECT_TRUE(loaded.model.warnings.empty()) << loaded.model.warnings.front().message;
    const auto expected = kExpected.find(name);
    ASSERT_NE(expected, kExpected.end()) << "a new sample needs its expected counts here";
    EXPECT_EQ(loaded.model.blocks.size(), expected->second.blocks);
    EXPECT_EQ(loaded.model.interfaces.size(), expected->second.interfaces);
  }
  EXPECT_EQ(seen, kExpected.size());
}

// Each sample's headline number against samples/expected.json (closed forms, or CLP on the LP
// rbla writes), and its result JSON valid against the result schema.
TEST(Samples, HeadlineResultsMatchIndependentReferences) {
  const fs::path dir = fs::path(RBLA_SOURCE_DIR) / "samples";
  std::ifstream in(dir / "expected.json");
  const nlohmann::json expected = nlohmann::json::parse(in)["samples"];
  ASSERT_EQ(expected.size(), kExpected.size());
  for (const auto& [name, reference] : expected.items()) {
    SCOPED_TRACE(name);
    const auto loaded = rbla::io::load_model_file((dir / name).string());
    const auto result = rbla::analysis::analyse(loaded.model);
    ASSERT_EQ(result.verdict, rbla::analysis::Verdict::Collapse) << result.verdict_text;
    if (reference.contains("load_multiplier")) {
      const double value = reference["load_multiplier"].get<double>();
      ASSERT_TRUE(result.load_multiplier.has_value());
      EXPECT_NEAR(*result.load_multiplier, value, 1e-6 * value);
    } else {
      const double value = reference["base_reaction"].get<double>();
      ASSERT_TRUE(result.base_reaction.has_value());
      EXPECT_NEAR(*result.base_reaction, value, 1e-6 * value);
      const double initial = reference.at("initial_base_reaction").get<double>();
      ASSERT_TRUE(result.initial_base_reaction.has_value());
      EXPECT_NEAR(*result.initial_base_reaction, initial, 1e-9 * initial);
    }
    EXPECT_LT(result.work.relative_error, 1e-6);
    const nlohmann::json json = rbla::io::analysis_result_json(loaded.model, result, loaded.timings, name);
    const auto issues = rbla::io::validate_against_schema(json, rbla::io::SchemaKind::Result);
    EXPECT_TRUE(issues.empty()) << issues.front().pointer << ": " << issues.front().message;
  }
}

// Every sample with non-associative friction at the default scheme settings: a state that passes
// the fixed-point test, never above the associative value (never below, for a settlement
// reaction), its work balance with mu N |slip| closing, and its result valid.
TEST(Samples, NonAssociativeConvergesOnTheSafeSide) {
  const fs::path dir = fs::path(RBLA_SOURCE_DIR) / "samples";
  for (const auto& [name, counts] : kExpected) {
    SCOPED_TRACE(name);
    const auto loaded = rbla::io::load_model_file((dir / name).string());
    rbla::model::Model model = loaded.model;
    const auto associative = rbla::analysis::analyse(model);
    model.analysis.friction_model = rbla::model::FrictionModel::NonAssociative;
    const auto result = rbla::analysis::analyse(model);
    ASSERT_EQ(result.verdict, rbla::analysis::Verdict::Collapse) << result.verdict_text;
    EXPECT_TRUE(result.non_associative_converged) << result.non_associative_stop;
    if (result.base_reaction) {
      EXPECT_GE(*result.base_reaction, *associative.base_reaction * (1.0 - 1e-7));
    } else {
      EXPECT_LE(*result.load_multiplier, *associative.load_multiplier * (1.0 + 1e-7));
    }
    EXPECT_LT(result.work.relative_error, 1e-3);
    const nlohmann::json json = rbla::io::analysis_result_json(model, result, loaded.timings, name);
    const auto issues = rbla::io::validate_against_schema(json, rbla::io::SchemaKind::Result);
    EXPECT_TRUE(issues.empty()) << issues.front().pointer << ": " << issues.front().message;
  }
}
