// The planar reduction is used only where it is exact (issue 17): on every scene where `auto`
// picks planar, the 3-D formulation gives the same verdict and the same value. The 3-D problem is
// the independent reference here: it drops nothing, so a planar answer that differs from it was
// a reduction the scene did not allow (a block overhanging its support along the axis, loaded in
// the plane, gets "collapse at 0.6" from the planar LP although it cannot stand).
//
// Scenes: the bundled samples, the fast stiff cases (tests/stiff/stiff_cases.hpp: units from mm
// to km, friction 0.01 to 10, weight contrasts, knife edges, stacks, edge of stability, cannot
// stand, no mechanism) and the overhang scenes, each solved associative with the exact cone
// (the pyramids and the non-associative scheme sit on top of the formulation, not in it).
#include "analysis/formulation.hpp"
#include "analysis/limit_analysis.hpp"
#include "io/load_model.hpp"
#include "io/model_reader.hpp"
#include "stiff/stiff_cases.hpp"
#include "support/model_builder.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <set>

namespace {

using nlohmann::json;
using rbla::analysis::Verdict;
namespace fs = std::filesystem;

struct Scene {
  std::string name;
  json model;
};

json cap_with_far_marker();

std::vector<Scene> scenes() {
  std::vector<Scene> out;
  const fs::path dir = fs::path(RBLA_SOURCE_DIR) / "samples";
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "expected.json") continue;
    out.push_back({entry.path().filename().string(), json::parse(rbla::io::read_text(entry.path().string()))});
  }
  for (auto& c : rbla::stiff::stiff_cases()) {
    if (!c.slow && c.expect != rbla::stiff::Expect::TimeLimit) out.push_back({c.name, std::move(c.model)});
  }
  // A block on a slab that ends before the block's centroid along x (it cannot stand), loaded
  // along x (a planar scene along y: the bed joint spans the depth along y) and along y (every
  // block is a box over the same depth along x, but the bed joint covers 0.3 of it: not planar).
  for (const double load_y : {0.0, 1.0}) {
    json model = rbla::testing::model_with(json::array({rbla::testing::box_block("slab", -1, -1, -0.5, 0.3, 2, 0, "fixed"),
                                                        rbla::testing::box_block("B", 0, 0, 0, 1, 1, 1)}));
    model["analysis"] = {{"type", "load_multiplier"}, {"seismic", {{"direction", {1.0 - load_y, load_y, 0.0}}}}};
    out.push_back({"slab_edge_before_centroid_load_" + std::string(load_y > 0 ? "y" : "x"), model});
  }
  out.push_back({"cap_overhanging_its_pier_and_a_far_marker", cap_with_far_marker()});
  return out;
}

/// A cap stone on a pier, overhanging it by 0.3 m along y (its centroid beyond the pier's edge:
/// it cannot stand), loaded along x, and a fixed marker block 3 km away touching nothing (a
/// survey point in a georeferenced export). The marker made the model 4 km across; the extrusion
/// tests then took the overhang for CAD noise and the planar LP reported a collapse at 0.38.
json cap_with_far_marker() {
  using rbla::testing::box_block;
  json model = rbla::testing::model_with(json::array({box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"),
                                                      box_block("pier", 0, 0, 0, 0.5, 0.5, 0.5),
                                                      box_block("cap", 0, 0.3, 0.5, 0.5, 0.8, 0.8),
                                                      box_block("marker", 3000, 3000, 0, 3001, 3001, 1, "fixed")}));
  model["analysis"] = {{"type", "load_multiplier"}, {"seismic", {{"direction", {1.0, 0.0, 0.0}}}}};
  return model;
}

/// The verdict and value of the scene with the formulation forced; analysis settings that do not
/// belong to the formulation are reset to associative, exact cone.
std::pair<Verdict, double> solve(json model, const std::string& formulation) {
  json& a = model["analysis"];
  a["formulation"] = formulation;
  a["friction_model"] = "associative";
  a["cone"] = "exact";
  a.erase("pyramid_bracket");
  const auto loaded = rbla::io::load_model_text(model.dump());
  const auto r = rbla::analysis::analyse(loaded.model);
  const double value = r.load_multiplier ? *r.load_multiplier : r.base_reaction.value_or(0.0);
  return {r.verdict, value};
}

TEST(PlanarAgreement, PlanarEqualsThreeDWhereverAutoPicksPlanar) {
  std::size_t planar = 0, compared = 0;
  std::set<std::string> seen;
  for (const Scene& scene : scenes()) {
    json key = scene.model;
    key["analysis"].erase("formulation");
    key["analysis"].erase("friction_model");
    key["analysis"].erase("cone");
    key["analysis"].erase("pyramid_faces");
    key["analysis"].erase("non_associative");
    if (!seen.insert(key.dump()).second) continue;  // the same scene under other settings
    SCOPED_TRACE(scene.name);
    const auto loaded = rbla::io::load_model_text(scene.model.dump());
    const rbla::analysis::PlanarFrame frame = rbla::analysis::detect_planar(loaded.model);
    if (scene.name == "slab_edge_before_centroid_load_y") {
      EXPECT_FALSE(frame.planar) << "the bed joint does not span the depth along x";
    }
    if (scene.name == "slab_edge_before_centroid_load_x") {
      EXPECT_TRUE(frame.planar) << frame.reason;
    }
    if (!frame.planar) continue;
    ++planar;
    const auto [verdict_2d, value_2d] = solve(scene.model, "planar");
    const auto [verdict_3d, value_3d] = solve(scene.model, "3d");
    EXPECT_STREQ(rbla::analysis::to_string(verdict_2d), rbla::analysis::to_string(verdict_3d));
    if (verdict_2d != Verdict::Collapse || verdict_3d != Verdict::Collapse) continue;
    ++compared;
    // Both solves stop at a relative gap of 1e-8 of max(1, |value|): two orders more, relative,
    // and one absolute (as the stiff cases allow against their closed forms).
    EXPECT_LE(std::abs(value_2d - value_3d), 1e-6 * std::abs(value_3d) + 1e-7)
        << "planar " << value_2d << ", 3-D " << value_3d;
  }
  // The suite must actually compare: the samples and most stiff cases are planar scenes.
  EXPECT_GE(planar, 40u);
  EXPECT_GE(compared, 30u);
  std::cout << "[          ] " << planar << " planar scenes, " << compared << " collapse values compared\n";
}

// The extrusion tests' tolerance is the blocks' scale, not the model's extent: a far block must
// not turn an overhang into CAD noise.
TEST(PlanarAgreement, AFarBlockDoesNotMakeAnOverhangPlanar) {
  const auto loaded = rbla::io::load_model_text(cap_with_far_marker().dump());
  const rbla::analysis::PlanarFrame frame = rbla::analysis::detect_planar(loaded.model);
  EXPECT_FALSE(frame.planar);
  const auto r = rbla::analysis::analyse(loaded.model);
  EXPECT_STREQ(rbla::analysis::to_string(r.verdict), rbla::analysis::to_string(Verdict::CannotStand));
}

// A block that is narrower along y in its upper half (an L in the y-z plane, extruded along x)
// has every face parallel or normal to y and spans y in [0, 1], but it is no prism along y: its
// centroid is off the mid-plane. Planar along y would be wrong; planar along x is excluded by
// the load. So the scene is 3-D.
TEST(PlanarAgreement, BlockSteppedAlongTheAxisIsNotAPrism) {
  // The L outline in (y, z), extruded along x over [0, 1]: (u, v, w) -> (x, y, z) = (w, u, v) is
  // a cyclic permutation, so the faces keep their outward orientation.
  json stepped = rbla::testing::prism_block("L", {{0, 0}, {1, 0}, {1, 1}, {0.5, 1}, {0.5, 2}, {0, 2}}, 0.0, 1.0);
  for (auto& v : stepped["vertices"]) v = json::array({v[2], v[0], v[1]});
  json model = rbla::testing::model_with(json::array({rbla::testing::box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"),
                                                      stepped}));
  model["analysis"] = {{"type", "load_multiplier"}, {"seismic", {{"direction", {1.0, 0.0, 0.0}}}}};
  const auto loaded = rbla::io::load_model_text(model.dump());
  const rbla::analysis::PlanarFrame frame = rbla::analysis::detect_planar(loaded.model);
  EXPECT_FALSE(frame.planar);
  EXPECT_NE(frame.reason.find("block 'L' is not a prism along y (a vertex lies between its end faces)"),
            std::string::npos)
      << frame.reason;
}

}  // namespace
