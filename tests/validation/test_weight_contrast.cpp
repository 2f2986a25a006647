// Unit-weight contrasts (issue 19): the per-block force scales of the conic problem
// (analysis/force_scales.hpp) give closed-form answers where one scale for the whole model did
// not, leave ordinary models with the very same problem, and a warning names the blocks where no
// scaling can be trusted. The closed forms themselves are asserted over 1e9 to 1e20 in the stiff
// suite (tests/stiff/stiff_cases.hpp, "Unit-weight contrasts 1e9 to 1e20").
#include "analysis/force_scales.hpp"
#include "analysis/formulation.hpp"
#include "validation_helpers.hpp"

#include <algorithm>
#include <string>

namespace rbla::validation {
namespace {

/// Two stacked blocks on a fixed base: a 1 x 1 x 1 block of unit weight `bottom` (kN/m3) and on
/// it a 1 x 1 x 2 block of unit weight `top`; seismic +x, friction 0.6.
json stacked(double bottom, double top, const std::string& friction_model = "associative") {
  json blocks = json::array({box_block("base", -0.5, -0.5, -0.5, 1.5, 1.5, 0.0, "fixed"),
                             box_block("bottom", 0, 0, 0, 1, 1, 1), box_block("top", 0, 0, 1, 1, 1, 3)});
  blocks[1]["unit_weight"] = bottom;
  blocks[2]["unit_weight"] = top;
  Case c;
  c.friction_model = friction_model;
  return finish(blocks, c);
}

/// A 1 x 1 x 1 block "H" (unit weight `heavy`) and beside it, touching, "L" (`light`), both on
/// the base; L's bed joint has friction 0.3, so pushed away from H it slides at alpha = 0.3.
json side_by_side(double heavy, double light, const std::string& friction_model = "associative") {
  json blocks = json::array({box_block("base", -0.5, -0.5, -0.5, 2.5, 1.5, 0.0, "fixed"),
                             box_block("H", 0, 0, 0, 1, 1, 1), box_block("L", 1, 0, 0, 2, 1, 1)});
  blocks[1]["unit_weight"] = heavy;
  blocks[2]["unit_weight"] = light;
  Case c;
  c.friction_model = friction_model;
  json model = finish(blocks, c);
  model["interfaces"] = json::array({{{"id", "L_bed"}, {"blocks", {"base", "L"}}, {"friction", 0.3},
                                      {"polygon", {{1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}}}}});
  model["detection"] = {{"mode", "merge"}};
  return model;
}

const model::Warning* find_warning(const AnalysisResult& r, const std::string& code) {
  const auto it = std::find_if(r.warnings.begin(), r.warnings.end(), [&](const auto& w) { return w.code == code; });
  return it == r.warnings.end() ? nullptr : &*it;
}

// The case: 10^9 : 1, the light 1 x 2 top block rocks at b/h = 0.5; with one force scale
// (the mean weight) its equilibrium fell under the solver's tolerance and the heavy block's
// sliding (0.6) was reported, exit 0, no warning.
TEST(WeightContrast, LightBlockOnAHeavyOneRocksAtItsOwnMultiplier) {
  for (const std::string friction : {"associative", "non_associative"}) {
    const AnalysisResult r = run(stacked(1e9, 1.0, friction));
    ASSERT_EQ(r.verdict, Verdict::Collapse) << r.verdict_text;
    EXPECT_NEAR(*r.load_multiplier, 0.5, 1e-6) << friction;
    EXPECT_EQ(find_warning(r, "weight_contrast"), nullptr);
    // The mechanism read back from the dual (rows scaled per block) does the same work.
    EXPECT_LT(r.work.relative_error, 1e-6);
    EXPECT_TRUE(r.mechanism.blocks[2].moving);
    EXPECT_FALSE(r.mechanism.blocks[1].moving);
  }
}

// A model whose loads stay within kForceScaleBand of the mean weight keeps one scale: the conic
// problem is the one rbla built before per-block scales (the samples' dumps are byte-identical).
TEST(WeightContrast, OrdinaryModelsKeepOneScale) {
  Case c;
  const auto loaded = rbla::io::load_model_text(finish(running_bond_blocks(6, 8), c).dump());
  const analysis::Formulation f = analysis::build_formulation(loaded.model, {});
  for (std::size_t b = 0; b < loaded.model.blocks.size(); ++b) EXPECT_EQ(f.block_scale[b], f.force_scale);
  for (const auto& point : f.points) EXPECT_EQ(point.force_scale, f.force_scale);
  EXPECT_EQ(f.rhs_resolution, 1.0);
}

// Carried loads follow gravity: the bottom of a heavy-on-light column carries the heavy block.
TEST(WeightContrast, CarriedLoadsFollowTheLoadPath) {
  const auto loaded = rbla::io::load_model_text(stacked(1.0, 1e12).dump());
  const analysis::ForceScales s = analysis::force_scales(loaded.model, 1.0, analysis::kLateralContrastLimit);
  const double bottom = loaded.model.blocks[1].weight(), top = loaded.model.blocks[2].weight();
  EXPECT_DOUBLE_EQ(s.carried[2], top);
  EXPECT_DOUBLE_EQ(s.carried[1], bottom + top);
  EXPECT_EQ(s.num_lateral_over_limit, 0);
}

// Side by side, whether the heavy block pushes on the light one is known only after the solve;
// under the limits the closed form holds, beyond them a warning names the blocks and the
// contrast (the answer is then wrong: 0.6 instead of 0.3 at 1e18, measured).
TEST(WeightContrast, SideBySideBeyondTheLimitIsNamedInAWarning) {
  const AnalysisResult ok = run(side_by_side(1e12, 1.0));
  ASSERT_EQ(ok.verdict, Verdict::Collapse);
  EXPECT_NEAR(*ok.load_multiplier, 0.3, 1e-6);
  EXPECT_EQ(find_warning(ok, "weight_contrast"), nullptr);

  const AnalysisResult far = run(side_by_side(1e12, 1e-6));
  const model::Warning* w = find_warning(far, "weight_contrast");
  ASSERT_NE(w, nullptr);
  EXPECT_NE(w->message.find("blocks 'L' and 'H'"), std::string::npos) << w->message;
  EXPECT_NE(w->message.find("1e+18 times apart"), std::string::npos) << w->message;
  EXPECT_NE(w->message.find("beyond a contrast of 1e+14"), std::string::npos) << w->message;
  EXPECT_EQ(w->pointer, "/blocks/2");

  // Non-associative friction resolves less: 1e10.
  const AnalysisResult na = run(side_by_side(1e9, 1.0, "non_associative"));
  EXPECT_NEAR(*na.load_multiplier, 0.3, 1e-5);
  EXPECT_EQ(find_warning(na, "weight_contrast"), nullptr);
  const AnalysisResult na_far = run(side_by_side(1e12, 0.1, "non_associative"));
  w = find_warning(na_far, "weight_contrast");
  ASSERT_NE(w, nullptr);
  EXPECT_NE(w->message.find("1e+10 (non-associative)"), std::string::npos) << w->message;
}

}  // namespace
}  // namespace rbla::validation
