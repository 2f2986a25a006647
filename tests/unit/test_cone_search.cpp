// The bracketed maximum over a cone of directions (analysis/cone_search.hpp) against brute force:
// a dense sampling of the cone (every 0.05 degrees of tilt, 0.1 degrees of azimuth) for concave
// functions whose maximum lies inside the cone, on its rim, at a kink, and with a tilted
// functional w.
#include "analysis/cone_search.hpp"
#include "model/angles.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <vector>

namespace {

using Eigen::Vector3d;
using rbla::analysis::ConeSample;
using rbla::analysis::DirectionCone;
using rbla::analysis::find_cone_maximum;

using rbla::model::kPi;

/// A concave, positively homogeneous function with its supergradient.
struct Concave {
  std::function<double(const Vector3d&)> value;
  std::function<Vector3d(const Vector3d&)> supergradient;
};

/// f(d) = min_i g_i . d: the minimiser's g is a supergradient.
Concave piecewise(std::vector<Vector3d> g) {
  auto arg = [g](const Vector3d& d) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < g.size(); ++i) best = g[i].dot(d) < g[best].dot(d) ? i : best;
    return g[best];
  };
  return {[arg](const Vector3d& d) { return arg(d).dot(d); }, arg};
}

/// f(d) = a . d - |B d| (a norm is convex): smooth away from B d = 0, where a is a supergradient.
Concave smooth(Vector3d a, Eigen::Matrix3d b) {
  return {[a, b](const Vector3d& d) { return a.dot(d) - (b * d).norm(); },
          [a, b](const Vector3d& d) {
            const double norm = (b * d).norm();
            return norm > 0.0 ? Vector3d(a - b.transpose() * (b * d) / norm) : a;
          }};
}

ConeSample evaluate(const Concave& f, const DirectionCone& cone, const Vector3d& d) {
  ConeSample s;
  s.ratio = f.value(d) / cone.w.dot(d);
  s.supergradient = f.supergradient(d);
  return s;
}

/// The largest ratio over a dense grid of the cone's directions.
double dense_maximum(const Concave& f, const DirectionCone& cone) {
  const Vector3d a = cone.axis.normalized();
  const Vector3d seed = std::abs(a.x()) < 0.9 ? Vector3d::UnitX() : Vector3d::UnitY();
  const Vector3d e1 = (seed - seed.dot(a) * a).normalized(), e2 = a.cross(e1);
  double best = -1e300;
  const int tilts = static_cast<int>(cone.half_angle * 180.0 / kPi / 0.05);
  for (int i = 0; i <= tilts; ++i) {
    const double tilt = cone.half_angle * i / tilts;
    for (int j = 0; j < 3600; ++j) {
      const double azimuth = 2.0 * kPi * j / 3600;
      const Vector3d d = std::cos(tilt) * a + std::sin(tilt) * (std::cos(azimuth) * e1 + std::sin(azimuth) * e2);
      best = std::max(best, f.value(d) / cone.w.dot(d));
    }
  }
  return best;
}

void expect_bracket_holds(const Concave& f, const DirectionCone& cone) {
  const auto result = find_cone_maximum([&](const Vector3d& d) { return evaluate(f, cone, d); }, cone);
  ASSERT_GE(result.best, 0) << result.stop;
  ASSERT_TRUE(result.converged) << result.stop;
  ASSERT_TRUE(result.upper_bound);
  const double best = result.samples[result.best].ratio;
  const double dense = dense_maximum(f, cone);
  // The dense grid finds at most the true maximum, which the bound must cover; the search's
  // best must be within the tolerance (1e-3) of it, and no worse than the grid by more.
  EXPECT_GE(*result.upper_bound, dense - 1e-9) << result.stop;
  EXPECT_GE(best, dense - 1e-3 * std::abs(dense)) << "dense " << dense << ", search " << best;
  EXPECT_LE(best, *result.upper_bound + 1e-12);
  EXPECT_LE(static_cast<int>(result.samples.size()), 30);
}

TEST(ConeSearch, APiecewiseLinearMaximumOnTheRimOfAVerticalCone) {
  DirectionCone cone;
  cone.half_angle = 30.0 * kPi / 180.0;
  expect_bracket_holds(piecewise({{1.0, 0.0, 1.0}, {-0.5, 0.3, 1.2}}), cone);
}

TEST(ConeSearch, AKinkInsideTheCone) {
  // Three planes meeting above the slice's interior, off the axis: on the slice z = 1 they are
  // 0.4 x + 1.1, -0.3 x + 0.3 y + 1.05 and -0.1 x - 0.5 y + 1.08, equal at (-0.062, 0.022),
  // where their gradients surround zero: the maximum 1.0752 is there.
  DirectionCone cone;
  cone.half_angle = 40.0 * kPi / 180.0;
  expect_bracket_holds(piecewise({{0.4, 0.0, 1.1}, {-0.3, 0.3, 1.05}, {-0.1, -0.5, 1.08}}), cone);
}

TEST(ConeSearch, ASmoothMaximumWithATiltedFunctional) {
  DirectionCone cone;
  cone.axis = Vector3d(0.0, 0.0, -1.0);
  cone.half_angle = 25.0 * kPi / 180.0;
  cone.w = Vector3d(0.1, -0.05, -1.0);
  Eigen::Matrix3d b = Eigen::Matrix3d::Zero();
  b(0, 0) = 1.0;
  b(1, 1) = 2.0;
  b(0, 1) = 0.5;
  b(2, 2) = 0.3;  // |B d| > 0 on the whole cone: no kink
  expect_bracket_holds(smooth(Vector3d(0.2, 0.1, -1.0), b), cone);
}

TEST(ConeSearch, AFailedEvaluationStopsWithItsReason) {
  DirectionCone cone;
  int calls = 0;
  const auto result = find_cone_maximum(
      [&](const Vector3d&) {
        ConeSample s;
        s.ratio = 1.0;
        s.supergradient = Vector3d::UnitZ();
        if (++calls == 3) {
          s.usable = false;
          s.why_unusable = "the solver gave up";
        }
        return s;
      },
      cone);
  EXPECT_TRUE(result.failed);
  EXPECT_EQ(result.samples.size(), 3u);
  EXPECT_NE(result.stop.find("the solver gave up"), std::string::npos);
  EXPECT_FALSE(result.converged);
}

TEST(ConeSearch, RefusesAFunctionalThatVanishesOnTheCone) {
  DirectionCone cone;
  cone.half_angle = 60.0 * kPi / 180.0;
  cone.w = Vector3d(1.0, 0.0, 0.5);  // at 63 degrees from the axis: w . d < 0 on part of the cone
  EXPECT_LT(rbla::analysis::smallest_on_cone(cone), 0.0);
  EXPECT_THROW(find_cone_maximum([](const Vector3d&) { return ConeSample{}; }, cone), std::invalid_argument);
}

}  // namespace
