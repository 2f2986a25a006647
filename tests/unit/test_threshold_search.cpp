// The bracketed threshold of a monotone test (analysis/threshold_search.hpp) on functions whose
// crossing is known: with and without values, beyond the range, failed evaluations.
#include "analysis/threshold_search.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {

using rbla::analysis::find_threshold;
using rbla::analysis::ThresholdOutcome;
using rbla::analysis::ThresholdSample;
using rbla::analysis::ThresholdSettings;

ThresholdSample with_value(double x, double g) {
  ThresholdSample s;
  s.x = x;
  s.value = g;
  s.passes = g >= 0.0;
  return s;
}

ThresholdSample boolean(double x, bool passes) {
  ThresholdSample s;
  s.x = x;
  s.passes = passes;
  return s;
}

TEST(ThresholdSearch, ValuesFindTheCrossingOfACurvedFunctionFastAndBracketIt) {
  // g(x) = min(x, 0.5) - 0.3 crosses at 0.3 (the load multiplier of a block, alpha = min(mu, b/h),
  // against a target of 0.3); and a smooth convex curve crossing at sqrt(2).
  ThresholdSettings settings;
  settings.tolerance = 1e-9;
  const auto kink = find_threshold([](double x) { return with_value(x, std::min(x, 0.5) - 0.3); }, settings);
  ASSERT_EQ(kink.outcome, ThresholdOutcome::Bracketed) << kink.stop;
  EXPECT_TRUE(kink.converged);
  EXPECT_LE(*kink.lower, 0.3);
  EXPECT_GE(*kink.upper, 0.3);
  EXPECT_NEAR(*kink.upper, 0.3, 1e-9);
  const auto smooth = find_threshold([](double x) { return with_value(x, x * x - 2.0); }, settings);
  ASSERT_TRUE(smooth.converged) << smooth.stop;
  EXPECT_NEAR(*smooth.upper, std::sqrt(2.0), 1e-8);
  // Illinois: superlinear, far fewer samples than the ~30 bisections of 1e-9.
  EXPECT_LE(smooth.samples.size(), 15u);
}

TEST(ThresholdSearch, APlateauJustAboveTheTargetDoesNotStallTheChord) {
  // A column's load multiplier min(mu, b/H), mu = 0.6 x and b/H = 0.125, against targets just
  // below that plateau: at the passing end g is flat and tiny, so the chord points at that end
  // and, without the bisection guard, crept by 4e-4 of x per sample to the 40-sample cap.
  for (const double target : {0.124999, 0.1249999, 0.125 - 1e-12}) {
    ThresholdSettings settings;
    const auto t = find_threshold([&](double x) { return with_value(x, std::min(0.6 * x, 0.125) - target); }, settings);
    ASSERT_TRUE(t.converged) << target << ": " << t.stop;
    EXPECT_LE(0.6 * *t.lower, target);
    EXPECT_GE(0.6 * *t.upper, target);
    EXPECT_LE(t.samples.size(), 20u) << target;
  }
}

TEST(ThresholdSearch, WithoutValuesItBisects) {
  ThresholdSettings settings;
  settings.tolerance = 1e-3;
  const auto t = find_threshold([](double x) { return boolean(x, x >= 0.3639702); }, settings);
  ASSERT_TRUE(t.converged) << t.stop;
  EXPECT_LT(*t.lower, 0.3639702);
  EXPECT_GE(*t.upper, 0.3639702);
  EXPECT_LE(*t.upper - *t.lower, 1e-3 * *t.upper);
}

TEST(ThresholdSearch, ReportsWhenItPassesOrFailsEverywhereInRange) {
  ThresholdSettings settings;
  settings.max_x = 10.0;
  const auto never = find_threshold([](double x) { return with_value(x, -1.0); }, settings);
  EXPECT_EQ(never.outcome, ThresholdOutcome::FailsAtMaximum);
  EXPECT_DOUBLE_EQ(*never.lower, 10.0);  // the range's end itself was tried
  EXPECT_FALSE(never.upper.has_value());
  const auto always = find_threshold([](double x) { return boolean(x, true); }, settings);
  EXPECT_EQ(always.outcome, ThresholdOutcome::PassesAtMinimum);
  EXPECT_DOUBLE_EQ(*always.upper, settings.min_x);
}

TEST(ThresholdSearch, AFailedEvaluationStopsTheSearchWithItsReason) {
  int calls = 0;
  const auto t = find_threshold([&](double x) {
    ThresholdSample s = boolean(x, x > 0.1);
    if (++calls == 3) {
      s.usable = false;
      s.why_unusable = "numerical failure";
    }
    return s;
  });
  EXPECT_EQ(t.outcome, ThresholdOutcome::Failed);
  EXPECT_EQ(t.stop, "numerical failure");
  EXPECT_EQ(t.samples.size(), 3u);
}

TEST(ThresholdSearch, InfiniteValuesFallBackToBisection) {
  ThresholdSettings settings;
  settings.tolerance = 1e-6;
  const auto t = find_threshold([](double x) {
    return x >= 0.7 ? with_value(x, std::numeric_limits<double>::infinity()) : with_value(x, -1.0);
  }, settings);
  ASSERT_TRUE(t.converged) << t.stop;
  EXPECT_NEAR(*t.upper, 0.7, 1e-6);
}

}  // namespace
