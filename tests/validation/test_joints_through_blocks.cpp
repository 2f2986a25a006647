// A joint is not formed through a third block. Detection accepts two faces as touching across a
// gap within the joint tolerance; a thin block lying in that gap and touching both (a shim, a damp
// proof course drawn as its own block) holds them apart, and a joint through it would carry the
// load through its volume. Closed form: a 1 x 1 x 2 block on a shim 0.7 wide and t thick, on a
// fixed base, under a horizontal load: block and shim tip together about the shim's far edge,
//   alpha = (W_C 0.2 + W_S 0.35) / (W_C (1 + t) + W_S t / 2),  W_C = 2 gamma, W_S = 0.7 t gamma
// (0.199614 at t = 5 mm). With the joint through the shim the block stood on its whole base and
// alpha was 0.4988.
#include "validation_helpers.hpp"

#include "model/angles.hpp"

#include <cmath>
#include <cstdlib>
#include <string>

namespace rbla::validation {
namespace {

json shimmed_block(double t) {
  Case s;
  s.mu = 0.6;
  return finish(json::array({box_block("base", -0.5, -0.5, -0.5, 1.5, 1.5, 0.0, "fixed"),
                             box_block("shim", 0.0, 0.0, 0.0, 0.7, 1.0, t),
                             box_block("block", 0.0, 0.0, t, 1.0, 1.0, t + 2.0)}),
                s);
}

bool has_warning(const std::vector<model::Warning>& warnings, const std::string& code) {
  for (const model::Warning& w : warnings) {
    if (w.code == code) return true;
  }
  return false;
}

TEST(JointsThroughBlocks, ABlockOnAShimTipsAboutTheShimsEdge) {
  for (const double t : {0.001, 0.005, 0.02}) {
    SCOPED_TRACE(t);
    const auto loaded = rbla::io::load_model_text(shimmed_block(t).dump());
    for (const model::ContactInterface& c : loaded.model.interfaces) {
      EXPECT_FALSE(std::minmax(c.block_a, c.block_b) == std::minmax(0, 2)) << "a joint between the base and the block";
    }
    EXPECT_TRUE(has_warning(loaded.model.warnings, "joints_through_blocks"));
    const AnalysisResult r = rbla::analysis::analyse(loaded.model);
    const double wc = 2.0, ws = 0.7 * t;
    const double expected = (wc * 0.2 + ws * 0.35) / (wc * (1.0 + t) + ws * t / 2.0);
    EXPECT_LT(relative_error(alpha_of(r), expected), 1e-6) << alpha_of(r) << " against " << expected;
  }
}

// The filter needs a block between the two faces, not beside them: a block across two supports
// of the same height keeps both joints (and carries alpha = 0.5 b / h about the far support's edge).
TEST(JointsThroughBlocks, ABlockAcrossTwoSupportsKeepsBothJoints) {
  Case s;
  const json model = finish(json::array({box_block("left", 0.0, 0.0, -0.5, 0.5, 1.0, 0.0, "fixed"),
                                         box_block("right", 0.5, 0.0, -0.5, 1.0, 1.0, 0.0, "fixed"),
                                         box_block("block", 0.0, 0.0, 0.0, 1.0, 1.0, 2.0)}),
                            s);
  const auto loaded = rbla::io::load_model_text(model.dump());
  EXPECT_EQ(loaded.model.interfaces.size(), 2u);
  EXPECT_FALSE(has_warning(loaded.model.warnings, "joints_through_blocks"));
}

// Slabs 7 mm thick under a joint tolerance of 30 cm (3 % of their 10 m faces): each slab touches
// only its neighbours. Without the two rules, the bottom of one slab and the top of the one above
// (back to back across a slab) and every pair of slabs with slabs between them (at most 28 mm
// apart: a gap the same all over closes up to 30 mm) were joined too.
TEST(JointsThroughBlocks, ThinSlabsStackedJoinOnlyTheirNeighbours) {
  json blocks = json::array({box_block("base", -1.0, -1.0, -0.5, 11.0, 2.0, 0.0, "fixed")});
  for (int k = 0; k < 5; ++k) {
    blocks.push_back(box_block("S" + std::to_string(k), 0.0, 0.0, 0.007 * k, 10.0, 1.0, 0.007 * (k + 1)));
  }
  Case s;
  const auto loaded = rbla::io::load_model_text(finish(blocks, s).dump());
  ASSERT_EQ(loaded.model.interfaces.size(), 5u);
  for (const model::ContactInterface& c : loaded.model.interfaces) {
    EXPECT_EQ(std::abs(c.block_a - c.block_b), 1) << c.block_a << " and " << c.block_b;
    EXPECT_NEAR(c.area, 10.0, 1e-9);
  }
  EXPECT_TRUE(has_warning(loaded.model.warnings, "joints_through_blocks"));
  EXPECT_EQ(loaded.model.detection_summary.through_blocks.joints, 10u);
}

// Only faces apart everywhere are held apart by a block. A 1 m cube tilted by 0.1 degrees about
// its left bottom edge touches the base along that edge and is 1.7 mm clear at the right, where a
// pinning stone fills the gap at one corner: all three joints stay and the cube stands (it slides
// at alpha = tan(atan(0.6) + 0.1 deg), 0.6012). The second review found it "cannot stand" when the
// cube's joint with the base was dropped because of the stone.
TEST(JointsThroughBlocks, ABlockTouchingTheBaseKeepsItsJointBesideAPinningStone) {
  const double tilt = 0.1 * model::kPi / 180.0;
  json cube = box_block("cube", 0.0, 0.0, 0.0, 1.0, 1.0, 1.0);
  for (json& v : cube["vertices"]) {
    const double x = v[0], z = v[2];
    v[0] = std::cos(tilt) * x - std::sin(tilt) * z;
    v[2] = std::sin(tilt) * x + std::cos(tilt) * z;
  }
  const double under = 0.9 * std::sin(tilt);  // the cube's bottom above x = 0.9, where the stone's top is
  Case s;
  const json model = finish(json::array({box_block("base", -1.0, -1.0, -0.5, 2.0, 2.0, 0.0, "fixed"),
                                         box_block("stone", 0.9, 0.0, 0.0, 0.97, 0.1, under), cube}),
                            s);
  const auto loaded = rbla::io::load_model_text(model.dump());
  EXPECT_EQ(loaded.model.interfaces.size(), 3u);
  EXPECT_FALSE(has_warning(loaded.model.warnings, "joints_through_blocks"));
  const AnalysisResult r = rbla::analysis::analyse(loaded.model);
  EXPECT_LT(relative_error(alpha_of(r), std::tan(std::atan(0.6) + tilt)), 2e-3) << alpha_of(r);
}

// Supports form no joints with each other, so a plinth that is itself a support shows no joint to
// the ground under it; it still holds the block apart from the ground. A 1 x 1 x 2 block on a fixed
// plinth 5 mm thick under 70 % of its base tips about the plinth's edge: alpha = 0.2 / 1.
TEST(JointsThroughBlocks, AFixedPlinthHoldsTheBlockApartFromTheGround) {
  Case s;
  const json model = finish(json::array({box_block("ground", -0.5, -0.5, -0.5, 1.5, 1.5, 0.0, "fixed"),
                                         box_block("plinth", 0.0, 0.0, 0.0, 0.7, 1.0, 0.005, "fixed"),
                                         box_block("block", 0.0, 0.0, 0.005, 1.0, 1.0, 2.005)}),
                            s);
  const AnalysisResult r = run(model);
  EXPECT_LT(relative_error(alpha_of(r), 0.2), 1e-6) << alpha_of(r);
}

// Two supports that overlap at the same level (a foundation embedded in a ground slab) are not one
// between the block and the other: it would have to lie in the gap, nearer the block than the
// other's face. The third review found both joints dropped ("cannot stand") for a block drawn at
// 0.1 + 0.2 on supports at 0.3 (5.6e-17 m above) and for gaps of 1e-9 m to 5 mm. alpha = b / h.
TEST(JointsThroughBlocks, OverlappingSupportsAtOneLevelAreNotBetween) {
  Case s;
  for (const double gap : {0.0, 1e-9, 0.001}) {
    SCOPED_TRACE(gap);
    const double bottom = 0.1 + 0.2 + gap;  // 0.30000000000000004 m at gap 0
    const json model = finish(json::array({box_block("ground", -1.0, -1.0, -0.5, 2.0, 2.0, 0.3, "fixed"),
                                           box_block("foundation", 0.3, -0.2, -0.2, 1.2, 1.2, 0.3, "fixed"),
                                           box_block("block", 0.0, 0.0, bottom, 1.0, 1.0, bottom + 2.0)}),
                              s);
    const auto loaded = rbla::io::load_model_text(model.dump());
    EXPECT_FALSE(has_warning(loaded.model.warnings, "joints_through_blocks"));
    EXPECT_LT(relative_error(alpha_of(rbla::analysis::analyse(loaded.model)), 0.5), 2e-3);
  }
}

}  // namespace
}  // namespace rbla::validation
