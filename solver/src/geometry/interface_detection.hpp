// Interface detection: which faces of different blocks touch, and the polygon they share.
#pragma once

#include "model/model.hpp"

#include <Eigen/Core>

#include <vector>

namespace rbla::geometry {

/// Right-handed local frame (n, t1, t2) with n x t1 = t2. t1 is the projection on the interface
/// plane of the global axis least aligned with n (ties go to x, then y), so axis-aligned
/// interfaces get axis-aligned tangents: an axis-aligned friction pyramid is then exact for
/// in-plane loads on walls symmetric about their mid-plane (METHOD.md, "A free exact oracle").
void local_frame(const Eigen::Vector3d& normal, Eigen::Vector3d& tangent1, Eigen::Vector3d& tangent2);

struct DetectionStats {
  std::size_t candidate_block_pairs = 0;  // pairs whose boxes overlap (broad phase)
  std::size_t face_pairs_tested = 0;      // opposite, coplanar face pairs clipped (narrow phase)
  std::size_t interfaces_found = 0;
};

/// Finds the contact interfaces between blocks whose geometry has been prepared (volumes,
/// centroids). Two faces touch when their outward normals are opposite within
/// `settings.angle_tolerance_degrees`, their planes are within `tolerance` (m) of each other, and
/// their polygons, projected on the mid-plane, overlap by more than `min_area_fraction` of the
/// smaller face. Each overlap component becomes one interface (so a block pair may have several).
/// Pairs of supports are skipped: no unknowns act between them.
/// Broad phase: sweep and prune of the blocks' bounding boxes along the longest axis of the model
/// (Baraff 1992), so a wall of N blocks costs O(N log N + contacts), not O(N^2).
/// `skip_pair(a, b)` (a < b) lets the caller exclude pairs it already has interfaces for.
std::vector<model::ContactInterface> detect_interfaces(const model::Model& model, double tolerance,
                                                        const model::DetectionSettings& settings,
                                                        const std::vector<std::pair<int, int>>& skip_pairs,
                                                        DetectionStats* stats = nullptr);

}  // namespace rbla::geometry
