// The weakest horizontal direction (analysis/worst_direction.hpp) against a closed form with
// several local minima.
//
// A rigid block on a fixed base, friction high enough that only overturning governs: with the
// seismic load alpha W d applied at the centroid, at height h_c above the contact, the resultant
// of W and alpha W d meets the contact plane at c + alpha h_c d, which must stay inside the contact
// polygon P. So alpha(theta) = rho_P(theta) / h_c, rho_P the radial function of P about the
// centroid's projection c. For a rectangle reaching a_-x, a_+x, a_-y, a_+y from c, alpha(theta)
// has a local minimum at each edge normal, a/h_c, and the global one at the nearest edge.
#include "analysis/worst_direction.hpp"
#include "validation_helpers.hpp"
#include "model/angles.hpp"

#include <cmath>

namespace rbla::validation {
namespace {

using rbla::model::kPi;

/// Block [-1,1]x[-0.7,0.7]x[0,2] (centroid height 1) on a base whose top meets it over
/// [-0.4,1.0]x[-0.6,0.7]: edges at 1.0 (+x), 0.7 (+y), 0.4 (-x), 0.6 (-y) from the centroid.
/// The whole scene is turned by `turn` (rad) about the vertical.
json off_centre_block(double turn, const std::string& friction_model = "associative") {
  json blocks = json::array({box_block("base", -0.4, -0.6, -0.5, 1.5, 1.0, 0.0, "fixed"),
                             box_block("block", -1.0, -0.7, 0.0, 1.0, 0.7, 2.0)});
  for (json& block : blocks) {
    for (json& v : block["vertices"]) {
      const double x = v[0], y = v[1];
      v[0] = std::cos(turn) * x - std::sin(turn) * y;
      v[1] = std::sin(turn) * x + std::cos(turn) * y;
    }
  }
  Case c;
  c.mu = 3.0;  // sliding would need alpha >= 3; overturning governs (alpha <= 1.23)
  c.friction_model = friction_model;
  return finish(blocks, c);
}

/// alpha(theta) of the closed form, theta measured from x in the turned frame.
double overturning_alpha(double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  double rho = std::numeric_limits<double>::infinity();
  if (c > 0) rho = std::min(rho, 1.0 / c);
  if (c < 0) rho = std::min(rho, 0.4 / -c);
  if (s > 0) rho = std::min(rho, 0.7 / s);
  if (s < 0) rho = std::min(rho, 0.6 / -s);
  return rho / 1.0;
}

rbla::analysis::WorstDirection search(const json& model, const rbla::analysis::RadialSearchSettings& settings = {}) {
  const auto loaded = rbla::io::load_model_text(model.dump());
  return rbla::analysis::find_worst_direction(loaded.model, {}, settings);
}

TEST(WorstDirection, AlphaAlongSingleDirectionsMatchesTheOverturningClosedForm) {
  for (double theta : {0.0, 0.5, 1.2, 2.0, kPi, 4.0, 5.0}) {
    Case c;
    c.mu = 3.0;
    c.seismic_direction = json::array({std::cos(theta), std::sin(theta), 0.0});
    json model = off_centre_block(0.0);
    model["analysis"]["seismic"]["direction"] = c.seismic_direction;
    const AnalysisResult r = run(model);
    ASSERT_EQ(r.verdict, Verdict::Collapse) << theta;
    EXPECT_LT(relative_error(*r.load_multiplier, overturning_alpha(theta)), 1e-6) << theta;
  }
}

TEST(WorstDirection, FindsTheNearestEdgeAmongFourLocalMinimaOffTheSamplingGrid) {
  // Turned by 17 degrees, the weakest direction (away from the nearest edge) is at 197 degrees,
  // on none of the directions a 5-degree sampling (or the search's first eight) would try.
  const double turn = 17.0 * kPi / 180.0;
  const auto w = search(off_centre_block(turn));
  ASSERT_EQ(w.verdict, Verdict::Collapse) << w.verdict_text;
  ASSERT_TRUE(w.alpha_min && w.angle && w.lower_bound);
  EXPECT_TRUE(w.certified) << w.stop;
  EXPECT_LT(relative_error(*w.alpha_min, 0.4), 1e-6);
  EXPECT_NEAR(*w.angle, kPi + turn, 1e-4);
  EXPECT_LE(*w.lower_bound, 0.4 * (1.0 + 1e-6));
  EXPECT_GE(*w.lower_bound, 0.4 * (1.0 - 1e-3));
  // Never worse than a dense sampling of directions (every 5 degrees, closed form here; the
  // closed form itself is checked against solves in the test above).
  double dense = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 72; ++k) dense = std::min(dense, overturning_alpha(k * 5.0 * kPi / 180.0 - turn));
  EXPECT_LE(*w.alpha_min, dense);
  EXPECT_LE(w.evaluations.size(), 15u);
  // The result carried along is the analysis at the minimum, along the direction reported.
  EXPECT_EQ(w.at_minimum.verdict, Verdict::Collapse);
  EXPECT_DOUBLE_EQ(*w.at_minimum.load_multiplier, *w.alpha_min);
  const rbla::model::Vec3 d = *w.model_at_minimum.analysis.seismic_direction;
  EXPECT_NEAR(std::atan2(d.y(), d.x()), -kPi + turn, 1e-4);
}

TEST(WorstDirection, ATightToleranceIsReachedAndCertified) {
  // A tolerance near the solver's own accuracy must still be reached and certified.
  rbla::analysis::RadialSearchSettings settings;
  settings.tolerance = 1e-7;
  settings.max_samples = 60;
  const auto w = search(off_centre_block(0.3), settings);
  ASSERT_EQ(w.verdict, Verdict::Collapse) << w.verdict_text;
  EXPECT_TRUE(w.certified) << w.stop;
  EXPECT_LT(relative_error(*w.alpha_min, 0.4), 1e-6);
}

TEST(WorstDirection, NonAssociativeFrictionGivesNoCertifiedBracket) {
  const auto w = search(off_centre_block(0.0, "non_associative"));
  ASSERT_EQ(w.verdict, Verdict::Collapse) << w.verdict_text;
  EXPECT_FALSE(w.certified);
  EXPECT_FALSE(w.lower_bound.has_value());
  // No sliding anywhere at mu = 3: the same overturning minimum.
  EXPECT_LT(relative_error(*w.alpha_min, 0.4), 1e-3);
  EXPECT_NE(w.verdict_text.find("not certified"), std::string::npos) << w.verdict_text;
}

TEST(WorstDirection, ABlockThatCannotStandStopsTheSearchWithThatVerdict) {
  // Centroid outside the contact: the base reaches only x in [0.2, 1.5].
  json blocks = json::array({box_block("base", 0.2, -1.0, -0.5, 1.5, 1.0, 0.0, "fixed"),
                             box_block("block", -1.0, -0.7, 0.0, 1.0, 0.7, 2.0)});
  Case c;
  c.mu = 3.0;
  const auto w = search(finish(blocks, c));
  EXPECT_EQ(w.verdict, Verdict::CannotStand) << w.verdict_text;
  EXPECT_FALSE(w.alpha_min.has_value());
  EXPECT_EQ(w.evaluations.size(), 1u);
}

TEST(WorstDirection, RefusesSettlementAndLivePointLoads) {
  json settlement = off_centre_block(0.0);
  settlement["analysis"] = {{"type", "settlement"}};
  settlement["blocks"][0]["role"] = "moving_support";
  EXPECT_THROW(search(settlement), rbla::model::ModelError);
  json point_load = off_centre_block(0.0);
  point_load["loads"] = {{"live", json::array({{{"block", "block"}, {"force", {1.0, 0.0, 0.0}}, {"point", {0.0, 0.0, 1.0}}}})}};
  try {
    search(point_load);
    ADD_FAILURE() << "live point loads accepted";
  } catch (const rbla::model::ModelError& error) {
    // The model's own field (it said /live_loads, which no model has).
    EXPECT_EQ(error.issues().front().pointer, "/loads/live") << error.what();
  }
}

}  // namespace
}  // namespace rbla::validation
