// Settling along a direction the structure does not need the ground along forms no mechanism
// (analysis/settlement_bound.hpp). Found by the search review: a flat arch that stands was
// reported "Cannot stand under dead load alone" along a settlement direction tilted 30 degrees
// inwards, and "Collapse ... R = 3e-9 kN, loss 100 %" along smaller tilts, with sensitivities of
// that R which finite differences put at 0.
//
// Closed form (the scene of tests/validation/test_worst_settlement.cpp): a block [0, L] x [0, 1]
// x [0, h] of weight W on a fixed support under [0, a] and a moving one under [a + g, L]. Along a
// direction tilted theta from gravity in the plane x-z, the least reaction of the admissible
// states is R(theta) = N* cos(theta) - mu sin(theta) min(N*, W - N*), N* = W (L/2 - a) / (L - a).
// With a = 1.5, L = 4, h = 1, mu = 0.6: N* = 14.4 kN = min(N*, W - N*), so R(theta) = 14.4
// (cos(theta) - 0.6 sin(theta)), which is 0 at tan(theta) = 1 / 0.6 (59.04 degrees) and negative
// beyond: there the supports' reaction can fall to 0 and no mechanism forms.
//
// The flat arch (three voussoirs, 4 m span, 0.4 m deep, joints radial to a point 3 m below the
// intrados; drawn in x-y with gravity -y) pushes its right abutment outwards: along a direction
// tilted 30 degrees inwards every state that holds it pushes that abutment back against the
// direction, and the settlement problem (R >= 0) is infeasible although the arch stands.
#include "analysis/worst_settlement.hpp"
#include "model/angles.hpp"
#include "validation_helpers.hpp"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace rbla::validation {
namespace {

using model::Vec3;

json settling_along(json model, const Vec3& direction) {
  model["analysis"]["settlement"] = {{"direction", {direction.x(), direction.y(), direction.z()}}};
  return model;
}

Vec3 tilted_in_xz(double degrees) {
  const double t = degrees * model::kPi / 180.0;
  return {std::sin(t), 0.0, -std::cos(t)};
}

json flat_arch(const std::string& right_role) {
  const double span = 4.0, depth = 0.4, below = 3.0;
  const auto top = [&](double x) { return x * (depth + below) / below; };  // joints radial to (0, -below)
  using Outline = std::vector<std::pair<double, double>>;
  json blocks = json::array();
  blocks.push_back(prism_block("abL", Outline{{-span / 2 - 2, -0.5}, {-span / 2, -0.5}, {-span / 2, 0}, {top(-span / 2), depth},
                                              {-span / 2 - 2, depth}},
                               0.0, 1.0, "fixed"));
  blocks.push_back(prism_block("abR", Outline{{span / 2, -0.5}, {span / 2 + 2, -0.5}, {span / 2 + 2, depth}, {top(span / 2), depth},
                                              {span / 2, 0}},
                               0.0, 1.0, right_role));
  for (int k = 0; k < 3; ++k) {
    const double x0 = -span / 2 + span * k / 3.0, x1 = -span / 2 + span * (k + 1) / 3.0;
    blocks.push_back(prism_block("v" + std::to_string(k), Outline{{x0, 0}, {x1, 0}, {top(x1), depth}, {top(x0), depth}}, 0.0, 1.0));
  }
  json model = model_with(blocks);
  model["gravity"] = "-y";
  model["defaults"] = {{"unit_weight", 18.0}, {"friction", 0.6}};
  return model;
}

/// The right abutment settling along the direction tilted `degrees` inwards (towards -x) from -y.
json flat_arch_settling_inwards(double degrees) {
  json model = flat_arch("moving_support");
  const double t = degrees * model::kPi / 180.0;
  model["analysis"] = {{"type", "settlement"}, {"settlement", {{"direction", {-std::sin(t), -std::cos(t), 0.0}}}}};
  return model;
}

}  // namespace

// Below 59.04 degrees the closed form's R is positive and reached by a collapse; beyond it the
// supports can shed their whole reaction along the direction: no mechanism, no R, no sensitivities.
TEST(SettlementNoMechanism, TheSettlingBlockCollapsesOnlyWhereTheClosedFormIsPositive) {
  for (const double degrees : {0.0, 30.0, 50.0}) {
    const AnalysisResult r = run(settling_along(settling_block(1.5, 4.0, 1.0, "3d"), tilted_in_xz(degrees)));
    const double t = degrees * model::kPi / 180.0;
    const double expected = 14.4 * (std::cos(t) - 0.6 * std::sin(t));
    ASSERT_EQ(r.verdict, Verdict::Collapse) << degrees << ": " << r.verdict_text;
    ASSERT_TRUE(r.base_reaction);
    EXPECT_LT(relative_error(*r.base_reaction, expected), 1e-6) << degrees << ": " << *r.base_reaction;
  }
  for (const double degrees : {60.0, 65.0, 80.0}) {
    const AnalysisResult r = run(settling_along(settling_block(1.5, 4.0, 1.0, "3d"), tilted_in_xz(degrees)));
    EXPECT_EQ(r.verdict, Verdict::NoMechanism) << degrees << ": " << r.verdict_text;
    EXPECT_FALSE(r.base_reaction) << degrees;
    EXPECT_FALSE(r.sensitivities) << degrees;
    EXPECT_FALSE(r.settlement_pushes_back) << degrees;
    EXPECT_NE(r.verdict_text.find("can fall to 0"), std::string::npos) << r.verdict_text;
  }
}

// The flat arch stands with both abutments fixed; settling its right abutment straight down
// collapses it; tilted 30 degrees inwards every state pushes the abutment back: no mechanism,
// not "cannot stand".
TEST(SettlementNoMechanism, AFlatArchThatPushesItsSupportBackStands) {
  json fixed = flat_arch("fixed");
  fixed["analysis"] = {{"type", "load_multiplier"}, {"seismic", {{"direction", {1, 0, 0}}}}};
  ASSERT_EQ(run(fixed).verdict, Verdict::Collapse);
  const AnalysisResult down = run(flat_arch_settling_inwards(0.0));
  ASSERT_EQ(down.verdict, Verdict::Collapse) << down.verdict_text;
  EXPECT_GT(*down.base_reaction, 0.0);
  const AnalysisResult inwards = run(flat_arch_settling_inwards(30.0));
  EXPECT_EQ(inwards.verdict, Verdict::NoMechanism) << inwards.verdict_text;
  EXPECT_TRUE(inwards.settlement_pushes_back);
  EXPECT_NE(inwards.verdict_text.find("pushes the moving supports back"), std::string::npos) << inwards.verdict_text;
}

// A structure that cannot stand even with its supports held still says so under settlement: a
// block overhanging the fixed support beside the settling block.
TEST(SettlementNoMechanism, AStructureThatCannotStandStillCannot) {
  json model = settling_block(1.5, 4.0, 1.0, "3d");
  model["blocks"].push_back(box_block("C", -1.4, 0.0, 0.0, -0.2, 1.0, 0.5));
  const AnalysisResult r = run(settling_along(model, tilted_in_xz(20.0)));
  EXPECT_EQ(r.verdict, Verdict::CannotStand) << r.verdict_text;
  EXPECT_NE(r.verdict_text.find("'C'"), std::string::npos) << r.verdict_text;
}

// The search goes on past such directions (it stopped there) and finds the flat arch's most
// harmful direction outwards, certified.
TEST(SettlementNoMechanism, TheSearchGoesOnPastDirectionsWithoutAMechanism) {
  const auto loaded = rbla::io::load_model_text(flat_arch_settling_inwards(0.0).dump());
  analysis::WorstSettlementSettings settings;
  settings.cone_angle = 30.0 * model::kPi / 180.0;
  const analysis::WorstSettlement w = analysis::find_worst_settlement(loaded.model, {}, settings);
  ASSERT_EQ(w.verdict, Verdict::Collapse) << w.verdict_text;
  EXPECT_TRUE(w.certified) << w.stop;
  int without = 0;
  for (const auto& e : w.evaluations) without += e.verdict == Verdict::NoMechanism ? 1 : 0;
  EXPECT_GE(without, 1);
  ASSERT_TRUE(w.worst);
  EXPECT_GT(w.evaluations[*w.worst].direction.x(), 0.0) << "outwards, away from the arch";
}

}  // namespace rbla::validation
