// The bracketed minimum of a radial function (analysis/radial_search.hpp) on convex sets whose
// smallest radius is known in closed form: ellipses, polygons around an off-centre point, sets
// unbounded along some directions.
#include "analysis/radial_search.hpp"
#include "model/angles.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace {

using rbla::analysis::minimise_radius;
using rbla::analysis::RadialSample;
using rbla::analysis::RadialSearchSettings;

using rbla::model::kPi;
constexpr double kInf = std::numeric_limits<double>::infinity();

RadialSample sample(double angle, double radius) {
  RadialSample s;
  s.angle = angle;
  s.radius = radius;
  return s;
}

/// Radial function of the ellipse x^2/a^2 + y^2/b^2 <= 1, turned by `turn`.
RadialSample ellipse(double a, double b, double turn, double t) {
  const double c = std::cos(t - turn), s = std::sin(t - turn);
  return sample(t, 1.0 / std::sqrt(c * c / (a * a) + s * s / (b * b)));
}

/// Radial function of the half-plane intersection { x : n_i . x <= h_i } (h_i > 0), with the
/// nearest point of the constraint that binds as the supporting line (as a mechanism gives it).
struct Polygon {
  std::vector<std::pair<double, double>> normal_angle_and_distance;
  RadialSample operator()(double t) const {
    RadialSample s = sample(t, kInf);
    for (const auto& [angle, h] : normal_angle_and_distance) {
      const double c = std::cos(t - angle);
      if (c > 0.0 && h / c < s.radius) {
        s.radius = h / c;
        s.bound_angle = angle;
        s.bound_radius = h;
      }
    }
    return s;
  }
  double smallest() const {
    double m = kInf;
    for (const auto& [angle, h] : normal_angle_and_distance) m = std::min(m, h);
    return m;
  }
};

/// The tip-over set of a block whose centroid stands off-centre over a rectangular base: four
/// local minima of r, one per edge (0.4, 0.6, 0.7, 1.0), the smallest to the left.
Polygon off_centre_rectangle() { return {{{0.0, 1.0}, {0.5 * kPi, 0.7}, {kPi, 0.4}, {1.5 * kPi, 0.6}}}; }

TEST(RadialSearch, EllipseMinimumIsTheMinorSemiAxisWithinTheBracket) {
  for (double turn : {0.0, 0.3, 1.1, 2.9}) {
    RadialSearchSettings settings;
    settings.tolerance = 1e-6;
    settings.max_samples = 200;
    const auto result = minimise_radius([&](double t) { return ellipse(2.0, 0.5, turn, t); }, settings);
    ASSERT_TRUE(result.converged) << result.stop;
    ASSERT_TRUE(result.lower_bound);
    const double found = result.samples[result.best].radius;
    EXPECT_LE(*result.lower_bound, 0.5 * (1.0 + 1e-12));
    EXPECT_GE(found, 0.5 * (1.0 - 1e-12));
    EXPECT_NEAR(found, 0.5, 1e-6 * 0.5);
    // The minor axis is along turn + pi/2 (or its opposite).
    EXPECT_NEAR(std::abs(std::sin(result.samples[result.best].angle - turn)), 1.0, 1e-3);
  }
}

TEST(RadialSearch, PolygonWithFourLocalMinimaFindsTheGlobalOneWithoutMechanismSteps) {
  const Polygon polygon = off_centre_rectangle();
  RadialSearchSettings settings;
  settings.tolerance = 1e-9;
  const auto result = minimise_radius([&](double t) {
    RadialSample s = polygon(t);
    s.bound_angle.reset();  // chords only
    s.bound_radius.reset();
    return s;
  }, settings);
  ASSERT_TRUE(result.converged) << result.stop;
  EXPECT_NEAR(result.samples[result.best].radius, 0.4, 1e-9);
  EXPECT_NEAR(result.samples[result.best].angle, kPi, 1e-6);
  EXPECT_LE(*result.lower_bound, 0.4 + 1e-12);
}

TEST(RadialSearch, SupportingLinesReachAPolygonsMinimumInAFewSamples) {
  const Polygon polygon = off_centre_rectangle();
  const auto result = minimise_radius(polygon, {});
  ASSERT_TRUE(result.converged) << result.stop;
  EXPECT_DOUBLE_EQ(result.samples[result.best].radius, 0.4);
  // The 8 initial directions already include pi; at most a few more to close the bracket.
  EXPECT_LE(result.samples.size(), 12u);
}

TEST(RadialSearch, NeverAboveADenseSamplingOnManyRandomPolygons) {
  // Random convex polygons around the origin: the search must not stop above the smallest of
  // 3600 evenly spaced evaluations (minus the tolerance), and its bracket must hold the truth.
  unsigned state = 12345u;
  auto uniform = [&state]() {
    state = state * 1664525u + 1013904223u;
    return (state >> 8) / 16777216.0;
  };
  for (int trial = 0; trial < 50; ++trial) {
    Polygon polygon;
    const int sides = 3 + static_cast<int>(uniform() * 9);
    for (int i = 0; i < sides; ++i) {
      polygon.normal_angle_and_distance.push_back({2.0 * kPi * (i + 0.8 * uniform()) / sides, 0.2 + uniform()});
    }
    const auto result = minimise_radius(polygon, {});
    ASSERT_GE(result.best, 0);
    double dense = kInf;
    for (int k = 0; k < 3600; ++k) dense = std::min(dense, polygon(2.0 * kPi * k / 3600).radius);
    const double found = result.samples[result.best].radius;
    EXPECT_LE(found, dense * (1.0 + 1e-3)) << "trial " << trial;
    ASSERT_TRUE(result.lower_bound);
    EXPECT_LE(*result.lower_bound, polygon.smallest() * (1.0 + 1e-12)) << "trial " << trial;
    EXPECT_GE(found, polygon.smallest() * (1.0 - 1e-12)) << "trial " << trial;
  }
}

TEST(RadialSearch, UnboundedDirectionsBoundTheSectorsByRays) {
  // A half-plane y <= 1: r is infinite for directions with y <= 0, and the minimum 1 is at pi/2.
  const Polygon half_plane{{{0.5 * kPi, 1.0}}};
  RadialSearchSettings settings;
  settings.tolerance = 1e-8;
  const auto result = minimise_radius([&](double t) {
    RadialSample s = half_plane(t);
    s.bound_angle.reset();
    s.bound_radius.reset();
    return s;
  }, settings);
  ASSERT_TRUE(result.converged) << result.stop;
  EXPECT_NEAR(result.samples[result.best].radius, 1.0, 1e-8);
  // The whole plane: unbounded everywhere.
  const auto everywhere = minimise_radius([](double t) { return sample(t, kInf); }, {});
  EXPECT_EQ(everywhere.best, -1);
  EXPECT_TRUE(everywhere.converged);
  EXPECT_EQ(everywhere.samples.size(), 8u);
}

TEST(RadialSearch, StopsAtTheSampleLimitWithAnHonestBracket) {
  RadialSearchSettings settings;
  settings.tolerance = 1e-12;
  settings.max_samples = 10;
  const auto result = minimise_radius([](double t) { return ellipse(3.0, 1.0, 0.2, t); }, settings);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.samples.size(), 10u);
  ASSERT_TRUE(result.lower_bound);
  EXPECT_LE(*result.lower_bound, 1.0);
  EXPECT_NE(result.stop.find("10 evaluations"), std::string::npos) << result.stop;
}

TEST(RadialSearch, AnUnusableSampleStopsTheSearchAndSaysWhy) {
  int calls = 0;
  const auto result = minimise_radius([&](double t) {
    RadialSample s = sample(t, 1.0);
    if (++calls == 3) {
      s.usable = false;
      s.why_unusable = "solver failed";
    }
    return s;
  }, {});
  EXPECT_TRUE(result.failed);
  EXPECT_EQ(result.samples.size(), 3u);
  EXPECT_EQ(result.stop, "solver failed");
  // A negative radius means the origin is outside: not a set this search handles.
  const auto outside = minimise_radius([](double t) { return sample(t, -0.1); }, {});
  EXPECT_TRUE(outside.failed);
}

TEST(RadialSearch, WithoutConvexityNoBracketIsClaimed) {
  RadialSearchSettings settings;
  settings.convex = false;
  const auto result = minimise_radius([](double t) { return ellipse(2.0, 1.0, 0.0, t); }, settings);
  EXPECT_FALSE(result.lower_bound.has_value());
  EXPECT_FALSE(result.converged);
}

}  // namespace
