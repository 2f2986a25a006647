// The smallest radius of a convex set of the plane around a point inside it, from evaluations of
// its radial function only, with a certified bracket. Knows nothing about masonry: the worst
// load direction (analysis/worst_direction.hpp) is one use.
//
// Let S be a closed convex set of R^2 with the origin inside, and r(t) = max{ s : s d(t) in S },
// d(t) = (cos t, sin t), its radial function (+infinity along an unbounded ray). Every evaluated
// point r(t_k) d(t_k) lies on the boundary of S, so by convexity the polygon through consecutive
// evaluated points (a chord, or a ray where r is infinite) lies inside S: along any direction
// between two evaluated ones, r is at least the radius of that chord. The minimum of the chord
// radius over each sector is a closed form (the distance from the origin to the chord, when its
// foot falls in the sector), so min over sectors is a lower bound L of min r, and the smallest
// evaluated radius an upper bound U. The search evaluates where L is attained until
// U - L <= tolerance * U: the outer-approximation ("sandwich") scheme for convex curves (see
// Rote, Computing 48 (1992) 337-361, for its convergence on smooth and polygonal boundaries).
//
// A sample may also carry a supporting line of S found with it (for a load direction, the
// collapse mechanism): the point of that line nearest the origin, at `bound_angle` and
// `bound_radius`, bounds min r from above, and the search evaluates there first when that
// promises a lower radius (a descent step that needs no convexity).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rbla::analysis {

struct RadialSample {
  double angle = 0.0;   ///< rad, in [0, 2 pi)
  double radius = 0.0;  ///< r(angle); +infinity when the ray never leaves S
  /// Nearest point of a supporting line through r(angle) d(angle), when known (rad, radius).
  std::optional<double> bound_angle;
  std::optional<double> bound_radius;
  /// False: the evaluation failed or left the premises (radius below zero: origin outside S);
  /// the search stops there and says why.
  bool usable = true;
  std::string why_unusable;
};

struct RadialSearchSettings {
  /// Evenly spaced first directions; at least 3, so that every sector is narrower than pi.
  int initial_samples = 8;
  /// Stop when U - L <= tolerance * U (relative, dimensionless).
  double tolerance = 1e-3;
  /// Evaluations in all, initial ones included.
  int max_samples = 40;
  /// rad: directions closer than this to an evaluated one are not evaluated again.
  double angle_resolution = 1e-7;
  /// False when S is not known to be convex: the chords then only guide the search, and no
  /// lower bound is claimed.
  bool convex = true;
};

struct RadialMinimum {
  std::vector<RadialSample> samples;  ///< in evaluation order
  int best = -1;                      ///< index into samples of the smallest radius; -1 if none finite
  /// Certified lower bound of min r (convex sets only, when every sample was usable).
  std::optional<double> lower_bound;
  bool converged = false;  ///< U - L reached the tolerance (convex) ...
  std::string stop;        ///< why the search stopped, for people
  bool failed = false;     ///< a sample was unusable: `stop` says which and why
};

/// Minimises r over all directions; `evaluate` is called once per direction tried.
RadialMinimum minimise_radius(const std::function<RadialSample(double angle)>& evaluate,
                              const RadialSearchSettings& settings = {});

/// The lower bound of r between two evaluated directions a and b (b counter-clockwise from a, by
/// less than pi) and where it is attained: the chord (or ray) through their boundary points.
struct SectorBound {
  double radius = 0.0;
  double angle = 0.0;
};
SectorBound sector_lower_bound(const RadialSample& a, const RadialSample& b);

}  // namespace rbla::analysis
