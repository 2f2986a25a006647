#include "analysis/threshold_search.hpp"

#include "analysis/text.hpp"
#include <algorithm>
#include <cmath>

namespace rbla::analysis {
namespace {

/// The bracket's two ends with the values the chord uses (Illinois-scaled).
struct Bracket {
  double lo = 0.0, hi = 0.0;
  std::optional<double> g_lo, g_hi;
  int kept_lo = 0, kept_hi = 0;  ///< how many steps in a row each end stayed
};

/// The bisection point; over a wide bracket, halve the ratio rather than the difference.
double middle(const Bracket& b) { return b.hi > 4.0 * b.lo ? std::sqrt(b.lo * b.hi) : 0.5 * (b.lo + b.hi); }

/// The next x, and whether the chord's zero was moved in from next to an end (+1 the upper end,
/// -1 the lower one).
struct Chord {
  double x = 0.0;
  int clamped_at = 0;
};

/// The chord's zero, kept at least `step` inside the bracket: the end the chord converges to is
/// then crossed once the root is that close, which closes the bracket (as Dekker's and Brent's
/// methods take at least a tolerance-sized step).
Chord next_x(const Bracket& b, double step) {
  if (!b.g_lo || !b.g_hi || !std::isfinite(*b.g_lo) || !std::isfinite(*b.g_hi) || *b.g_hi <= *b.g_lo) return {middle(b), 0};
  const double x = b.lo + (b.hi - b.lo) * (-*b.g_lo) / (*b.g_hi - *b.g_lo);
  if (!std::isfinite(x) || b.hi - b.lo <= 2.0 * step) return {middle(b), 0};
  if (x > b.hi - step) return {b.hi - step, +1};
  if (x < b.lo + step) return {b.lo + step, -1};
  return {x, 0};
}

void update(Bracket& b, const ThresholdSample& s) {
  if (s.passes) {
    b.hi = s.x;
    b.g_hi = s.value;
    b.kept_hi = 0;
    if (++b.kept_lo >= 2 && b.g_lo) *b.g_lo *= 0.5;
  } else {
    b.lo = s.x;
    b.g_lo = s.value;
    b.kept_lo = 0;
    if (++b.kept_hi >= 2 && b.g_hi) *b.g_hi *= 0.5;
  }
}

}  // namespace

namespace {

/// One search: its samples so far, and its two phases (bracketing, then narrowing).
class Search {
 public:
  Search(const std::function<ThresholdSample(double x)>& evaluate, const ThresholdSettings& settings)
      : evaluate_(evaluate), settings_(settings) {}

  Threshold run() {
    if (bracket()) narrow();
    return std::move(out_);
  }

 private:
  /// Evaluates at x and records it; false when the evaluation was unusable (the search ends).
  bool take(double x) {
    ThresholdSample s = evaluate_(x);
    s.x = x;
    out_.samples.push_back(s);
    if (!s.usable) {
      out_.outcome = ThresholdOutcome::Failed;
      out_.stop = s.why_unusable;
      return false;
    }
    if (s.passes && (!out_.upper || x < *out_.upper)) out_.upper = x;
    if (!s.passes && (!out_.lower || x > *out_.lower)) out_.lower = x;
    return true;
  }

  bool out_of_samples() const { return static_cast<int>(out_.samples.size()) >= settings_.max_samples; }

  /// The range's far end first: a test that passes (or fails) everywhere is common (a wall of
  /// level courses stands with any friction) and is settled in two evaluations. Then halve from a
  /// passing start, double from a failing one. True when a bracket was found.
  bool bracket() {
    double x = settings_.start;
    if (!take(x)) return false;
    const bool first_passes = out_.samples.back().passes;
    const double far = first_passes ? settings_.min_x : settings_.max_x;
    if (far != x && !take(far)) return false;
    if (out_.samples.back().passes == first_passes) {
      out_.outcome = first_passes ? ThresholdOutcome::PassesAtMinimum : ThresholdOutcome::FailsAtMaximum;
      out_.stop = (first_passes ? "passes at every " + settings_.name + " tried, down to "
                                : "fails at every " + settings_.name + " tried, up to ") + format(far);
      return false;
    }
    for (;;) {
      const double next = first_passes ? 0.5 * x : 2.0 * x;
      if ((first_passes ? next <= settings_.min_x : next >= settings_.max_x) || out_of_samples()) break;
      x = next;
      if (!take(x)) return false;
      if (out_.samples.back().passes != first_passes) break;
    }
    if (!out_.lower || !out_.upper) {
      out_.outcome = ThresholdOutcome::Failed;
      out_.stop = "no bracket within " + std::to_string(settings_.max_samples) + " evaluations";
      return false;
    }
    return true;
  }

  /// Narrows the bracket to the tolerance by chords, with bisections where they would creep.
  void narrow() {
    Bracket b;
    b.lo = *out_.lower;
    b.hi = *out_.upper;
    for (const ThresholdSample& s : out_.samples) {
      if (s.x == b.lo) b.g_lo = s.value;
      if (s.x == b.hi) b.g_hi = s.value;
    }
    out_.outcome = ThresholdOutcome::Bracketed;
    // A chord step clamped next to an end is meant to cross the root; when it does not, the
    // chord points at that end for another reason (g flat there): bisect until a sample lands on
    // the other side of the root (+1: until one passes, -1: until one fails).
    int bisect_until = 0;
    while (b.hi - b.lo > settings_.tolerance * b.hi) {
      if (out_of_samples()) {
        out_.stop = "stopped at " + std::to_string(settings_.max_samples) + " evaluations with the bracket [" +
                    format(b.lo) + ", " + format(b.hi) + "]";
        return;
      }
      const Chord chord = bisect_until != 0 ? Chord{middle(b), 0} : next_x(b, 0.4 * settings_.tolerance * b.hi);
      if (!take(chord.x)) return;
      const int side = out_.samples.back().passes ? +1 : -1;
      if (side == bisect_until) bisect_until = 0;
      if (chord.clamped_at == side) bisect_until = -side;
      update(b, out_.samples.back());
    }
    out_.converged = true;
    out_.stop = "bracketed within the tolerance: [" + format(b.lo) + ", " + format(b.hi) + "]";
  }

  const std::function<ThresholdSample(double x)>& evaluate_;
  const ThresholdSettings& settings_;
  Threshold out_;
};

}  // namespace

Threshold find_threshold(const std::function<ThresholdSample(double x)>& evaluate, const ThresholdSettings& settings) {
  return Search(evaluate, settings).run();
}

}  // namespace rbla::analysis
