#include "analysis/radial_search.hpp"
#include "model/angles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

namespace rbla::analysis {
namespace {

using rbla::model::kPi;
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Vec2 {
  double x = 0.0, y = 0.0;
};
Vec2 unit(double angle) { return {std::cos(angle), std::sin(angle)}; }
double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }

/// Angle in [0, 2 pi).
double wrapped(double angle) {
  double t = std::fmod(angle, 2.0 * kPi);
  return t < 0.0 ? t + 2.0 * kPi : t;
}

/// Counter-clockwise angle from a to b, in [0, 2 pi).
double sweep(double a, double b) { return wrapped(b - a); }

/// Indices of the usable samples in counter-clockwise order of their directions.
std::vector<int> by_angle(const std::vector<RadialSample>& samples) {
  std::vector<int> order(samples.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int i, int j) { return samples[i].angle < samples[j].angle; });
  return order;
}

int smallest_radius(const std::vector<RadialSample>& samples) {
  int best = -1;
  for (int i = 0; i < static_cast<int>(samples.size()); ++i) {
    if (std::isfinite(samples[i].radius) && (best < 0 || samples[i].radius < samples[best].radius)) best = i;
  }
  return best;
}

double distance_to_nearest_sample(const std::vector<RadialSample>& samples, double angle) {
  double nearest = kInf;
  for (const RadialSample& s : samples) {
    const double d = sweep(s.angle, angle);
    nearest = std::min(nearest, std::min(d, 2.0 * kPi - d));
  }
  return nearest;
}

/// The next direction: the supporting line of the best sample where it promises a lower radius,
/// else where the lowest sector bound is attained. Empty when nothing is left to try.
struct Candidate {
  double angle = 0.0;
  bool found = false;
};

Candidate mechanism_step(const std::vector<RadialSample>& samples, int best, const RadialSearchSettings& s) {
  const RadialSample& b = samples[best];
  if (!b.bound_angle || !b.bound_radius) return {};
  if (!(*b.bound_radius < b.radius * (1.0 - 0.1 * s.tolerance))) return {};
  const double angle = wrapped(*b.bound_angle);
  if (distance_to_nearest_sample(samples, angle) < s.angle_resolution) return {};
  return {angle, true};
}

struct Sectors {
  double lower = kInf;  ///< min over sectors
  double angle = 0.0;   ///< where it is attained
  double width = 0.0;   ///< of the sector it lies in (rad)
  double start = 0.0;   ///< that sector's first direction
};

Sectors lowest_sector(const std::vector<RadialSample>& samples) {
  const std::vector<int> order = by_angle(samples);
  Sectors out;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const RadialSample& a = samples[order[k]];
    const RadialSample& b = samples[order[(k + 1) % order.size()]];
    const SectorBound bound = sector_lower_bound(a, b);
    if (bound.radius < out.lower) out = {bound.radius, bound.angle, sweep(a.angle, b.angle), a.angle};
  }
  return out;
}

std::string bracket_text(double lower, double upper) {
  std::ostringstream out;
  out.precision(6);
  out << "[" << lower << ", " << upper << "]";
  return out.str();
}

}  // namespace

SectorBound sector_lower_bound(const RadialSample& a, const RadialSample& b) {
  const double width = sweep(a.angle, b.angle);
  const bool a_finite = std::isfinite(a.radius), b_finite = std::isfinite(b.radius);
  if (!a_finite && !b_finite) return {kInf, a.angle + 0.5 * width};
  // The boundary of the hull between the two rays: the line through a finite point P along v (the
  // chord, or the ray parallel to the unbounded direction).
  const Vec2 da = unit(a.angle), db = unit(b.angle);
  const Vec2 p = a_finite ? Vec2{a.radius * da.x, a.radius * da.y} : Vec2{b.radius * db.x, b.radius * db.y};
  Vec2 v = !a_finite ? da : !b_finite ? db : Vec2{b.radius * db.x - p.x, b.radius * db.y - p.y};
  Vec2 n{v.y, -v.x};
  const double length = std::hypot(n.x, n.y);
  const double endpoint = std::min(a.radius, b.radius);
  if (length == 0.0) return {endpoint, a.radius <= b.radius ? a.angle : b.angle};
  n = {n.x / length, n.y / length};
  double h = dot(n, p);
  if (h < 0.0) {
    n = {-n.x, -n.y};
    h = -h;
  }
  // h is the distance from the origin to the line; its foot is at the angle of n.
  const double foot = wrapped(std::atan2(n.y, n.x));
  if (sweep(a.angle, foot) <= width && h < endpoint) return {h, foot};
  return {endpoint, a.radius <= b.radius ? a.angle : b.angle};
}

RadialMinimum minimise_radius(const std::function<RadialSample(double angle)>& evaluate,
                              const RadialSearchSettings& settings) {
  RadialMinimum out;
  const int initial = std::max(3, settings.initial_samples);
  auto take = [&](double angle) {
    RadialSample sample = evaluate(wrapped(angle));
    sample.angle = wrapped(angle);
    if (sample.usable && sample.radius < 0.0) {
      sample.usable = false;
      sample.why_unusable = "the radius is negative: the origin is outside the set";
    }
    out.samples.push_back(sample);
    if (!sample.usable) {
      out.failed = true;
      out.stop = sample.why_unusable;
    }
    return sample.usable;
  };
  for (int k = 0; k < initial; ++k) {
    if (!take(2.0 * kPi * k / initial)) return out;
  }
  for (;;) {
    out.best = smallest_radius(out.samples);
    if (out.best < 0) {
      // The hull of rays in every sector (each narrower than pi) is the whole plane.
      out.converged = settings.convex;
      out.stop = settings.convex ? "unbounded along every direction tried, and so (by convexity) along every direction"
                                 : "unbounded along every direction tried";
      return out;
    }
    const double upper = out.samples[out.best].radius;
    const Sectors sectors = lowest_sector(out.samples);
    const double lower = std::min(sectors.lower, upper);
    if (settings.convex) out.lower_bound = lower;
    if (upper - lower <= settings.tolerance * upper) {
      out.converged = settings.convex;
      out.stop = settings.convex ? "the bracket " + bracket_text(lower, upper) + " is within the tolerance"
                                 : "the sampled directions agree within the tolerance (no certified bracket: the set is not known to be convex)";
      return out;
    }
    if (static_cast<int>(out.samples.size()) >= settings.max_samples) {
      out.stop = "stopped at " + std::to_string(settings.max_samples) + " evaluations" +
                 (settings.convex ? " with the bracket " + bracket_text(lower, upper) : std::string());
      return out;
    }
    Candidate next = mechanism_step(out.samples, out.best, settings);
    if (!next.found) {
      double angle = sectors.angle;
      const double from_start = sweep(sectors.start, angle);
      if (std::min(from_start, sectors.width - from_start) < settings.angle_resolution) {
        angle = sectors.start + 0.5 * sectors.width;
      }
      if (sectors.width < 2.0 * settings.angle_resolution) {
        out.stop = "the directions left to try are closer than the angle resolution";
        return out;
      }
      next = {angle, true};
    }
    if (!take(next.angle)) return out;
  }
}

}  // namespace rbla::analysis
