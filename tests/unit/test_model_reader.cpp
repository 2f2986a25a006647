// The model pipeline: defaults, unit conversion, and bad input rejected with its JSON pointer.
#include "io/load_model.hpp"
#include "io/model_reader.hpp"
#include "support/model_builder.hpp"

#include <gtest/gtest.h>

using namespace rbla::testing;
using rbla::io::load_model_text;
using rbla::model::ModelError;

namespace {

json two_stacked_boxes() {
  return model_with(json::array({box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"), box_block("B1", 0, 0, 0, 1, 1, 2)}));
}

/// Runs the pipeline on `model` and returns the issues it threw (empty when it accepted the model).
std::vector<rbla::model::InputIssue> issues_of(const std::string& text) {
  try {
    load_model_text(text);
  } catch (const ModelError& error) {
    return error.issues();
  }
  return {};
}

std::vector<rbla::model::InputIssue> issues_of(const json& model) { return issues_of(model.dump()); }

/// True when some issue is at exactly `pointer` and its message contains `words`.
bool has_issue(const std::vector<rbla::model::InputIssue>& issues, const std::string& pointer,
               const std::string& words = "") {
  for (const auto& issue : issues) {
    if (issue.pointer == pointer && issue.message.find(words) != std::string::npos) return true;
  }
  return false;
}

std::string describe(const std::vector<rbla::model::InputIssue>& issues) {
  std::string text;
  for (const auto& issue : issues) text += "[" + issue.pointer + "] " + issue.message + "\n";
  return text.empty() ? "(accepted)" : text;
}

}  // namespace

TEST(ModelReader, DefaultsAndSelfWeight) {
  const auto loaded = load_model_text(two_stacked_boxes().dump());
  const auto& m = loaded.model;
  ASSERT_EQ(m.blocks.size(), 2u);
  EXPECT_EQ(m.blocks[0].role, rbla::model::BlockRole::Fixed);
  EXPECT_DOUBLE_EQ(m.blocks[1].unit_weight, 18.0);
  EXPECT_NEAR(m.blocks[1].weight(), 36.0, 1e-12);
  EXPECT_DOUBLE_EQ(m.default_friction, 0.6);
  EXPECT_EQ(m.gravity, -rbla::model::Vec3::UnitZ());
  // No analysis section and no live loads: seismic along +x by default (schema: analysis).
  ASSERT_TRUE(m.analysis.seismic_direction.has_value());
  EXPECT_EQ(*m.analysis.seismic_direction, rbla::model::Vec3::UnitX());
  EXPECT_TRUE(m.warnings.empty());
}

TEST(ModelReader, MillimetresAndNewtonsAreConverted) {
  json model = scaled(two_stacked_boxes(), 1000.0);
  model["units"] = {{"length", "mm"}, {"force", "N"}, {"unit_weight", "N/mm3"}};
  model["defaults"] = {{"unit_weight", 18e-6}};  // 18 kN/m^3 = 18e-6 N/mm^3
  model["loads"] = {{"live", {{{"block", "B1"}, {"force", {1000.0, 0, 0}}}}}};
  const auto m = load_model_text(model.dump()).model;
  EXPECT_NEAR(m.blocks[1].volume, 2.0, 1e-12);
  EXPECT_NEAR(m.blocks[1].unit_weight, 18.0, 1e-9);
  EXPECT_NEAR((m.blocks[1].centroid - rbla::model::Vec3(0.5, 0.5, 1.0)).norm(), 0.0, 1e-12);
  ASSERT_EQ(m.live_loads.size(), 1u);
  EXPECT_NEAR(m.live_loads[0].force.x(), 1.0, 1e-15);  // 1000 N = 1 kN
  EXPECT_NEAR((m.live_loads[0].point - m.blocks[1].centroid).norm(), 0.0, 1e-15);
}

TEST(ModelReaderErrors, MalformedJson) {
  const auto issues = issues_of(std::string("{\"schema_version\": \"1.0.0\", \"units\": "));
  ASSERT_EQ(issues.size(), 1u);
  // The pointer says where the parser was: the value of "units" never came.
  EXPECT_TRUE(has_issue(issues, "/units", "malformed JSON")) << describe(issues);
  EXPECT_TRUE(has_issue(issues, "/units", "line 1, column 38")) << describe(issues);
}

TEST(ModelReaderErrors, TruncatedFile) {
  const std::string text = two_stacked_boxes().dump();
  const auto issues = issues_of(text.substr(0, text.size() / 2));
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_NE(issues[0].message.find("malformed JSON"), std::string::npos) << describe(issues);
  EXPECT_NE(issues[0].message.find("unexpected end of input"), std::string::npos) << describe(issues);
  EXPECT_EQ(issues[0].pointer.rfind("/blocks/", 0), 0u) << describe(issues);  // cut inside the blocks
}

TEST(ModelReaderErrors, EmptyDocumentAndWrongTopLevelType) {
  EXPECT_TRUE(has_issue(issues_of(std::string("")), "", "malformed JSON"));
  EXPECT_FALSE(issues_of(std::string("[1, 2, 3]")).empty());
}

TEST(ModelReaderErrors, MissingUnits) {
  json model = two_stacked_boxes();
  model.erase("units");
  const auto issues = issues_of(model);
  EXPECT_TRUE(has_issue(issues, "", "units")) << describe(issues);
}

TEST(ModelReaderErrors, UnknownLengthUnit) {
  json model = two_stacked_boxes();
  model["units"]["length"] = "inch";
  const auto issues = issues_of(model);
  EXPECT_TRUE(has_issue(issues, "/units/length")) << describe(issues);
}

TEST(ModelReaderErrors, VertexWithTwoCoordinates) {
  json model = two_stacked_boxes();
  model["blocks"][1]["vertices"][3] = {0.0, 1.0};
  const auto issues = issues_of(model);
  EXPECT_TRUE(has_issue(issues, "/blocks/1/vertices/3")) << describe(issues);
}

TEST(ModelReaderErrors, WrongTypeForCoordinate) {
  json model = two_stacked_boxes();
  model["blocks"][1]["vertices"][2][0] = "1.0";
  const auto issues = issues_of(model);
  EXPECT_TRUE(has_issue(issues, "/blocks/1/vertices/2/0")) << describe(issues);
}

TEST(ModelReaderErrors, HugeCoordinate) {
  json model = two_stacked_boxes();
  model["blocks"][1]["vertices"][2][0] = 1e300;
  const auto issues = issues_of(model);
  EXPECT_TRUE(has_issue(issues, "/blocks/1/vertices/2/0")) << describe(issues);
}

TEST(ModelReaderErrors, FaceIndexOutOfRange) {
  json model = two_stacked_boxes();
  model["blocks"][1]["faces"][2][1] = 8;
  const auto issues = issues_of(model);
  EXPECT_TRUE(has_issue(issues, "/blocks/1/faces/2/1", "out of range")) << describe(issues);
}

TEST(ModelReaderErrors, DuplicateBlockId) {
  json model = two_stacked_boxes();
  model["blocks"][1]["id"] = "base";
  const auto issues = issues_of(model);
  EXPECT_TRUE(has_issue(issues, "/blocks/1/id", "duplicate")) << describe(issues);
}

TEST(ModelReaderErrors, DanglingInterfaceReference) {
  json model = two_stacked_boxes();
  model["interfaces"] = {{{"blocks", {"base", "B9"}}, {"polygon", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}}}};
  const auto issues = issues_of(model);
  EXPECT_TRUE(has_issue(issues, "/interfaces/0/blocks/1", "B9")) << describe(issues);
}

TEST(ModelReaderErrors, DanglingLoadReference) {
  json model = two_stacked_boxes();
  model["loads"] = {{"live", {{{"block", "nope"}, {"force", {1, 0, 0}}}}}};
  const auto issues = issues_of(model);
  EXPECT_TRUE(has_issue(issues, "/loads/live/0/block", "nope")) << describe(issues);
}

TEST(ModelReaderErrors, NegativeUnitWeight) {
  json model = two_stacked_boxes();
  model["blocks"][1]["unit_weight"] = -5;
  const auto issues = issues_of(model);
  EXPECT_TRUE(has_issue(issues, "/blocks/1/unit_weight")) << describe(issues);
}

TEST(ModelReaderErrors, InvertedBlockIsNamed) {
  json model = two_stacked_boxes();
  for (auto& face : model["blocks"][1]["faces"]) std::reverse(face.begin(), face.end());
  const auto issues = issues_of(model);
  EXPECT_TRUE(has_issue(issues, "/blocks/1/faces", "'B1' is inverted")) << describe(issues);
}

TEST(ModelReaderErrors, OpenBlockIsNamed) {
  json model = two_stacked_boxes();
  model["blocks"][1]["faces"].erase(5);
  const auto issues = issues_of(model);
  EXPECT_TRUE(has_issue(issues, "/blocks/1/faces", "'B1' is open")) << describe(issues);
}

TEST(ModelReaderErrors, FlatBlockHasZeroVolume) {
  json model = two_stacked_boxes();
  model["blocks"][1] = box_block("B1", 0, 0, 0, 1, 1, 0);
  const auto issues = issues_of(model);
  EXPECT_FALSE(issues.empty()) << describe(issues);
  EXPECT_EQ(issues[0].pointer.rfind("/blocks/1", 0), 0u) << describe(issues);
}

TEST(ModelReaderErrors, ZeroAreaFace) {
  json model = two_stacked_boxes();
  model["blocks"][1]["faces"].push_back({0, 1, 1});
  const auto issues = issues_of(model);
  EXPECT_TRUE(has_issue(issues, "/blocks/1/faces/6", "fewer than 3 distinct")) << describe(issues);
}

TEST(ModelReaderErrors, SeismicDirectionMustBeHorizontal) {
  json model = two_stacked_boxes();
  model["analysis"] = {{"seismic", {{"direction", {1, 0, 0.5}}}}};
  const auto issues = issues_of(model);
  EXPECT_TRUE(has_issue(issues, "/analysis/seismic/direction", "horizontal")) << describe(issues);
}

TEST(ModelReaderErrors, SettlementNeedsMovingSupport) {
  json model = two_stacked_boxes();
  model["analysis"] = {{"type", "settlement"}};
  const auto issues = issues_of(model);
  EXPECT_TRUE(has_issue(issues, "/analysis/type", "moving_support")) << describe(issues);
}

TEST(ModelReaderErrors, NoFreeBlock) {
  json model = two_stacked_boxes();
  model["blocks"][1]["role"] = "fixed";
  EXPECT_TRUE(has_issue(issues_of(model), "/blocks", "nothing to analyse"));
}

TEST(ModelReaderErrors, UnknownProperty) {
  json model = two_stacked_boxes();
  model["blocks"][1]["colour"] = "red";
  const auto issues = issues_of(model);
  // At the property itself, named (valijson reports it at the object, naming it only in words).
  EXPECT_TRUE(has_issue(issues, "/blocks/1/colour", "unknown property")) << describe(issues);
}

TEST(ModelReaderWarnings, CadVolumeAndCentroidDisagreement) {
  json model = two_stacked_boxes();
  model["blocks"][1]["volume"] = 2.5;
  model["blocks"][1]["centroid"] = {0.5, 0.5, 1.2};
  const auto m = load_model_text(model.dump()).model;
  ASSERT_EQ(m.warnings.size(), 2u);
  EXPECT_EQ(m.warnings[0].code, "cad_volume_mismatch");
  EXPECT_EQ(m.warnings[0].pointer, "/blocks/1/volume");
  EXPECT_EQ(m.warnings[1].code, "cad_centroid_mismatch");
  EXPECT_NEAR(m.blocks[1].volume, 2.0, 1e-12);  // the geometry wins
}

TEST(ModelReaderWarnings, CadValuesThatAgreeGiveNoWarning) {
  json model = two_stacked_boxes();
  model["blocks"][1]["volume"] = 2.0000001;
  model["blocks"][1]["centroid"] = {0.5, 0.5, 1.0000001};
  EXPECT_TRUE(load_model_text(model.dump()).model.warnings.empty());
}

TEST(ModelReaderWarnings, IsolatedBlock) {
  json model = two_stacked_boxes();
  model["blocks"].push_back(box_block("floating", 5, 5, 5, 6, 6, 6));
  const auto m = load_model_text(model.dump()).model;
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_EQ(m.warnings[0].code, "isolated_block");
  EXPECT_EQ(m.warnings[0].pointer, "/blocks/2");
}
