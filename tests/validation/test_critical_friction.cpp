// The critical friction (analysis/critical_friction.hpp) against closed forms: a block on an
// inclined plane stands iff mu >= tan(beta); a block of half-width b/2 and centroid height h/2
// on a flat base carries alpha = min(mu, b/h), so it reaches a target alpha_t < b/h at mu =
// alpha_t and no friction makes it reach alpha_t > b/h; with two blocks stacked on the plane and
// only one joint scaled, that joint alone needs mu >= tan(beta).
#include "analysis/critical_friction.hpp"
#include "validation_helpers.hpp"
#include "model/angles.hpp"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace rbla::validation {
namespace {

using rbla::analysis::ThresholdOutcome;

using rbla::model::kPi;

rbla::analysis::CriticalFriction search(const json& model, std::optional<double> target, double tolerance) {
  const auto loaded = rbla::io::load_model_text(model.dump());
  rbla::analysis::ThresholdSettings settings;
  settings.tolerance = tolerance;
  return rbla::analysis::find_critical_friction(loaded.model, target, {}, settings);
}

TEST(CriticalFriction, ABlockOnAnInclinedPlaneNeedsTanBetaToStand) {
  for (double degrees : {10.0, 20.0, 35.0}) {
    const double beta = degrees * kPi / 180.0;
    const auto c = search(inclined_block(beta, 0.6), std::nullopt, 1e-6);
    ASSERT_EQ(c.outcome, ThresholdOutcome::Bracketed) << c.verdict_text;
    EXPECT_TRUE(c.certified) << c.stop;
    ASSERT_TRUE(c.uniform_friction);
    const double mu_lower = *c.uniform_friction * *c.factor_lower, mu_upper = *c.uniform_friction * *c.factor_upper;
    EXPECT_LE(mu_lower, std::tan(beta) * (1.0 + 1e-7)) << degrees;
    EXPECT_GE(mu_upper, std::tan(beta) * (1.0 - 1e-7)) << degrees;
    EXPECT_LT(relative_error(mu_upper, std::tan(beta)), 2e-6) << degrees;
    // The analysis kept is the one at the critical factor: the block stands there.
    EXPECT_NE(c.at_critical.verdict, Verdict::CannotStand);
  }
}

TEST(CriticalFriction, ATargetAlphaBelowTheTippingLimitNeedsMuEqualToIt) {
  Case s;
  s.mu = 0.6;
  const json model = single_block(1.0, 2.0, s);  // alpha = min(mu, 0.5)
  const auto c = search(model, 0.3, 1e-6);
  ASSERT_EQ(c.outcome, ThresholdOutcome::Bracketed) << c.verdict_text;
  EXPECT_TRUE(c.certified);
  EXPECT_LT(relative_error(*c.uniform_friction * *c.factor_upper, 0.3), 2e-6);
  EXPECT_NE(c.verdict_text.find("to carry alpha = 0.3"), std::string::npos) << c.verdict_text;
}

TEST(CriticalFriction, NoFrictionReachesATargetAboveTheTippingLimit) {
  Case s;
  s.mu = 0.6;
  const auto c = search(single_block(1.0, 2.0, s), 0.6, 1e-3);
  EXPECT_EQ(c.outcome, ThresholdOutcome::FailsAtMaximum) << c.verdict_text;
  EXPECT_FALSE(c.factor_upper.has_value());
  // The largest factor tried is the one that takes mu to the schema's limit of 100.
  EXPECT_NEAR(*c.uniform_friction * *c.factor_lower, 100.0, 1e-9);
  EXPECT_NE(c.verdict_text.find("No friction up to mu = 100"), std::string::npos) << c.verdict_text;
}

// The target at the tipping limit itself, as a user copies it from an analysis: alpha = min(mu,
// 0.5) reaches 0.5 at mu = 0.5 and stays there, within the solver's last digits. The bracket
// holds mu = 0.5 (it held 0.3125 to 0.3216 on a block whose limit is 0.3 before targets were
// carried to 1e-6), and targets just below the limit take no more than 25 analyses.
TEST(CriticalFriction, ATargetAtTheTippingLimitNeedsMuEqualToIt) {
  Case s;
  s.mu = 0.6;
  for (const double target : {0.5, 0.5 - 1e-7, 0.49999}) {
    const auto c = search(single_block(1.0, 2.0, s), target, 1e-3);
    ASSERT_EQ(c.outcome, ThresholdOutcome::Bracketed) << c.verdict_text;
    EXPECT_TRUE(c.certified) << c.stop;
    EXPECT_LE(0.6 * *c.factor_lower, target) << target;
    EXPECT_GE(0.6 * *c.factor_upper, target * (1.0 - 1e-6)) << target;
    EXPECT_LE(c.evaluations.size(), 25u) << target;
  }
}

/// The interface between two blocks, by their ids.
int interface_between(const model::Model& m, const std::string& a, const std::string& b) {
  for (std::size_t k = 0; k < m.interfaces.size(); ++k) {
    const std::string& first = m.blocks[m.interfaces[k].block_a].id;
    const std::string& second = m.blocks[m.interfaces[k].block_b].id;
    if ((first == a && second == b) || (first == b && second == a)) return static_cast<int>(k);
  }
  return -1;
}

// Two blocks on a plane at 20 degrees, the bed joint at mu = 0.5 and the joint between them at
// 1.0, both above tan(20) = 0.364. Scaling only one joint, that joint must reach tan(beta): the
// factor is tan(beta) / 0.5 for the bed joint and tan(beta) / 1.0 for the upper one. Scaling
// both together would need the larger of the two, tan(beta) / 0.5, either way.
/// Two blocks stacked on a plane at 20 degrees, the bed joint at mu `bed_mu` and the joint
/// between them at `upper_mu`, with the indices of those joints.
struct InclinedStack {
  model::Model m;
  int bed = -1, upper = -1;
};
InclinedStack inclined_stack(double beta, double bed_mu, double upper_mu) {
  InclinedStack s{rbla::io::load_model_text(inclined_block(beta, 0.6, true).dump()).model};
  s.bed = interface_between(s.m, "base", "block");
  s.upper = interface_between(s.m, "block", "top");
  if (s.bed >= 0) s.m.interfaces[s.bed].friction = bed_mu;
  if (s.upper >= 0) s.m.interfaces[s.upper].friction = upper_mu;
  return s;
}

TEST(CriticalFriction, OnlyTheChosenJointIsScaled) {
  const double beta = 20.0 * kPi / 180.0;
  InclinedStack stack = inclined_stack(beta, 0.5, 1.0);
  model::Model& m = stack.m;
  const int bed = stack.bed, upper = stack.upper;
  ASSERT_GE(bed, 0);
  ASSERT_GE(upper, 0);
  rbla::analysis::ThresholdSettings settings;
  settings.tolerance = 1e-6;
  for (const auto& [joint, given] : {std::pair{bed, 0.5}, std::pair{upper, 1.0}}) {
    const auto c = rbla::analysis::find_critical_friction(m, std::nullopt, {}, settings, {joint});
    ASSERT_EQ(c.outcome, ThresholdOutcome::Bracketed) << c.verdict_text;
    EXPECT_TRUE(c.certified) << c.stop;
    ASSERT_TRUE(c.uniform_friction);
    EXPECT_EQ(*c.uniform_friction, given);
    EXPECT_LT(relative_error(*c.factor_upper, std::tan(beta) / given), 2e-6) << joint;
    EXPECT_EQ(c.scaled_interfaces, std::vector<int>{joint});
    EXPECT_NE(c.verdict_text.find("of the 1 chosen interface times"), std::string::npos) << c.verdict_text;
    // The other joint kept its coefficient in the analysis reported.
    const int other = joint == bed ? upper : bed;
    EXPECT_EQ(c.model_at_critical.interfaces[other].friction, m.interfaces[other].friction);
  }
  // Picked by block: the interfaces of "top" are the upper joint alone.
  std::vector<std::string> unmatched;
  EXPECT_EQ(m.interfaces_named({}, {"top"}, unmatched), std::vector<int>{upper});
  EXPECT_EQ(m.interfaces_named({m.interfaces[bed].id, "nothing"}, {}, unmatched), std::vector<int>{bed});
  EXPECT_EQ(unmatched, std::vector<std::string>{"nothing"});
}

// A joint far above the others (a keyed joint at mu = 50) is held at the schema's limit of 100
// while the others grow: the two blocks on the plane at 20 degrees with the bed joint at 0.15
// need the factor tan(beta) / 0.15. Capping the factor at 100 / 50 stopped the bed at 0.3 and
// reported that no friction is enough.
TEST(CriticalFriction, ACoefficientAtTheLimitIsHeldWhileTheOthersGrow) {
  const double beta = 20.0 * kPi / 180.0;
  const InclinedStack stack = inclined_stack(beta, 0.15, 50.0);
  ASSERT_GE(stack.upper, 0);
  rbla::analysis::ThresholdSettings settings;
  settings.tolerance = 1e-6;
  const auto c = rbla::analysis::find_critical_friction(stack.m, std::nullopt, {}, settings);
  ASSERT_EQ(c.outcome, ThresholdOutcome::Bracketed) << c.verdict_text;
  EXPECT_TRUE(c.certified) << c.stop;
  EXPECT_LT(relative_error(*c.factor_upper, std::tan(beta) / 0.15), 2e-6);
  EXPECT_EQ(c.model_at_critical.interfaces[stack.upper].friction, 100.0);
  EXPECT_NE(c.verdict_text.find("1 coefficient held at 100"), std::string::npos) << c.verdict_text;
}

TEST(CriticalFriction, AFlatStackStandsWithAnyFriction) {
  Case s;
  s.mu = 0.6;
  const auto c = search(column(3, 1.0, 2.0, s), std::nullopt, 1e-3);
  EXPECT_EQ(c.outcome, ThresholdOutcome::PassesAtMinimum) << c.verdict_text;
}

}  // namespace
}  // namespace rbla::validation
