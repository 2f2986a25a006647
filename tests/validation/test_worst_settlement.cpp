// The most harmful settlement direction (analysis/worst_settlement.hpp) against a closed form
// and against a dense sampling of the cone.
//
// Closed form: a block [0, L] x [0, 1] x [0, h] of weight W on a fixed support under [0, a] and
// a moving one under [a + g, L] (the scene of ClosedForms.SettlementBaseReaction). Let the
// support settle along d at tilt theta from gravity, in the plane x-z. The block's force on the
// moving support is G = (G_x, -N), and R = G . d = N cos(theta) - G_x' sin(theta), G_x' its
// horizontal component against the tilt. Moments about the support edge x = a do not involve
// the horizontal forces (they act in the plane z = 0), so N >= N* = W (L/2 - a) / (L - a) as for
// vertical settlement; G_x is bounded by friction at both supports, |G_x| <= mu min(N, W - N).
// For tan(theta) < 1 / mu the smallest R has N = N* and the full friction against the tilt:
//     R(theta) = N* cos(theta) - mu sin(theta) min(N*, W - N*).
// Before settlement the base pressure is vertical, R0(theta) = R0 cos(theta), so R / R0 =
// (N* - mu tan(theta) min(N*, W - N*)) / R0 is largest for vertical settlement.
#include "analysis/sweep.hpp"
#include "analysis/worst_settlement.hpp"
#include "validation_helpers.hpp"
#include "model/angles.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <string>
#include <vector>

namespace rbla::validation {
namespace {

using model::Vec3;
using rbla::analysis::WorstSettlement;
using rbla::analysis::WorstSettlementSettings;

using rbla::model::kPi;

WorstSettlement search(const model::Model& m, double cone_degrees, int max_directions = 30) {
  WorstSettlementSettings settings;
  settings.cone_angle = cone_degrees * kPi / 180.0;
  settings.search.max_samples = max_directions;
  return rbla::analysis::find_worst_settlement(m, {}, settings);
}

TEST(WorstSettlement, ABlockOnASettlingSupportIsWorstHitVertically) {
  const double a = 1.5, L = 4.0, h = 1.0, mu = 0.6;
  const auto loaded = rbla::io::load_model_text(settling_block(a, L, h, "3d").dump());
  const double W = 18.0 * L * h, n_star = W * (L / 2 - a) / (L - a);
  const WorstSettlement w = search(loaded.model, 30.0);
  ASSERT_EQ(w.verdict, Verdict::Collapse) << w.verdict_text;
  ASSERT_TRUE(w.certified) << w.stop;
  ASSERT_TRUE(w.worst);
  const auto& vertical = w.evaluations.front();
  ASSERT_NEAR(vertical.tilt, 0.0, 1e-12);
  const double r0 = vertical.initial_reaction;
  EXPECT_LT(relative_error(*w.ratio, n_star / r0), 1e-6) << w.verdict_text;
  EXPECT_LT(w.evaluations[*w.worst].tilt, 1e-6);
  EXPECT_LE(*w.upper_bound, n_star / r0 * (1.0 + 1e-3));
  // The initial pressure is vertical: R0 = R0_vertical cos(tilt) for every direction tried.
  EXPECT_NEAR(w.initial_reaction_vector.head<2>().norm(), 0.0, 1e-9 * r0);
  for (const auto& e : w.evaluations) {
    SCOPED_TRACE("tilt " + std::to_string(e.tilt) + " azimuth " + std::to_string(e.azimuth));
    EXPECT_LT(relative_error(e.initial_reaction, r0 * std::cos(e.tilt)), 1e-9);
    ASSERT_TRUE(e.ratio);
    EXPECT_LE(*e.ratio, n_star / r0 * (1.0 + 1e-7));
    // Along the block's length (azimuth 0 or 180 degrees) the closed form holds exactly; across
    // it, the torsion of the block eats friction, so R lies between it and N* cos(tilt).
    const double closed = n_star * std::cos(e.tilt) - mu * std::sin(e.tilt) * std::min(n_star, W - n_star);
    const double along = std::abs(std::sin(e.azimuth));
    if (along < 1e-9) {
      EXPECT_LT(relative_error(*e.base_reaction, closed), 1e-6) << *e.base_reaction << " expected " << closed;
    } else {
      EXPECT_GE(*e.base_reaction, closed * (1.0 - 1e-6));
      EXPECT_LE(*e.base_reaction, n_star * std::cos(e.tilt) * (1.0 + 1e-6));
    }
  }
}

TEST(WorstSettlement, NonAssociativeFrictionIsSearchedButNotCertified) {
  // The vertical settlement of the block has the same closed form with either flow rule
  // (ClosedForms.SettlementBaseReaction); away from it the non-associative R is never below the
  // associative one, so neither is its ratio.
  json model = settling_block(1.5, 4.0, 1.0, "3d");
  const auto associative = rbla::io::load_model_text(model.dump());
  model["analysis"]["friction_model"] = "non_associative";
  const auto loaded = rbla::io::load_model_text(model.dump());
  const WorstSettlement a = search(associative.model, 30.0);
  const WorstSettlement w = search(loaded.model, 30.0, 7);
  ASSERT_TRUE(w.worst) << w.verdict_text;
  EXPECT_FALSE(w.certified);
  EXPECT_FALSE(w.upper_bound.has_value());
  EXPECT_NE(w.verdict_text.find("not certified"), std::string::npos) << w.verdict_text;
  ASSERT_GE(a.evaluations.size(), 7u);
  const double W = 18.0 * 4.0, n_star = W * (2.0 - 1.5) / (4.0 - 1.5);
  EXPECT_LT(relative_error(*w.evaluations.front().base_reaction, n_star), 1e-5);
  for (std::size_t k = 0; k < 7; ++k) {
    EXPECT_GE(*w.evaluations[k].ratio, *a.evaluations[k].ratio * (1.0 - 1e-6)) << k;
  }
}

TEST(WorstSettlement, TheSupportForceIsASupergradientTightWhereItWasFound) {
  // R(d) = min over admissible states of G . d: the state found at d gives G* . d = R(d) there,
  // and G* . d' >= R(d') at any other d'.
  const auto loaded = rbla::io::load_model_text(settling_block(1.0, 4.0, 1.0, "3d").dump());
  model::Model m = loaded.model;
  const double tilt = 20.0 * kPi / 180.0;
  m.analysis.settlement_direction = Vec3(std::sin(tilt), 0.0, -std::cos(tilt));
  const auto r = rbla::analysis::analyse(m);
  ASSERT_EQ(r.verdict, Verdict::Collapse) << r.verdict_text;
  const Vec3 g = rbla::analysis::force_on_moving_supports(m, r);
  EXPECT_LT(relative_error(g.dot(m.analysis.settlement_direction), *r.base_reaction), 1e-7);
  for (const Vec3& other : {Vec3(0.0, 0.0, -1.0), Vec3(-std::sin(tilt), 0.0, -std::cos(tilt)),
                            Vec3(0.0, std::sin(tilt), -std::cos(tilt))}) {
    m.analysis.settlement_direction = other;
    const auto there = rbla::analysis::analyse(m);
    ASSERT_EQ(there.verdict, Verdict::Collapse);
    EXPECT_GE(g.dot(other), *there.base_reaction * (1.0 - 1e-7));
  }
}

/// A small running-bond wall (4 courses of 0.5 x 0.3 x 0.25 blocks, 2 m long) on a fixed support
/// under its left half and a settling one under its right half, turned by `turn` about the
/// vertical so that its plane is at no axis the search starts from.
json turned_wall(double turn) {
  json blocks = json::array({box_block("fixed", -0.5, -0.5, -0.5, 1.0, 0.8, 0.0, "fixed"),
                             box_block("moving", 1.001, -0.5, -0.5, 2.5, 0.8, 0.0, "moving_support")});
  for (int course = 0; course < 4; ++course) {
    const double z0 = 0.25 * course, offset = course % 2 == 0 ? 0.0 : 0.25;
    std::vector<double> cuts{0.0};
    for (double x = offset > 0.0 ? offset : 0.5; x < 2.0 - 1e-9; x += 0.5) cuts.push_back(x);
    cuts.push_back(2.0);
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      blocks.push_back(box_block("c" + std::to_string(course) + "_" + std::to_string(k), cuts[k], 0.0, z0, cuts[k + 1],
                                 0.3, z0 + 0.25));
    }
  }
  const Eigen::Matrix3d r = Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (json& block : blocks) {
    for (json& v : block["vertices"]) {
      const Eigen::Vector3d p = r * Eigen::Vector3d(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
      v = json::array({p.x(), p.y(), p.z()});
    }
  }
  json model = model_with(blocks);
  model["defaults"] = {{"unit_weight", 18.0}, {"friction", 0.6}};
  model["analysis"] = {{"type", "settlement"}};
  return model;
}

TEST(WorstSettlement, NeverBelowADenseSamplingOfTheCone) {
  const auto loaded = rbla::io::load_model_text(turned_wall(17.0 * kPi / 180.0).dump());
  const double cone = 25.0;
  const WorstSettlement w = search(loaded.model, cone);
  ASSERT_EQ(w.verdict, Verdict::Collapse) << w.verdict_text;
  ASSERT_TRUE(w.certified) << w.stop;
  // Every 5 degrees of tilt and 10 degrees of azimuth, with its own analyses.
  double dense = 0.0;
  for (double tilt = 0.0; tilt <= cone + 1e-9; tilt += 5.0) {
    for (double azimuth = 0.0; azimuth < (tilt > 0.0 ? 360.0 : 1.0); azimuth += 10.0) {
      const double t = tilt * kPi / 180.0, p = azimuth * kPi / 180.0;
      model::Model m = loaded.model;
      m.analysis.settlement_direction = Vec3(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), -std::cos(t));
      const auto r = rbla::analysis::analyse(m);
      ASSERT_EQ(r.verdict, Verdict::Collapse) << r.verdict_text;
      dense = std::max(dense, *r.base_reaction / w.initial_reaction_vector.dot(m.analysis.settlement_direction));
    }
  }
  EXPECT_GE(*w.ratio, dense * (1.0 - 1e-3)) << "search " << *w.ratio << ", dense " << dense;
  EXPECT_GE(*w.upper_bound, dense * (1.0 - 1e-7)) << "bound " << *w.upper_bound << ", dense " << dense;
}

// The tilt and azimuth reported are the ones `rbla sweep` takes: sweeping settlement_tilt and
// settlement_azimuth at them gives back the direction found.
TEST(WorstSettlement, ItsAnglesAreTheSweepsAngles) {
  const auto loaded = rbla::io::load_model_text(turned_wall(17.0 * kPi / 180.0).dump());
  const WorstSettlement w = search(loaded.model, 25.0);
  ASSERT_TRUE(w.worst);
  const auto& e = w.evaluations[*w.worst];
  ASSERT_GT(e.tilt, 0.1);
  using rbla::analysis::SweepParameter;
  const std::vector<rbla::analysis::SweepAxis> axes{{SweepParameter::SettlementTilt, 0.0, 80.0, 2},
                                                    {SweepParameter::SettlementAzimuth, 0.0, 360.0, 2}};
  rbla::analysis::SweepPoint point;
  point.values = {e.tilt * 180.0 / kPi, e.azimuth * 180.0 / kPi};
  const model::Model m = rbla::analysis::model_at(loaded.model, axes, point);
  EXPECT_LT((m.analysis.settlement_direction - e.direction).norm(), 1e-12)
      << m.analysis.settlement_direction.transpose() << " vs " << e.direction.transpose();
}

TEST(WorstSettlement, RefusesALoadMultiplierModelAndAModelWithoutAnInitialReaction) {
  Case s;
  const auto seismic = rbla::io::load_model_text(single_block(1.0, 2.0, s).dump());
  try {
    search(seismic.model, 30.0);
    ADD_FAILURE() << "a load-multiplier model was searched";
  } catch (const model::ModelError& e) {
    EXPECT_EQ(e.issues().front().pointer, "/analysis/type");
  }
  // A block on one sloping base: ground springs normal to it cannot carry its weight alone, so
  // the reaction before settlement, and with it R / R0, is not defined; the message says why.
  json model = settling_block(1.5, 4.0, 1.0, "3d");
  for (json& block : model["blocks"]) {
    for (json& v : block["vertices"]) {
      const double x = v[0], z = v[2], t = 20.0 * kPi / 180.0;
      v[0] = std::cos(t) * x + std::sin(t) * z;
      v[2] = -std::sin(t) * x + std::cos(t) * z;
    }
  }
  const auto sloped = rbla::io::load_model_text(model.dump());
  try {
    search(sloped.model, 30.0);
    ADD_FAILURE() << "a model without an initial reaction was searched";
  } catch (const model::ModelError& e) {
    EXPECT_EQ(e.issues().front().pointer, "/analysis");
    EXPECT_NE(std::string(e.what()).find("reaction before settlement"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rbla::validation
