// The structure's extent, which the default distance tolerance (1e-4 of its diagonal) follows. A
// block far from the rest (a survey marker or a terrain tile of a georeferenced export) made the
// tolerance that of a model kilometres across: a vault's warped faces and small overlaps went
// unreported with a marker 3 km away (the invariance review). The expectations come from the
// geometry as built, not from an earlier run: the vault's own bounding box, and the warnings the
// same vault gets without the marker.
#include "io/load_model.hpp"
#include "support/model_builder.hpp"
#include "support/vault_builder.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>

using namespace rbla::testing;

namespace {

json vault_with_marker(const VaultSpec& spec, double distance) {
  json model = vault_model(spec);
  model["blocks"].push_back(box_block("marker", distance, distance, 0, distance + 1, distance + 1, 1, "fixed"));
  return model;
}

std::map<std::string, std::string> warnings_by_code(const rbla::model::Model& m) {
  std::map<std::string, std::string> out;
  for (const auto& w : m.warnings) out[w.code] += w.message + "\n";
  return out;
}

void expect_same_box(const rbla::model::BoundingBox& a, const rbla::model::BoundingBox& b) {
  EXPECT_EQ(a.min, b.min);
  EXPECT_EQ(a.max, b.max);
}

}  // namespace

// A connected structure keeps its whole bounding box: the default tolerance of every model
// without a wide gap is what it was.
TEST(StructureBox, AConnectedStructureIsItsBoundingBox) {
  VaultSpec spec;
  spec.units = 3;
  const rbla::model::Model m = rbla::io::load_model_text(vault_model(spec).dump()).model;
  expect_same_box(m.structure_box(), m.bounding_box());
}

// Likewise every bundled sample: none has a gap of ten blocks, so none changes its tolerance.
TEST(StructureBox, EverySampleIsItsBoundingBox) {
  const std::filesystem::path samples = std::filesystem::path(RBLA_SOURCE_DIR) / "samples";
  int checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(samples)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".json" || name == "expected.json") continue;
    const rbla::model::Model m = rbla::io::load_model_file(entry.path().string()).model;
    expect_same_box(m.structure_box(), m.bounding_box());
    ++checked;
  }
  EXPECT_GE(checked, 5);
}

// A marker kilometres away, along two axes or along one only, leaves the box and the tolerance
// as without it; the bounding box still has it.
TEST(StructureBox, AFarMarkerLeavesTheToleranceAsWithoutIt) {
  VaultSpec spec;
  spec.units = 3;
  const rbla::model::Model alone = rbla::io::load_model_text(vault_model(spec).dump()).model;
  for (const double distance : {100.0, 3000.0, 1e5}) {
    const rbla::model::Model m = rbla::io::load_model_text(vault_with_marker(spec, distance).dump()).model;
    EXPECT_GT(m.bounding_box().diagonal(), distance);
    expect_same_box(m.structure_box(), alone.structure_box());
    EXPECT_EQ(m.distance_tolerance(), alone.distance_tolerance()) << distance;
  }
  json along_x = vault_model(spec);
  along_x["blocks"].push_back(box_block("marker", 3000, 0, 0, 3001, 1, 1, "fixed"));
  const rbla::model::Model m = rbla::io::load_model_text(along_x.dump()).model;
  EXPECT_EQ(m.distance_tolerance(), alone.distance_tolerance());
}

// What the tolerance is for: a vault whose vertices moved by up to 3 mm (warps well under 1 % of
// a voussoir) gets the same warnings about its own geometry with the marker 3 km away as without.
TEST(StructureBox, AFarMarkerDoesNotSilenceWarpWarnings) {
  VaultSpec spec;
  spec.units = 3;
  spec.noise = 3e-3;
  const auto alone = warnings_by_code(rbla::io::load_model_text(vault_model(spec).dump()).model);
  const auto with_marker = warnings_by_code(rbla::io::load_model_text(vault_with_marker(spec, 3000).dump()).model);
  ASSERT_TRUE(alone.count("non_planar_face")) << "the noise should warp faces";
  for (const auto& [code, messages] : alone) {
    ASSERT_TRUE(with_marker.count(code)) << code;
    EXPECT_EQ(with_marker.at(code), messages) << code;
  }
}

// Two groups of similar size: the box is that of the group with more blocks along the axis that
// separates them, so the tolerance stays that of one building, not of the site.
TEST(StructureBox, TwoBuildingsFarApartTakeTheLarger) {
  json blocks = json::array();
  for (int i = 0; i < 5; ++i) blocks.push_back(box_block("a" + std::to_string(i), i, 0, 0, i + 1, 1, 1, i == 0 ? "fixed" : "free"));
  for (int i = 0; i < 3; ++i) {
    blocks.push_back(box_block("b" + std::to_string(i), 500 + i, 0, 0, 501 + i, 1, 1, i == 0 ? "fixed" : "free"));
  }
  const rbla::model::Model m = rbla::io::load_model_text(model_with(blocks).dump()).model;
  const rbla::model::BoundingBox box = m.structure_box();
  EXPECT_EQ(box.min.x(), 0.0);
  EXPECT_EQ(box.max.x(), 5.0);
  EXPECT_EQ(box.max.y(), 1.0);
}
