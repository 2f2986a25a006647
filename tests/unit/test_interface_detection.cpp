// Interface detection against hand-computed contact polygons.
#include "geometry/interface_detection.hpp"
#include "io/load_model.hpp"
#include "support/model_builder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>

using namespace rbla::testing;
using rbla::io::load_model_text;
using rbla::model::ContactInterface;
using rbla::model::Model;
using rbla::model::Vec3;

namespace {

Model load(const json& model) { return load_model_text(model.dump()).model; }

double total_area(const Model& m) {
  double area = 0.0;
  for (const auto& c : m.interfaces) area += c.area;
  return area;
}

/// Contact points of all interfaces, sorted, for comparisons that ignore order.
std::vector<std::array<double, 3>> sorted_points(const Model& m, double scale = 1.0) {
  std::vector<std::array<double, 3>> points;
  for (const auto& c : m.interfaces) {
    for (const auto& p : c.polygon) points.push_back({p.x() * scale, p.y() * scale, p.z() * scale});
  }
  for (auto& p : points) {
    for (double& x : p) x = std::round(x * 1e9) / 1e9;
  }
  std::sort(points.begin(), points.end());
  return points;
}

}  // namespace

TEST(LocalFrame, RightHandedAndAxisAligned) {
  for (const Vec3& n : {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(1, 2, 3).normalized()}) {
    Vec3 t1, t2;
    rbla::geometry::local_frame(n, t1, t2);
    EXPECT_NEAR(t1.norm(), 1.0, 1e-15);
    EXPECT_NEAR(t1.dot(n), 0.0, 1e-15);
    EXPECT_NEAR((n.cross(t1) - t2).norm(), 0.0, 1e-15);
  }
  Vec3 t1, t2;
  rbla::geometry::local_frame(Vec3::UnitZ(), t1, t2);
  EXPECT_EQ(t1, Vec3::UnitX());
  EXPECT_EQ(t2, Vec3::UnitY());
}

TEST(InterfaceDetection, StackedBoxes) {
  const Model m = load(model_with(json::array({box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"),
                                               box_block("B1", 0, 0, 0, 1, 1, 1), box_block("B2", 0, 0, 1, 1, 1, 2)})));
  ASSERT_EQ(m.interfaces.size(), 2u);
  for (const ContactInterface& c : m.interfaces) {
    EXPECT_EQ(c.polygon.size(), 4u);
    EXPECT_NEAR(c.area, 1.0, 1e-12);
    EXPECT_TRUE(c.detected);
    // The normal points from block_a into block_b.
    EXPECT_GT(c.normal.dot(m.blocks[c.block_b].centroid - m.blocks[c.block_a].centroid), 0.0);
    EXPECT_NEAR(std::abs(c.normal.z()), 1.0, 1e-12);
    EXPECT_NEAR((c.centroid - Vec3(0.5, 0.5, c.centroid.z())).norm(), 0.0, 1e-12);
    EXPECT_DOUBLE_EQ(c.friction, 0.6);
  }
}

/// `block` written as an export writes a triangle soup: each face split into triangles, each
/// triangle with copies of its own corners, rounded apart by up to `jitter` (deterministic).
json triangle_soup(json block, double jitter) {
  json vertices = json::array(), faces = json::array();
  int k = 0;
  for (const auto& face : block["faces"]) {
    for (std::size_t i = 1; i + 1 < face.size(); ++i) {
      json triangle = json::array();
      for (const auto& corner : {face[0], face[i], face[i + 1]}) {
        json v = block["vertices"][corner.get<int>()];
        for (auto& x : v) x = x.get<double>() + jitter * std::sin(12.9898 * ++k);  // any order of rounding
        triangle.push_back(vertices.size());
        vertices.push_back(v);
      }
      faces.push_back(triangle);
    }
  }
  block["vertices"] = vertices;
  block["faces"] = faces;
  return block;
}

// Copies of a corner rounded apart by 1e-9 of the block were welded only when their x order
// matched their index order, and the split faces then stayed split: two stacked boxes gave
// several small interfaces instead of one square.
TEST(InterfaceDetection, ATriangleSoupRoundedApartGivesTheSameInterfaces) {
  const Model exact = load(model_with(json::array({box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"),
                                                   box_block("B1", 0, 0, 0, 1, 1, 1), box_block("B2", 0, 0, 1, 1, 1, 2)})));
  for (const double jitter : {0.0, 1e-9, 1e-7}) {
    SCOPED_TRACE(jitter);
    const Model soup = load(model_with(json::array({triangle_soup(box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"), jitter),
                                                    triangle_soup(box_block("B1", 0, 0, 0, 1, 1, 1), jitter),
                                                    triangle_soup(box_block("B2", 0, 0, 1, 1, 1, 2), jitter)})));
    ASSERT_EQ(soup.interfaces.size(), exact.interfaces.size());
    for (const ContactInterface& c : soup.interfaces) EXPECT_EQ(c.polygon.size(), 4u);
    EXPECT_NEAR(total_area(soup), total_area(exact), 1e-6);
  }
}

// A block drawn clear of two walls on its sides: glued to them it is clamped and carries any
// horizontal load, so a gap above half the joint tolerance (3 % of the block's 0.6 x 1 m side
// face: 35 mm) is said, with the widest; a millimetre of CAD gap is not. The walls lean away from
// the block, touching it at its foot and 25 mm clear at its top: walls parallel to it and clear of
// it all the way up are held apart by the 30 mm clearance limit (Clearance tests).
TEST(InterfaceDetection, AJointClosedAcrossAWideGapIsSaid) {
  auto channel = [](double gap) {
    json left = box_block("wall_left", -1, -1, 0, 2, 0, 2, "fixed");
    json right = box_block("wall_right", -1, 1, 0, 2, 2, 2, "fixed");
    for (int v : {4, 5, 6, 7}) {  // the top vertices, 2 m up: twice the gap at the block's top
      left["vertices"][v][1] = left["vertices"][v][1].get<double>() - 2.0 * gap;
      right["vertices"][v][1] = right["vertices"][v][1].get<double>() + 2.0 * gap;
    }
    return load(model_with(json::array({box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"), std::move(left),
                                        std::move(right), box_block("B", 0, 0, 0, 0.6, 1, 1)})));
  };
  auto wide_gap_warning = [](const Model& m) {
    return std::find_if(m.warnings.begin(), m.warnings.end(),
                        [](const auto& w) { return w.code == "joints_closed_across_gaps"; });
  };
  const Model wide = channel(0.025);
  ASSERT_EQ(wide.interfaces.size(), 3u) << "the bed joint and both side joints";
  const auto said = wide_gap_warning(wide);
  ASSERT_NE(said, wide.warnings.end());
  EXPECT_NE(said->message.find("2 detected joints"), std::string::npos) << said->message;
  EXPECT_NEAR(said->magnitude, 0.025, 1e-4);  // measured along the joint's mid-plane normal
  EXPECT_EQ(wide.detection_summary.wide_gaps.joints, 2u);
  const Model narrow = channel(0.001);
  EXPECT_EQ(narrow.interfaces.size(), 3u);
  EXPECT_EQ(wide_gap_warning(narrow), narrow.warnings.end());
}

TEST(InterfaceDetection, RunningBondOverlap) {
  // One block resting on two half-offset blocks: two interfaces of area 0.5 each, plus the head
  // joint between the two lower blocks and their two base contacts.
  const Model m = load(model_with(json::array({box_block("base", -1, -1, -1, 3, 2, 0, "fixed"),
                                               box_block("L", 0, 0, 0, 1, 1, 1), box_block("R", 1, 0, 0, 2, 1, 1),
                                               box_block("T", 0.5, 0, 1, 1.5, 1, 2)})));
  ASSERT_EQ(m.interfaces.size(), 5u);
  int bed_joints_on_top = 0;
  for (const auto& c : m.interfaces) {
    const bool touches_top = m.blocks[c.block_a].id == "T" || m.blocks[c.block_b].id == "T";
    if (touches_top) {
      ++bed_joints_on_top;
      EXPECT_NEAR(c.area, 0.5, 1e-12);
      EXPECT_EQ(c.polygon.size(), 4u);
    }
  }
  EXPECT_EQ(bed_joints_on_top, 2);
  EXPECT_NEAR(total_area(m), 0.5 + 0.5 + 1.0 + 1.0 + 1.0, 1e-12);
  EXPECT_EQ(m.num_contact_points(), 20u);
}

TEST(InterfaceDetection, LShapedFaceOnTwoBlocksGivesClippedPolygons) {
  // An L-shaped prism (outline [0,2]x[0,1] + [0,1]x[1,2]) rests on a 2x2 block: the contact is
  // the L itself (area 3, 6 corners).
  const Model m = load(model_with(json::array(
      {box_block("base", 0, 0, -1, 2, 2, 0, "fixed"),
       prism_block("L", {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, 0, 1)})));
  ASSERT_EQ(m.interfaces.size(), 1u);
  EXPECT_NEAR(m.interfaces[0].area, 3.0, 1e-12);
  EXPECT_EQ(m.interfaces[0].polygon.size(), 6u);
}

TEST(InterfaceDetection, UShapedFaceOverBarGivesTwoInterfaces) {
  // A U outline over a bar crossing both arms: two separate contact components for one pair.
  const Model m = load(model_with(json::array(
      {box_block("bar", -1, 0.5, -1, 4, 1.0, 0, "fixed"),
       prism_block("U", {{0, 0}, {3, 0}, {3, 2}, {2, 2}, {2, 0.25}, {1, 0.25}, {1, 2}, {0, 2}}, 0, 1)})));
  ASSERT_EQ(m.interfaces.size(), 2u);
  EXPECT_NEAR(m.interfaces[0].area, 0.5, 1e-12);
  EXPECT_NEAR(m.interfaces[1].area, 0.5, 1e-12);
}

TEST(InterfaceDetection, NearlyCoplanarInsideAndOutsideTolerance) {
  // Default tolerance: 3 % of the diameter of the smaller face (the 1 m square: sqrt(2) m), 42.4 mm,
  // for a face tilted onto the base (one edge on it, the other `gap` above); a gap the same all
  // over closes up to 30 mm only.
  for (const bool tilted : {false, true}) {
    for (const auto& [gap, uniform, tilt] : {std::tuple{1e-5, 1u, 1u}, std::tuple{0.03, 1u, 1u},
                                             std::tuple{0.031, 0u, 1u}, std::tuple{0.042, 0u, 1u},
                                             std::tuple{0.043, 0u, 0u}, std::tuple{0.1, 0u, 0u}}) {
      json block = box_block("B1", 0, 0, gap, 1, 1, 2);
      if (tilted) block["vertices"][0][2] = block["vertices"][3][2] = 0.0;  // the x = 0 edge on the base
      const Model m = load(model_with(json::array({box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"), block})));
      EXPECT_EQ(m.interfaces.size(), tilted ? tilt : uniform) << "gap " << gap << (tilted ? ", tilted" : "");
    }
  }
}

TEST(InterfaceDetection, ExplicitDistanceToleranceOverridesRelative) {
  json model = model_with(json::array({box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"),
                                       box_block("B1", 0, 0, 0.05, 1, 1, 2)}));
  EXPECT_EQ(load(model).interfaces.size(), 0u);  // 50 mm all over: beyond 30 mm
  model["detection"] = {{"distance_tolerance", 0.06}};
  EXPECT_EQ(load(model).interfaces.size(), 1u);
}

TEST(InterfaceDetection, SlightlyTiltedFaceWithinAngleTolerance) {
  json model = model_with(json::array({box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"), box_block("B1", 0, 0, 0, 1, 1, 2)}));
  // Lift one bottom corner by 1e-5 m: a tilt of about 0.0008 degrees.
  model["blocks"][1]["vertices"][2][2] = 1e-5;
  // The bottom face is then not exactly planar: warn, still detect.
  const Model m = load(model);
  EXPECT_EQ(m.interfaces.size(), 1u);
}

TEST(InterfaceDetection, MillimetresAndMetresGiveTheSameContactPoints) {
  const json metres = model_with(json::array({box_block("base", -1, -1, -1, 3, 2, 0, "fixed"), box_block("L", 0, 0, 0, 1, 1, 1),
                                              box_block("R", 1, 0, 0, 2, 1, 1), box_block("T", 0.5, 0, 1, 1.5, 1, 2)}));
  json millimetres = scaled(metres, 1000.0);
  millimetres["units"]["length"] = "mm";
  const Model a = load(metres);
  const Model b = load(millimetres);
  ASSERT_EQ(a.interfaces.size(), b.interfaces.size());
  EXPECT_EQ(sorted_points(a), sorted_points(b));  // both internally in metres
}

TEST(InterfaceDetection, SupportPairsAreSkipped) {
  const Model m = load(model_with(json::array({box_block("ground", -1, -1, -1, 0, 1, 0, "fixed"),
                                               box_block("settling", 0, -1, -1, 1, 1, 0, "moving_support"),
                                               box_block("B", -0.5, 0, 0, 0.5, 1, 1)})));
  ASSERT_EQ(m.interfaces.size(), 2u);  // B on each support; ground-settling not an interface
  for (const auto& c : m.interfaces) {
    EXPECT_TRUE(m.blocks[c.block_a].id == "B" || m.blocks[c.block_b].id == "B");
    EXPECT_NEAR(c.area, 0.5, 1e-12);
  }
}

TEST(InterfaceDetection, EdgeAndCornerTouchingAreNotInterfaces) {
  const Model m = load(model_with(json::array({box_block("base", -1, -1, -0.5, 3, 3, 0, "fixed"), box_block("A", 0, 0, 0, 1, 1, 1),
                                               box_block("diagonal", 1, 1, 0, 2, 2, 1)})));
  EXPECT_EQ(m.interfaces.size(), 2u);  // each on the base; A and diagonal share only an edge
}

TEST(InterfaceDetection, GivenInterfacesKeepTheirLabels) {
  json model = model_with(json::array({box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"), box_block("B1", 0, 0, 0, 1, 1, 2),
                                       box_block("B2", 0, 0, 2, 1, 1, 3)}));
  model["interfaces"] = {{{"id", "joint-1"},
                          {"label", "bed joint north"},
                          {"blocks", {"B1", "base"}},
                          {"friction", 0.4},
                          {"polygon", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}}}};
  {
    const Model m = load(model);  // interfaces given: detection off by default
    ASSERT_EQ(m.interfaces.size(), 1u);
    const auto& c = m.interfaces[0];
    EXPECT_EQ(c.id, "joint-1");
    EXPECT_EQ(c.label, "bed joint north");
    EXPECT_DOUBLE_EQ(c.friction, 0.4);
    EXPECT_FALSE(c.detected);
    EXPECT_NEAR((c.normal - Vec3(0, 0, -1)).norm(), 0.0, 1e-12);  // from B1 (above) into base
  }
  model["detection"] = {{"mode", "merge"}};
  const Model merged = load(model);
  ASSERT_EQ(merged.interfaces.size(), 2u);  // B1-B2 added; base-B1 kept as labelled
  EXPECT_EQ(merged.interfaces[0].label, "bed joint north");
  EXPECT_TRUE(merged.interfaces[1].detected);
}

TEST(InterfaceDetection, BroadPhaseDoesNotTestAllPairs) {
  // A 20 x 10 grid of blocks: candidate pairs grow with contacts, not with N^2.
  json blocks = json::array({box_block("base", -1, -1, -1, 21, 2, 0, "fixed")});
  for (int row = 0; row < 10; ++row) {
    for (int col = 0; col < 20; ++col) {
      const double shift = (row % 2) * 0.5;
      blocks.push_back(box_block("b" + std::to_string(row) + "_" + std::to_string(col), col + shift, 0, row,
                                 col + shift + 1, 1, row + 1));
    }
  }
  const auto loaded = load_model_text(model_with(blocks).dump());
  const std::size_t n = loaded.model.blocks.size();
  EXPECT_LT(loaded.prepare.detection.candidate_block_pairs, n * 10);
  EXPECT_GT(loaded.model.interfaces.size(), 0u);
}
