// Derivatives of alpha from the collapse state (analysis/sensitivities.hpp) against a closed form
// (a block: alpha = min(mu, b/h), so d alpha / d mu is 1 while it slides and 0 while it tips, and
// alpha does not depend on its unit weight) and against central finite differences of whole
// analyses on the bundled wall with an opening.
#include "analysis/sensitivities.hpp"
#include "validation_helpers.hpp"

#include <algorithm>
#include <cmath>

namespace rbla::validation {
namespace {

double alpha_of(const model::Model& m) {
  const AnalysisResult r = rbla::analysis::analyse(m);
  EXPECT_EQ(r.verdict, Verdict::Collapse);
  return r.load_multiplier.value_or(std::nan(""));
}

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

/// The wall in its own (planar LP) formulation and with 3-D cones.
class WallDifferences : public ::testing::TestWithParam<model::Formulation> {
 protected:
  void SetUp() override {
    loaded_ = rbla::io::load_model_file(std::string(RBLA_SOURCE_DIR) + "/samples/wall_opening.json");
    loaded_.model.analysis.formulation = GetParam();
    result_ = rbla::analysis::analyse(loaded_.model);
    ASSERT_EQ(result_.verdict, Verdict::Collapse);
    ASSERT_TRUE(result_.sensitivities);
  }
  /// Central difference of alpha for a change `apply(model, +-h)`.
  template <class Apply>
  double difference(Apply apply, double h) const {
    model::Model up = loaded_.model, down = loaded_.model;
    apply(up, h);
    apply(down, -h);
    return (alpha_of(up) - alpha_of(down)) / (2.0 * h);
  }
  rbla::io::LoadedModel loaded_;
  AnalysisResult result_;
};

// Central differences carry the solver's error over the step: alpha to ~1e-8 relative over a
// step of 1e-4 is ~5e-5 relative in the difference (the 3-D cones' interior point lands less
// exactly than the LP's). The sum over every joint uses a larger step and a looser tolerance.
constexpr double kStep = 1e-4;
constexpr double kFactorStep = 1e-3;

TEST_P(WallDifferences, FrictionFactorMatchesACentralDifference) {
  const double fd = difference([](model::Model& m, double h) {
    for (auto& contact : m.interfaces) contact.friction *= 1.0 + h;
  }, kFactorStep);
  EXPECT_NEAR(result_.sensitivities->friction_factor, fd, 1e-4 * std::max(1e-2, std::abs(fd)))
      << "analytic " << result_.sensitivities->friction_factor << ", difference " << fd;
}

TEST_P(WallDifferences, TheMostInfluentialJointsMatchCentralDifferences) {
  auto joints = result_.sensitivities->interface_friction;
  ASSERT_FALSE(joints.empty());
  std::sort(joints.begin(), joints.end(), [](const auto& a, const auto& b) { return std::abs(a.second) > std::abs(b.second); });
  for (std::size_t i = 0; i < std::min<std::size_t>(3, joints.size()); ++i) {
    const int k = joints[i].first;
    const double fd = difference([k](model::Model& m, double h) { m.interfaces[k].friction += h; }, kStep);
    EXPECT_NEAR(joints[i].second, fd, 1e-5 * std::max(1e-2, std::abs(fd))) << "interface " << k;
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

INSTANTIATE_TEST_SUITE_P(Formulations, WallDifferences,
                         ::testing::Values(model::Formulation::Planar, model::Formulation::ThreeD),
                         [](const auto& info) { return info.param == model::Formulation::Planar ? "planar" : "cones_3d"; });

}  // namespace
}  // namespace rbla::validation
