// The largest value of a concave function over the directions of a circular cone, from values and
// supergradients, with a certified bracket. Knows nothing about masonry: the worst settlement
// direction (analysis/worst_settlement.hpp) is one use.
//
// Let f be concave and positively homogeneous of degree 1 on R^3 and w a linear functional
// positive on the cone C = {d : angle(d, axis) <= half_angle}. The ratio f(d) / (w . d) does not
// depend on the length of d, so its largest value over the directions of C is the largest value
// of f over the slice P = {d in C : w . d = 1}, a convex set (a disc or an ellipse) on which f is
// concave. Every evaluation at a direction d_k returns the ratio and a supergradient g_k, with
// f(d) <= g_k . d for every d (for a function that is a minimum of linear ones, the minimiser at
// d_k). Then min_k g_k . d bounds f from above on P, and its largest value over P (a small
// second-order cone program, solved by rbla::conic) is an upper bound U of the maximum; the best
// ratio evaluated is a lower bound L. The search evaluates where U is attained until
// U - L <= tolerance * U: Kelley's cutting-plane method (Kelley, J. SIAM 8 (1960) 703-712) on a
// two-dimensional convex set, here with a certified stop.
#pragma once

#include <Eigen/Core>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rbla::analysis {

struct ConeSample {
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  ///< unit
  double ratio = 0.0;                                   ///< f(d) / (w . d)
  /// f(d') <= supergradient . d' for every d' (for a concave f); the search needs one from every
  /// sample and stops at the first without.
  std::optional<Eigen::Vector3d> supergradient;
  /// False: the evaluation failed; the search stops there and says why.
  bool usable = true;
  std::string why_unusable;
};

struct ConeSearchSettings {
  /// Directions on the cone's rim evaluated first, after its axis (at least 3).
  int rim_samples = 6;
  /// Stop when U - L <= tolerance * U (relative, dimensionless).
  double tolerance = 1e-3;
  /// Evaluations in all, the first ones included.
  int max_samples = 30;
  /// rad: a direction closer than this to an evaluated one is not evaluated again.
  double angle_resolution = 1e-6;
  /// False when f is not known to be concave: the planes then only guide the search (it stops
  /// where their envelope closes on the best value) and no upper bound is claimed.
  bool concave = true;
};

struct ConeMaximum {
  std::vector<ConeSample> samples;  ///< in evaluation order
  int best = -1;                    ///< index into samples of the largest ratio; -1 if none
  std::optional<double> upper_bound;  ///< certified (concave f, every sample usable)
  bool converged = false;             ///< U - L reached the tolerance
  std::string stop;                   ///< why the search stopped, for people
  bool failed = false;                ///< a sample was unusable: `stop` says which and why
};

/// The cone: unit `axis`, `half_angle` in (0, pi/2) rad, and the functional `w` (w . d > 0 on
/// the cone; find_cone_maximum throws std::invalid_argument otherwise).
struct DirectionCone {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double half_angle = 0.5;
  Eigen::Vector3d w = Eigen::Vector3d::UnitZ();
};

/// The smallest value of w . d over the unit directions of the cone: w . axis cos(beta) -
/// |w_perp| sin(beta), with w_perp the part of w normal to the axis.
double smallest_on_cone(const DirectionCone& cone);

/// Maximises the ratio over the cone's directions; `evaluate` is called once per direction.
ConeMaximum find_cone_maximum(const std::function<ConeSample(const Eigen::Vector3d& direction)>& evaluate,
                              const DirectionCone& cone, const ConeSearchSettings& settings = {});

}  // namespace rbla::analysis
