// The faces of a block as detection sees them: neighbouring faces that lie in one plane (an end
// cap or a joint that a mesh export split into triangles) merged into one patch, and every patch
// given its fitted plane, so that faces warped by CAD are compared by their planes.
#pragma once

#include "model/model.hpp"

#include <Eigen/Core>

#include <vector>

namespace rbla::geometry {

/// One face of a block, or several neighbouring faces merged because they lie in one plane.
struct FacePatch {
  std::vector<int> faces;            ///< indices into Block::faces, the largest first
  std::vector<int> outline;          ///< vertex indices of the boundary, counter-clockwise seen from outside
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit outward normal of the fitted plane
  Eigen::Vector3d point = Eigen::Vector3d::Zero();    ///< a point of the fitted plane (outline mean)
  double area = 0.0;                 ///< m^2, the members' areas summed
  double size = 0.0;                 ///< m, diameter: the largest distance between two outline corners
  double max_plane_deviation = 0.0;  ///< m, largest distance of a member vertex from the fitted plane
  Eigen::Vector3d box_min = Eigen::Vector3d::Zero();
  Eigen::Vector3d box_max = Eigen::Vector3d::Zero();
  /// When several faces were merged: each of them as a patch of its own, for pairs the merged
  /// plane does not fit (a face of a finely faceted curve merged with its neighbours).
  std::vector<FacePatch> parts;
};

/// How far neighbouring faces of one block may differ and still be merged.
struct PatchLimits {
  double angle_degrees = 2.5;        ///< between the normals of a face and of the patch so far
  double flatness_fraction = 0.01;   ///< member vertices within this fraction of the patch size of its plane
  double flatness_fixed = -1.0;      ///< m, replaces the fraction when >= 0 (a fixed detection tolerance)
  /// Two triangles sharing an edge are a quad an export split along its diagonal: warped by a few
  /// centimetres, they crease by several degrees (up to 8.6 degrees for warps up to 2.5 cm in the
  /// generated vault `--nu 10 --nv 12 --wave 0.6`), while real facets of a curve are rarely
  /// triangles in pairs. Their looser limits:
  double triangle_pair_angle_degrees = 10.0;
  double triangle_pair_flatness_fraction = 0.03;
  double triangle_pair_flatness_fixed = -1.0;
};

/// The fitted plane of a polygon: Newell's normal (the area vector of the polygon, which for a
/// warped polygon is the normal of the plane its projected area is largest on, independent of
/// where it is split into triangles; Sutherland, Sproull & Schumacker 1974) through the mean of
/// its corners (the least-squares offset for that normal).
void fit_plane(const std::vector<Eigen::Vector3d>& vertices, const std::vector<int>& polygon, Eigen::Vector3d& normal,
               Eigen::Vector3d& point);

/// The largest distance between two corners of `polygon` (its diameter), m.
double polygon_diameter(const std::vector<Eigen::Vector3d>& vertices, const std::vector<int>& polygon);

/// The patches of a block: region growing from the largest face over shared edges, taking a
/// neighbour when its normal is within `limits.angle_degrees` of the patch's and every member
/// vertex stays within the flatness limit of the merged plane (the triangle-pair limits when a
/// single triangle takes its most nearly coplanar neighbouring triangle). A merged patch must have one
/// simple boundary loop (no hole, no pinched vertex); otherwise its faces stay separate.
/// Vertices closer than 1e-9 of the block's size are one vertex (exports repeat them per face).
/// Faces of zero area get no patch.
std::vector<FacePatch> face_patches(const model::Block& block, const PatchLimits& limits);

}  // namespace rbla::geometry
