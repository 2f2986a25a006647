// A joint is not formed through a third block. Detection accepts two faces as touching across a
// gap within the joint tolerance; a thin block lying in that gap and touching both (a shim, a damp
// proof course drawn as its own block) holds them apart, and a joint through it would carry the
// load through its volume. Closed form: a 1 x 1 x 2 block on a shim 0.7 wide and t thick, on a
// fixed base, under a horizontal load: block and shim tip together about the shim's far edge,
//   alpha = (W_C 0.2 + W_S 0.35) / (W_C (1 + t) + W_S t / 2),  W_C = 2 gamma, W_S = 0.7 t gamma
// (0.199614 at t = 5 mm). With the joint through the shim the block stood on its whole base and
// alpha was 0.4988.
#include "validation_helpers.hpp"

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

// Slabs 1 cm thick under a joint tolerance of 30 cm (3 % of their 10 m faces): each slab touches
// only its neighbours. Without the two rules, the bottom of one slab and the top of the one above
// (back to back across a slab) and every pair of slabs with slabs between them were joined too.
TEST(JointsThroughBlocks, ThinSlabsStackedJoinOnlyTheirNeighbours) {
  json blocks = json::array({box_block("base", -1.0, -1.0, -0.5, 11.0, 2.0, 0.0, "fixed")});
  for (int k = 0; k < 5; ++k) {
    blocks.push_back(box_block("S" + std::to_string(k), 0.0, 0.0, 0.01 * k, 10.0, 1.0, 0.01 * (k + 1)));
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

}  // namespace
}  // namespace rbla::validation
