// Interface detection on geometry as CAD exports it: tolerances that follow each joint's size,
// warped faces compared by their fitted planes, split faces merged, vertex noise, and the
// near-miss report. Expected counts and polygons come from the construction of each scene.
#include "geometry/interface_detection.hpp"
#include "io/load_model.hpp"
#include "io/result_writer.hpp"
#include "io/schema_validation.hpp"
#include "support/model_builder.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>

using namespace rbla::testing;
using rbla::io::load_model_text;
using rbla::model::Model;
using rbla::model::Vec3;

namespace {

Model load(const json& model) { return load_model_text(model.dump()).model; }

/// A block from its 8 corners: bottom quad p[0..3] (counter-clockwise seen from above) and the
/// top quad p[4..7] above it; faces as box_block writes them.
json hexahedron(const std::string& id, const std::array<std::array<double, 3>, 8>& p, const std::string& role = "free") {
  json vertices = json::array();
  for (const auto& v : p) vertices.push_back({v[0], v[1], v[2]});
  json faces = json::array({{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}});
  return json{{"id", id}, {"vertices", vertices}, {"faces", faces}, {"role", role}};
}

/// Deterministic noise in [-1, 1] (a 64-bit LCG: the same numbers on every platform).
struct Noise {
  std::uint64_t state;
  double next() {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / static_cast<double>(1ULL << 52) * 2.0 - 1.0;
  }
};

void add_noise(json& blocks, double amplitude, std::uint64_t seed) {
  Noise noise{seed};
  for (auto& block : blocks) {
    for (auto& v : block["vertices"]) {
      for (auto& c : v) c = c.get<double>() + amplitude * noise.next();
    }
  }
}

json rotated_about_z(json blocks, double degrees) {
  const double c = std::cos(degrees * M_PI / 180.0), s = std::sin(degrees * M_PI / 180.0);
  for (auto& block : blocks) {
    for (auto& v : block["vertices"]) {
      const double x = v[0].get<double>(), y = v[1].get<double>();
      v[0] = c * x - s * y;
      v[1] = s * x + c * y;
    }
  }
  return blocks;
}

double total_area(const Model& m) {
  double area = 0.0;
  for (const auto& c : m.interfaces) area += c.area;
  return area;
}

}  // namespace

// The distance tolerance of a joint is 3 % of the diameter of its smaller face (the schema's
// default): sqrt(2) m for a 1 m square, so 42.4 mm; 4.24 mm for a 0.1 m square. The same block
// pairs give the same answer whatever else the model holds. The large blocks are tilted onto the
// base (one edge on it): a gap the same all over closes only up to 30 mm (UniformGaps).
TEST(DetectionTolerance, FollowsEachJointNotTheModel) {
  const double large = 0.03 * std::sqrt(2.0), small = 0.1 * large;
  auto tilted = [](const std::string& id, double x0, double lift) {
    json block = box_block(id, x0, 0, 0, x0 + 1, 1, 1);
    block["vertices"][1][2] = block["vertices"][2][2] = lift;  // the x = x0 + 1 edge lifted
    return block;
  };
  for (const bool far_block : {false, true}) {
    json blocks = json::array({box_block("base", -1, -1, -0.5, 6, 2, 0, "fixed"),
                               tilted("big_in", 0, 0.95 * large),
                               tilted("big_out", 2, 1.1 * large),
                               box_block("small_in", 4, 0, 0.95 * small, 4.1, 0.1, 0.1),
                               box_block("small_out", 5, 0, 1.1 * small, 5.1, 0.1, 0.1)});
    // A block 200 m away: a tolerance relative to the model (1e-4 of 200 m = 20 mm) would now
    // accept small_out and refuse big_in.
    if (far_block) blocks.push_back(box_block("far", 200, 0, 0, 201, 1, 1, "fixed"));
    const Model m = load(model_with(blocks));
    std::set<std::string> touching;
    for (const auto& c : m.interfaces) touching.insert(m.blocks[c.block_b].id), touching.insert(m.blocks[c.block_a].id);
    EXPECT_EQ(touching, (std::set<std::string>{"base", "big_in", "small_in"})) << "far block: " << far_block;
    EXPECT_TRUE(m.detection_summary.per_joint);
    // big_in's tilted face is a little larger than the square: its diameter sqrt(2 + lift^2).
    EXPECT_NEAR(m.detection_summary.distance_tolerances.max, 0.03 * std::sqrt(2.0 + std::pow(0.95 * large, 2)), 1e-12);
    EXPECT_NEAR(m.detection_summary.distance_tolerances.min, small, 1e-12);
  }
}

TEST(DetectionTolerance, AFixedToleranceReplacesThePerJointOnes) {
  json model = model_with(json::array({box_block("base", -1, -1, -0.5, 3, 2, 0, "fixed"),
                                       box_block("A", 0, 0, 0.01, 1, 1, 1), box_block("B", 2, 0, 0.03, 2.1, 0.1, 1)}));
  model["detection"] = {{"distance_tolerance", 20.0}};  // mm
  model["units"]["length"] = "mm";
  const Model absolute = load(scaled(model, 1000.0));
  ASSERT_EQ(absolute.interfaces.size(), 1u);  // A (10 mm) only, B is 30 mm up
  EXPECT_FALSE(absolute.detection_summary.per_joint);
  EXPECT_NEAR(absolute.detection_summary.fixed_distance, 0.02, 1e-15);

  model["units"]["length"] = "m";
  model["detection"] = {{"relative_tolerance", 0.01}};  // of a diagonal of sqrt(4^2 + 3^2 + 1.5^2) m
  const Model relative = load(model);
  EXPECT_EQ(relative.interfaces.size(), 2u);
  EXPECT_NEAR(relative.detection_summary.fixed_distance, 0.01 * std::sqrt(16.0 + 9.0 + 2.25), 1e-12);
}

TEST(NearMisses, NameTheBlocksFacesDistanceAndAngle) {
  // A 1 m cube 60 mm above the base (a gap the same all over: 30 mm closes), one 200 mm above
  // (beyond three times the joint's tolerance of 42.4 mm),
  // and a 0.4 x 1 m block tilted by 11 degrees about a bottom edge: beyond the 10 degree angle
  // tolerance, and 78 mm off the base at the other edge (its tolerance: 3 % of sqrt(1.16) m =
  // 32.3 mm).
  const double t = 0.4 * std::tan(11.0 * M_PI / 180.0);
  json blocks = json::array({box_block("base", -1, -1, -0.5, 8, 2, 0, "fixed"), box_block("gap", 0, 0, 0.06, 1, 1, 1),
                             box_block("far", 2, 0, 0.2, 3, 1, 1),
                             hexahedron("tilted", {{{4, 0, 0}, {4.4, 0, t}, {4.4, 1, t}, {4, 1, 0},
                                                    {4, 0, 1}, {4.4, 0, 1 + t}, {4.4, 1, 1 + t}, {4, 1, 1}}})});
  const Model m = load(model_with(blocks));
  EXPECT_TRUE(m.interfaces.empty());
  ASSERT_EQ(m.near_misses.size(), 2u);
  EXPECT_EQ(m.detection_summary.near_misses_total, 2u);
  const auto& gap = m.near_misses[0];  // 1.41 times its tolerance, before 12/10
  EXPECT_EQ(m.blocks[gap.block_a].id, "base");
  EXPECT_EQ(m.blocks[gap.block_b].id, "gap");
  EXPECT_EQ(gap.face_a, 1);  // the base's top
  EXPECT_EQ(gap.face_b, 0);  // the cube's bottom
  EXPECT_NEAR(gap.distance, 0.06, 1e-12);
  EXPECT_NEAR(gap.distance_tolerance, 0.03, 1e-12);  // the limit of a gap the same all over
  EXPECT_NEAR(gap.angle_degrees, 0.0, 1e-9);
  EXPECT_NEAR(gap.overlap_area, 1.0, 1e-12);
  const auto& tilted = m.near_misses[1];
  EXPECT_EQ(m.blocks[tilted.block_b].id, "tilted");
  EXPECT_NEAR(tilted.angle_degrees, 11.0, 1e-9);
  // Measured along the mid-plane's normal, 5.5 degrees from either face's: the far edge, at
  // s = 0.4 cos(5.5)/cos(11) from the hinge in the mid-plane, is 2 s tan(5.5) apart.
  EXPECT_NEAR(tilted.distance, 0.8 * std::sin(5.5 * M_PI / 180.0) / std::cos(11.0 * M_PI / 180.0), 1e-9);

  json bounded = model_with(blocks);
  bounded["detection"] = {{"max_near_misses", 1}};
  const Model one = load(bounded);
  ASSERT_EQ(one.near_misses.size(), 1u);
  EXPECT_EQ(one.blocks[one.near_misses[0].block_b].id, "gap");
  EXPECT_EQ(one.detection_summary.near_misses_total, 2u);
}

TEST(NearMisses, AreInTheResultJsonInTheModelsUnits) {
  // The near-miss scene in millimetres: a 1000 mm cube 60 mm above its base.
  json model = scaled(model_with(json::array({box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"),
                                              box_block("gap", 0, 0, 0.06, 1, 1, 1), box_block("on", 1.5, 0, 0, 1.9, 1, 1)})),
                      1000.0);
  model["units"]["length"] = "mm";
  const Model m = load(model);
  const json result = rbla::io::model_only_result(m, {}, "");
  const auto issues = rbla::io::validate_against_schema(result, rbla::io::SchemaKind::Result);
  EXPECT_TRUE(issues.empty()) << issues.front().pointer << ": " << issues.front().message;
  const json& d = result["detection"];
  EXPECT_EQ(d["tolerances"]["rule"], "per_joint");
  EXPECT_DOUBLE_EQ(d["tolerances"]["joint_tolerance"].get<double>(), 0.03);
  EXPECT_EQ(d["num_interfaces"], 1);
  EXPECT_EQ(d["num_near_misses"], 1);
  ASSERT_EQ(d["near_misses"].size(), 1u);
  const json& miss = d["near_misses"][0];
  EXPECT_EQ(miss["blocks"], json::array({"base", "gap"}));
  EXPECT_EQ(miss["faces"], json::array({1, 0}));
  EXPECT_NEAR(miss["distance"].get<double>(), 60.0, 1e-9);
  EXPECT_NEAR(miss["distance_tolerance"].get<double>(), 30.0, 1e-9);  // a gap the same all over
  EXPECT_NEAR(miss["overlap_area"].get<double>(), 1e6, 1e-3);
  // The block "on" is 0.4 x 1 m at its base: its joint's tolerance is 3 % of sqrt(1.16) m.
  EXPECT_NEAR(d["tolerances"]["distance_used"]["max"].get<double>(), 30.0 * std::sqrt(1.16), 1e-9);
}

TEST(WarpedFaces, AJointWarpedByCentimetresIsOneInterfaceOnItsFittedPlane) {
  // Two blocks share the vertical joint x = 1, whose corner (1, 1, 1) is pushed 25 mm along x:
  // a warped quad (its corners are 6.25 mm from their best plane). Block B then splits the joint
  // along the other diagonal than A's fan would, as a mesh export does.
  const double w = 0.025;
  json a = hexahedron("A", {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1 + w, 1, 1}, {0, 1, 1}}});
  json b = hexahedron("B", {{{1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 0, 1}, {2, 0, 1}, {2, 1, 1}, {1 + w, 1, 1}}});
  b["faces"][5] = json::array({3, 0, 4});  // face [3, 0, 4, 7] split along 3-4
  b["faces"].push_back({3, 4, 7});
  const Model m = load(model_with(json::array({box_block("base", -1, -1, -0.5, 3, 2, 0, "fixed"), a, b})));
  ASSERT_EQ(m.interfaces.size(), 3u);  // A and B on the base, A-B
  const auto* joint = &m.interfaces[0];
  for (const auto& c : m.interfaces) {
    if (m.blocks[c.block_a].id != "base" && m.blocks[c.block_b].id != "base") joint = &c;
  }
  EXPECT_EQ(joint->polygon.size(), 4u);
  // Projected on the plane normal to its Newell area vector, a warped quad covers the length of
  // that vector: its projections on the coordinate planes have areas 1, w/2 and w/2.
  EXPECT_NEAR(joint->area, std::sqrt(1.0 + w * w / 2.0), 1e-9);
  EXPECT_EQ(m.detection_summary.merged_faces, 1u);
  EXPECT_LT(m.detection_summary.gaps.max, 1e-12);  // both fit the same four corners
  int warned = 0;
  for (const auto& w : m.warnings) warned += w.code == "non_planar_face";
  EXPECT_EQ(warned, 1);
}

TEST(SplitFaces, ACapSplitIntoTrianglesGivesOneInterfaceWithFourCorners) {
  // The bottom of a 1 m cube as four triangles around a centre vertex, and as two quads: both
  // are the same square to the base.
  for (const bool triangles : {true, false}) {
    json cube = box_block("B", 0, 0, 0, 1, 1, 1);
    cube["vertices"].push_back({0.5, 0.5, 0.0});  // 8: centre of the bottom
    cube["vertices"].push_back({0.5, 0.0, 0.0});  // 9: midpoint of edge 0-1
    cube["vertices"].push_back({0.5, 1.0, 0.0});  // 10: midpoint of edge 2-3
    if (triangles) {
      cube["faces"][0] = json::array({0, 3, 8});
      for (const json& f : {json{3, 2, 8}, json{2, 1, 8}, json{1, 0, 8}}) cube["faces"].push_back(f);
    } else {  // the front and back faces then carry the midpoints too (no T-junction)
      cube["faces"][0] = json::array({0, 3, 10, 9});
      cube["faces"].push_back({9, 10, 2, 1});
      cube["faces"][2] = json::array({0, 9, 1, 5, 4});
      cube["faces"][4] = json::array({2, 10, 3, 7, 6});
    }
    const Model m = load(model_with(json::array({box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"), cube})));
    ASSERT_EQ(m.interfaces.size(), 1u) << "triangles " << triangles;
    EXPECT_NEAR(m.interfaces[0].area, 1.0, 1e-12);
    EXPECT_EQ(m.interfaces[0].polygon.size(), 4u);
    EXPECT_EQ(m.detection_summary.merged_faces, triangles ? 3u : 1u);
  }
}

TEST(SplitFaces, FacetsOfACurveAreNotMergedAndEachFindsItsPartner) {
  // A block whose bottom is two facets meeting at 4 degrees (a polygonal arch's extrados) rests
  // on two blocks cut to match each facet exactly: two interfaces with zero gap, whatever the
  // merging of nearly coplanar faces does.
  const double s = std::tan(4.0 * M_PI / 180.0);
  json top = json{{"id", "T"},
                  {"vertices", {{0, 0, 1}, {1, 0, 1}, {2, 0, 1 + s}, {2, 1, 1 + s}, {1, 1, 1}, {0, 1, 1},
                                {0, 0, 2}, {2, 0, 2}, {2, 1, 2}, {0, 1, 2}}},
                  {"faces", {{0, 5, 4, 1}, {1, 4, 3, 2}, {6, 7, 8, 9}, {0, 1, 2, 7, 6}, {3, 4, 5, 9, 8}, {5, 0, 6, 9},
                             {2, 3, 8, 7}}}};
  json right = hexahedron("R", {{{1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 0, 1}, {2, 0, 1 + s}, {2, 1, 1 + s}, {1, 1, 1}}});
  const Model m = load(model_with(json::array({box_block("base", -1, -1, -0.5, 3, 2, 0, "fixed"),
                                               box_block("L", 0, 0, 0, 1, 1, 1), right, top})));
  int on_top = 0;
  for (const auto& c : m.interfaces) {
    if (m.blocks[c.block_a].id == "T" || m.blocks[c.block_b].id == "T") {
      ++on_top;
      EXPECT_NEAR(c.area, m.blocks[c.block_a].id == "L" || m.blocks[c.block_b].id == "L" ? 1.0 : 1.0 / std::cos(4.0 * M_PI / 180.0),
                  1e-9);
    }
  }
  EXPECT_EQ(on_top, 2);
  EXPECT_EQ(m.detection_summary.merged_faces, 0u);
  EXPECT_LT(m.detection_summary.gaps.max, 1e-12);
}

// The issue's façade: +-0.5 mm of independent noise on every vertex tilts each brick's faces by
// about 0.1 degree; measured from a brick, the centroid of a 12 m base face is then centimetres
// off its plane, and a detector that compares centroids loses bed joints on the ground.
TEST(NoisyExports, EveryJointOfANoisyRunningBondWallIsFound) {
  const json clean_blocks = running_bond_blocks(30, 8);
  const Model clean = load(model_with(clean_blocks));
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    json noisy = clean_blocks;
    add_noise(noisy, 0.0005, seed);
    const Model m = load(model_with(noisy));
    EXPECT_EQ(m.interfaces.size(), clean.interfaces.size()) << "seed " << seed;
    EXPECT_EQ(m.num_contact_points(), clean.num_contact_points()) << "seed " << seed;
    EXPECT_NEAR(total_area(m), total_area(clean), 2e-3 * total_area(clean));
    EXPECT_LT(m.detection_summary.gaps.max, 0.0025);  // two noisy corners and a tilt
    EXPECT_TRUE(m.near_misses.empty());
  }
}

TEST(NoisyExports, RotatedAndInMillimetresTheWallHasTheSameJoints) {
  const json blocks = running_bond_blocks(12, 6);
  const Model clean = load(model_with(blocks));
  json other = scaled(model_with(rotated_about_z(blocks, 37.0)), 1000.0);
  other["units"]["length"] = "mm";
  const Model m = load(other);
  EXPECT_EQ(m.interfaces.size(), clean.interfaces.size());
  EXPECT_EQ(m.num_contact_points(), clean.num_contact_points());
  EXPECT_NEAR(total_area(m), total_area(clean), 1e-9 * total_area(clean));
}

TEST(WarpedFaces, HundredsOfWarpedFacesGiveOneWarning) {
  // 400 blocks, each with a top corner raised by 20 to 40 mm (the top face warped by a quarter of
  // that; the sides keep the corner in their planes): one aggregated warning naming the count and
  // the worst face, not one line per face.
  json blocks = json::array({box_block("base", -1, -1, -0.5, 21, 21, 0, "fixed")});
  for (int i = 0; i < 20; ++i) {
    for (int j = 0; j < 20; ++j) {
      json b = box_block("b" + std::to_string(i) + "_" + std::to_string(j), i, j, 0, i + 1, j + 1, 1);
      b["vertices"][6][2] = 1.02 + 0.02 * ((i * 20 + j) % 7) / 6.0;
      blocks.push_back(b);
    }
  }
  const Model m = load(model_with(blocks));
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_EQ(m.warnings[0].code, "non_planar_face");
  EXPECT_NE(m.warnings[0].message.find("400 faces"), std::string::npos) << m.warnings[0].message;
  EXPECT_NE(m.warnings[0].message.find("within the joint tolerance"), std::string::npos);
}

// The detection defaults against the schema: tests/unit/test_schema_defaults.cpp.

TEST(GivenInterfaces, TheNormalComesFromTheFaceTheContactLiesOn) {
  // B rests on the low step of an L-shaped A whose centroid (z = 1.65) is above B's (0.75): the
  // direction between the centroids points down, but the contact is A's top face of the step and
  // its normal from A into B is +z.
  const json a{{"id", "A"}, {"role", "fixed"},
               {"vertices", {{0, 0, 0}, {3, 0, 0}, {3, 0, 0.5}, {1, 0, 0.5}, {1, 0, 4}, {0, 0, 4},
                             {0, 1, 0}, {3, 1, 0}, {3, 1, 0.5}, {1, 1, 0.5}, {1, 1, 4}, {0, 1, 4}}},
               {"faces", {{0, 1, 2, 3, 4, 5}, {6, 11, 10, 9, 8, 7}, {0, 6, 7, 1}, {1, 7, 8, 2},
                          {2, 8, 9, 3}, {3, 9, 10, 4}, {4, 10, 11, 5}, {5, 11, 6, 0}}}};
  json model = model_with(json::array({a, box_block("B", 2, 0, 0.5, 3, 1, 1.0)}));
  model["interfaces"] = {{{"id", "step"}, {"blocks", {"A", "B"}},
                          {"polygon", {{2, 0, 0.5}, {3, 0, 0.5}, {3, 1, 0.5}, {2, 1, 0.5}}}}};
  const Model m = load(model);
  ASSERT_EQ(m.interfaces.size(), 1u);
  EXPECT_NEAR((m.interfaces[0].normal - Vec3::UnitZ()).norm(), 0.0, 1e-12);
  EXPECT_GT(m.blocks[0].centroid.z(), m.blocks[1].centroid.z());
}
