// Interface detection: which faces of different blocks touch, and the polygon they share.
#pragma once

#include "geometry/face_patches.hpp"
#include "model/model.hpp"

#include <Eigen/Core>

#include <utility>
#include <vector>

namespace rbla::geometry {

/// Right-handed local frame (n, t1, t2) with n x t1 = t2. t1 is the projection on the interface
/// plane of the global axis least aligned with n (ties go to x, then y), so axis-aligned
/// interfaces get axis-aligned tangents: an axis-aligned friction pyramid is then exact for
/// in-plane loads on walls symmetric about their mid-plane (docs/method.md, "An exact check for in-plane loads").
void local_frame(const Eigen::Vector3d& normal, Eigen::Vector3d& tangent1, Eigen::Vector3d& tangent2);

/// The tolerances detection applies, derived once from the model's settings.
struct DetectionTolerances {
  bool per_joint = true;        ///< each joint's distance tolerance from its size
  double joint_fraction = 0.0;  ///< of the smaller face's diameter (per_joint)
  double fixed_distance = 0.0;  ///< m, for every joint (!per_joint)
  double angle_degrees = 0.0;
  /// m, the widest clearance (the nearest a joint's faces come) that still closes (per_joint):
  /// 30 mm at the default joint_fraction, in proportion to it otherwise.
  double clearance_limit = 0.0;
  /// The distance tolerance (m) of a joint between faces of diameters size_a and size_b.
  double distance(double size_a, double size_b) const;
  /// The limits for merging split faces of one block, consistent with the joint tolerances.
  PatchLimits patch_limits() const;
  /// From model.detection: a fixed tolerance when the model gives distance_tolerance (absolute)
  /// or relative_tolerance (of the bounding-box diagonal), else per joint.
  static DetectionTolerances of(const model::Model& model);
};

/// A rejected face pair is a near miss when its distance and its angle are both within this
/// factor of the tolerances it missed.
inline constexpr double kNearMissFactor = 3.0;

/// Alias kept for PrepareReport: the counts of a detection run.
using DetectionStats = model::DetectionSummary;

struct DetectionOutcome {
  std::vector<model::ContactInterface> interfaces;
  std::vector<model::NearMiss> near_misses;  ///< the closest first, at most settings.max_near_misses
  model::DetectionSummary summary;
};

/// Finds the contact interfaces between blocks whose geometry has been prepared (volumes,
/// centroids), on the blocks' face patches (face_patches(): split coplanar faces merged, warped
/// faces replaced by their fitted planes). Two patches of different blocks touch where
///  - their outward normals are opposite within the angle tolerance,
///  - their outlines, projected on the mid-plane (normal n_a - n_b), overlap by more than
///    `min_area_fraction` of the smaller patch (each overlap component is one interface, so a
///    block pair may have several), and
///  - over that overlap the two fitted planes are nowhere further apart, along n, than the
///    joint's distance tolerance (DetectionTolerances::distance).
/// The contact polygon lies on the plane with normal n halfway between the two fitted planes at
/// the overlap's centroid. Pairs of supports are skipped: no unknowns act between them. Pairs that
/// fail within kNearMissFactor of both tolerances are reported as near misses.
/// Broad phase: sweep and prune of the blocks' bounding boxes along the longest axis of the model
/// (Baraff 1992), so a wall of N blocks costs O(N log N + contacts), not O(N^2).
/// `skip_pairs` (a < b) are block pairs the caller already has interfaces for.
DetectionOutcome detect_interfaces(const model::Model& model, const std::vector<std::pair<int, int>>& skip_pairs);

/// The unit normal, pointing from block a into block b, of a contact polygon the model gives
/// (normal n and centroid c from the polygon): the outward normal of the face of `a` the polygon
/// lies on (a face whose normal is within 10 degrees of +-n, whose plane passes within
/// `tolerance` of c and whose outline contains c), oriented like n. Interlocking blocks touch on
/// faces whose normals point towards their own centroid's side, so the centroids alone do not
/// tell (COMPAS stores such contacts for its concave pieces); they decide only when no face of
/// `a` carries the polygon.
Eigen::Vector3d given_interface_normal(const model::Model& model, int a, int b, const Eigen::Vector3d& n,
                                       const Eigen::Vector3d& c, double tolerance);

/// Min, median and max of `values` (reordered).
model::Spread spread_of(std::vector<double>& values);

}  // namespace rbla::geometry
