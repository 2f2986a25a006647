// The smallest x > 0 at which a monotone test passes, bracketed: x_lo fails, x_hi passes,
// x_hi - x_lo <= tolerance * x_hi. Knows nothing about masonry: the critical friction
// (analysis/critical_friction.hpp) is one use.
//
// The test must be monotone (fails below some x*, passes above it): then every failing sample is
// a certified lower bound of x* and every passing one an upper bound. When the test comes with a
// value g(x) that crosses zero at x* (pass <=> g >= 0), the next x is where the chord between the
// bracket's ends crosses zero, with the Illinois modification (Dowell & Jarratt, BIT 11 (1971)
// 168-174: halve the value kept at an end retained twice) so that both ends move; otherwise, and
// whenever a value is missing, bisection. The chord's zero is kept a small step inside the bracket
// (as Dekker's and Brent's methods step at least a tolerance), so that a zero next to an end
// crosses the root; when it does not cross, g is flat at that end (a load multiplier on a plateau
// just above the target) and the chord would creep by that small step: the search bisects until
// a sample lands on the other side of the root.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rbla::analysis {

struct ThresholdSample {
  double x = 0.0;
  bool passes = false;
  /// g(x), when the test has one: pass <=> g >= 0. +infinity is allowed (passes by far).
  std::optional<double> value;
  /// False: the evaluation failed; the search stops and says why.
  bool usable = true;
  std::string why_unusable;
};

struct ThresholdSettings {
  double start = 1.0;       ///< first x tried
  double tolerance = 1e-3;  ///< stop when x_hi - x_lo <= tolerance * x_hi (relative)
  double min_x = 1e-4;      ///< below this a passing test is reported as passing everywhere tried
  double max_x = 1e3;       ///< above this a failing test is reported as failing everywhere tried
  int max_samples = 40;
  /// What x is, in the stop messages ("fails at every factor tried, up to 2").
  std::string name = "value";
};

enum class ThresholdOutcome {
  Bracketed,         ///< x_lo fails, x_hi passes
  PassesAtMinimum,   ///< passes even at min_x: x* <= min_x
  FailsAtMaximum,    ///< fails even at max_x: x* > max_x, if it exists
  Failed,            ///< an evaluation was unusable
};

struct Threshold {
  ThresholdOutcome outcome = ThresholdOutcome::Failed;
  std::vector<ThresholdSample> samples;  ///< in evaluation order
  std::optional<double> lower;           ///< largest failing x
  std::optional<double> upper;           ///< smallest passing x
  bool converged = false;                ///< bracketed within the tolerance
  std::string stop;                      ///< why the search stopped, for people
};

Threshold find_threshold(const std::function<ThresholdSample(double x)>& evaluate, const ThresholdSettings& settings = {});

}  // namespace rbla::analysis
