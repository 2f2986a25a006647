// Derivatives of alpha from the collapse state (analysis/sensitivities.hpp) against a closed form
// (a block: alpha = min(mu, b/h), so d alpha / d mu is 1 while it slides and 0 while it tips, and
// alpha does not depend on its unit weight) and against central finite differences of whole
// analyses on the bundled wall with an opening.
#include "analysis/sensitivities.hpp"
#include "io/sensitivities_json.hpp"
#include "validation_helpers.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace rbla::validation {
namespace {

TEST(Sensitivities, ASlidingBlockGainsAlphaOneForOneWithFrictionAndATippingOneNothing) {
  for (const auto& [mu, slides] : {std::pair{0.3, true}, std::pair{0.6, false}}) {
    Case s;
    s.mu = mu;
    const AnalysisResult r = run(single_block(1.0, 2.0, s));  // alpha = min(mu, 0.5)
    ASSERT_TRUE(r.sensitivities) << mu;
    const auto& d = *r.sensitivities;
    EXPECT_NEAR(d.friction_factor, slides ? mu : 0.0, 1e-6) << mu;
    if (slides) {
      ASSERT_EQ(d.interface_friction.size(), 1u);
      EXPECT_NEAR(d.interface_friction[0].second, 1.0, 1e-6);
    } else {
      for (const auto& [k, value] : d.interface_friction) EXPECT_NEAR(value, 0.0, 1e-6) << k;
      EXPECT_TRUE(d.interface_friction.empty());
    }
    for (const auto& [block, value] : d.block_unit_weight) EXPECT_NEAR(value, 0.0, 1e-9) << block;
  }
}

TEST(Sensitivities, NotReportedForNonAssociativeFriction) {
  Case s;
  s.mu = 0.3;
  s.friction_model = "non_associative";
  EXPECT_FALSE(run(single_block(1.0, 2.0, s)).sensitivities.has_value());
}

// A model drawn in millimetres with unit weights in kN/m3 (units.unit_weight) reports the same
// d alpha / d unit weight as the model in metres: per the unit the model gives unit weights in.
// They were per kN/mm^3, 1e9 times the metre model's.
TEST(Sensitivities, UnitWeightDerivativesArePerTheModelsUnitWeightUnit) {
  Case s;
  s.mu = 0.8;
  const json metres = column(3, 1.0, 3.0, s);  // tips about its base: each block's weight matters
  json millimetres = metres;
  millimetres["units"]["length"] = "mm";
  for (json& block : millimetres["blocks"]) {
    for (json& v : block["vertices"]) {
      for (json& x : v) x = x.get<double>() * 1000.0;
    }
  }
  std::vector<json> written;
  for (const json& model : {metres, millimetres}) {
    const auto loaded = rbla::io::load_model_text(model.dump());
    const AnalysisResult r = rbla::analysis::analyse(loaded.model);
    ASSERT_TRUE(r.sensitivities);
    written.push_back(rbla::io::sensitivities_json(loaded.model, *r.sensitivities)["blocks"]);
  }
  ASSERT_GE(written[0].size(), 2u);
  ASSERT_EQ(written[1].size(), written[0].size());
  for (std::size_t b = 0; b < written[0].size(); ++b) {
    const double in_m = written[0][b]["d_load_multiplier_d_unit_weight"], in_mm = written[1][b]["d_load_multiplier_d_unit_weight"];
    EXPECT_GT(std::abs(in_m), 1e-6) << b;
    EXPECT_LT(relative_error(in_mm, in_m), 1e-6) << b << ": " << in_mm << " against " << in_m;
  }
}

/// The value the sensitivities differentiate: alpha, or the base reaction under settlement (model
/// force units, kN in these samples).
double collapse_value_of(const AnalysisResult& r) {
  EXPECT_EQ(r.verdict, Verdict::Collapse);
  if (r.type == model::AnalysisType::Settlement) return r.base_reaction.value_or(std::nan(""));
  return r.load_multiplier.value_or(std::nan(""));
}

// Central differences carry the solver's error over the step: alpha to ~1e-8 relative (the
// default tolerances) over a step of 1e-4 would be ~5e-5 relative in the difference, above the
// 1e-5 the joints are compared to, so the differenced solves run at tighter tolerances. The sum
// over every joint uses a larger step and a looser comparison.
constexpr double kStep = 1e-4;
constexpr double kFactorStep = 1e-3;
constexpr double kDifferenceTolerance = 1e-10;

struct Scene {
  const char* sample;
  model::Formulation formulation;
};

/// The bundled walls (an opening under a seismic load, a settling base) in their own (planar LP)
/// formulation and with 3-D cones.
class WallDifferences : public ::testing::TestWithParam<Scene> {
 protected:
  void SetUp() override {
    loaded_ = rbla::io::load_model_file(std::string(RBLA_SOURCE_DIR) + "/samples/" + GetParam().sample);
    loaded_.model.analysis.formulation = GetParam().formulation;
    result_ = rbla::analysis::analyse(loaded_.model);
    ASSERT_EQ(result_.verdict, Verdict::Collapse);
    ASSERT_TRUE(result_.sensitivities);
    value_ = collapse_value_of(result_);
  }
  /// Central difference of the value for a change `apply(model, +-h)`.
  template <class Apply>
  double difference(Apply apply, double h) const {
    model::Model up = loaded_.model, down = loaded_.model;
    for (model::Model* m : {&up, &down}) {
      m->analysis.tol_relative_gap = kDifferenceTolerance;
      m->analysis.tol_feasibility = kDifferenceTolerance;
    }
    apply(up, h);
    apply(down, -h);
    return (collapse_value_of(rbla::analysis::analyse(up)) - collapse_value_of(rbla::analysis::analyse(down))) / (2.0 * h);
  }
  /// Derivatives below this are zero for the comparison (relative to the value: alpha ~ 0.5, R ~ 12 kN).
  double floor() const { return 1e-2 * std::max(1.0, std::abs(value_)); }
  rbla::io::LoadedModel loaded_;
  AnalysisResult result_;
  double value_ = 0.0;
};

TEST_P(WallDifferences, FrictionFactorMatchesACentralDifference) {
  const double fd = difference([](model::Model& m, double h) {
    for (auto& contact : m.interfaces) contact.friction *= 1.0 + h;
  }, kFactorStep);
  EXPECT_NEAR(result_.sensitivities->friction_factor, fd, 1e-4 * std::max(floor(), std::abs(fd)))
      << "analytic " << result_.sensitivities->friction_factor << ", difference " << fd;
}

TEST_P(WallDifferences, TheMostInfluentialJointsMatchCentralDifferences) {
  auto joints = result_.sensitivities->interface_friction;
  ASSERT_FALSE(joints.empty());
  std::sort(joints.begin(), joints.end(), [](const auto& a, const auto& b) { return std::abs(a.second) > std::abs(b.second); });
  for (std::size_t i = 0; i < std::min<std::size_t>(3, joints.size()); ++i) {
    const int k = joints[i].first;
    const double fd = difference([k](model::Model& m, double h) { m.interfaces[k].friction += h; }, kStep);
    EXPECT_NEAR(joints[i].second, fd, 1e-5 * std::max(floor(), std::abs(fd))) << "interface " << k;
  }
}

TEST_P(WallDifferences, UnitWeightsOfMovingBlocksMatchCentralDifferences) {
  auto blocks = result_.sensitivities->block_unit_weight;
  ASSERT_FALSE(blocks.empty());
  std::sort(blocks.begin(), blocks.end(), [](const auto& a, const auto& b) { return std::abs(a.second) > std::abs(b.second); });
  for (std::size_t i = 0; i < std::min<std::size_t>(3, blocks.size()); ++i) {
    const int b = blocks[i].first;
    const double gamma = loaded_.model.blocks[b].unit_weight;
    const double fd = difference([b, gamma](model::Model& m, double h) { m.blocks[b].unit_weight = gamma * (1.0 + h); },
                                 kStep) / gamma;
    EXPECT_NEAR(blocks[i].second, fd, 1e-4 * std::abs(fd) + 1e-9) << "block " << b;
  }
}

// Scaling every unit weight by t scales every load with it (the samples carry no point loads):
// alpha does not change and R scales by t. So sum_b gamma_b d value / d gamma_b is 0 for alpha
// and R for the base reaction (Euler's theorem for homogeneous functions).
TEST_P(WallDifferences, UnitWeightDerivativesObeyHomogeneity) {
  ASSERT_TRUE(loaded_.model.dead_loads.empty() && loaded_.model.live_loads.empty());
  double sum = 0.0;
  for (const auto& [b, value] : result_.sensitivities->block_unit_weight) sum += loaded_.model.blocks[b].unit_weight * value;
  const bool settlement = result_.type == model::AnalysisType::Settlement;
  EXPECT_NEAR(sum, settlement ? value_ : 0.0, 1e-6 * std::max(1.0, std::abs(value_)));
}

INSTANTIATE_TEST_SUITE_P(
    Samples, WallDifferences,
    ::testing::Values(Scene{"wall_opening.json", model::Formulation::Planar},
                      Scene{"wall_opening.json", model::Formulation::ThreeD},
                      Scene{"wall_settlement.json", model::Formulation::Planar},
                      Scene{"wall_settlement.json", model::Formulation::ThreeD}),
    [](const auto& info) {
      const std::string scene = std::string(info.param.sample).find("settlement") != std::string::npos
                                    ? "settlement" : "opening";
      return scene + (info.param.formulation == model::Formulation::Planar ? "_planar" : "_cones_3d");
    });

}  // namespace
}  // namespace rbla::validation
