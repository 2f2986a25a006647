// Interfaces the CAD gives must lie on a face of each of their two blocks (issue 19): one whose
// polygon lay 1 m from the blocks it names turned a block resting on its base into "cannot
// stand", and the interface was never named.
#include "analysis/limit_analysis.hpp"
#include "io/load_model.hpp"
#include "model/errors.hpp"
#include "support/load_error.hpp"
#include "support/model_builder.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>

using namespace rbla::testing;

namespace {

/// A 1 x 1 x 2 block on a base, its bed joint given as `polygon` (detection off).
json block_with_bed(const json& polygon, const std::string& unit = "m") {
  json model = model_with(json::array({box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"), box_block("B", 0, 0, 0, 1, 1, 2)}), unit);
  model["interfaces"] = json::array({{{"id", "bed"}, {"blocks", {"base", "B"}}, {"polygon", polygon}}});
  model["detection"] = {{"mode", "off"}};
  model["analysis"] = {{"type", "load_multiplier"}, {"seismic", {{"direction", {1, 0, 0}}}}};
  return model;
}

const json kBed = json::array({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});

}  // namespace

TEST(GivenInterfaces, OnBothBlocksTheyAreAcceptedAndGiveTheClosedForm) {
  EXPECT_EQ(load_error(block_with_bed(kBed)), "");
  const auto loaded = rbla::io::load_model_text(block_with_bed(kBed).dump());
  const auto result = rbla::analysis::analyse(loaded.model);
  ASSERT_TRUE(result.load_multiplier.has_value()) << result.verdict_text;
  EXPECT_NEAR(*result.load_multiplier, 0.5, 1e-7);  // [block] min(b/h, mu) = min(0.5, 0.6)
}

// The case: the bed joint's polygon 1 m above the base, in the middle of the block.
TEST(GivenInterfaces, APolygonAwayFromItsBlocksIsRefusedNamingItAndTheDistance) {
  json lifted = kBed;
  for (auto& p : lifted) p[2] = 1.0;
  const std::string error = load_error(block_with_bed(lifted));
  EXPECT_NE(error.find("/interfaces/0/polygon: interface 'bed' does not lie on block 'base': its corner 0 is 1 m from "
                       "the block's nearest face"),
            std::string::npos)
      << error;
  // Its centroid is inside B, half a metre from B's faces.
  EXPECT_NE(error.find("interface 'bed' does not lie on block 'B': its centroid is 0.5 m"), std::string::npos) << error;
  // Moved sideways off both blocks: corner 1, at x = 4, is 3 m from B.
  json aside = kBed;
  for (auto& p : aside) p[0] = p[0].get<double>() + 3.0;
  const std::string off = load_error(block_with_bed(aside));
  EXPECT_NE(off.find("interface 'bed' does not lie on block 'B': its corner 1 is 3 m"), std::string::npos) << off;
}

// A polygon across the block from edge to edge (a diagonal plane): its corners lie on the
// block's edges, its centroid inside, 0.35 m from the nearest face.
TEST(GivenInterfaces, APolygonAcrossABlockIsCaughtByItsCentroid) {
  json model = model_with(json::array({box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"), box_block("B", 0, 0, 0, 1, 1, 2),
                                       box_block("C", 0, 0, 2, 1, 1, 3)}));
  model["interfaces"] = json::array({{{"id", "diag"}, {"blocks", {"B", "C"}}, {"polygon", {{0, 0, 2}, {1, 0, 2}, {1, 1, 1}, {0, 1, 1}}}}});
  model["detection"] = {{"mode", "off"}};
  const std::string error = load_error(model);
  EXPECT_NE(error.find("interface 'diag' does not lie on block 'B': its centroid is 0.5 m"), std::string::npos) << error;
}

// Real exports are off by rounding: corners moved by up to a tenth of the tolerance at random,
// a millimetre model, and an interface on a face of a non-convex block are accepted.
TEST(GivenInterfaces, CadNoiseMillimetresAndNonConvexFacesAreAccepted) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> noise(-1.0, 1.0);
  const double tolerance = 1e-4 * std::sqrt(3.0 * 3.0 + 3.0 * 3.0 + 2.5 * 2.5);  // relative default
  json noisy = kBed;
  for (auto& p : noisy) {
    for (auto& c : p) c = c.get<double>() + 0.1 * tolerance * noise(random);
  }
  EXPECT_EQ(load_error(block_with_bed(noisy)), "");

  json mm = scaled(block_with_bed(kBed), 1000.0);
  for (auto& p : mm["interfaces"][0]["polygon"]) {
    for (auto& c : p) c = 1000.0 * c.get<double>();
  }
  mm["units"]["length"] = "mm";
  EXPECT_EQ(load_error(mm), "");

  // An L-shaped prism and a box in its notch, the given contact on the L's inner face x = 1.
  json l_model = model_with(json::array({box_block("base", -1, -1, -0.5, 3, 3, 0, "fixed"),
                                         prism_block("L", {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, 0, 1),
                                         box_block("N", 1, 1, 0, 2, 2, 1)}));
  l_model["interfaces"] = json::array({{{"id", "inner"}, {"blocks", {"L", "N"}}, {"polygon", {{1, 1, 0}, {1, 2, 0}, {1, 2, 1}, {1, 1, 1}}}}});
  l_model["detection"] = {{"mode", "merge"}};
  EXPECT_EQ(load_error(l_model), "");
}
