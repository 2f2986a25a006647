// Geometry of one polyhedral block: face normals and areas, volume and centroid, closure.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace rbla::geometry {

using Vec3 = Eigen::Vector3d;
using FaceList = std::vector<std::vector<int>>;

/// Area vector, centroid and flatness of one planar face.
struct FaceGeometry {
  Vec3 area_vector = Vec3::Zero();  // Newell's vector: |.| = area, direction = outward normal
  Vec3 normal = Vec3::UnitZ();      // unit outward normal (right-hand rule on the vertex order)
  double area = 0.0;
  Vec3 centroid = Vec3::Zero();     // area centroid
  double max_plane_deviation = 0.0; // largest distance of a vertex from the face's plane
};

/// Newell's method: A = 1/2 sum_i (v_i - o) x (v_{i+1} - o), exact for any planar simple polygon,
/// convex or not (Newell 1972; Sutherland, Sproull & Schumacker 1974). The centroid is the
/// area-weighted sum of the fan triangles' centroids, with signed areas along the normal, so it too
/// is exact for non-convex faces. The fan is from the mean of the corners (o): for a warped face it
/// is then the same whichever corner the list starts at (from the first corner, rolling the list
/// of a warped vault face moved its block's centroid by 12.5 mm).
FaceGeometry face_geometry(const std::vector<Vec3>& vertices, const std::vector<int>& face);

struct MassProperties {
  double volume = 0.0;           // signed: negative when the faces point inward
  Vec3 centroid = Vec3::Zero();
  double surface_area = 0.0;
};

/// Volume and centroid by the divergence theorem: the closed surface is split into signed
/// tetrahedra (r, a, b, c) over a fan triangulation of each face from the mean of its corners (the
/// same surface whichever corner a warped face's list starts at), with r a reference point inside
/// the block's bounding box (which keeps round-off small for models far from the origin):
///   V = sum 1/6 (a-r).((b-r) x (c-r)),   g = r + sum V_t (a+b+c-3r)/4 / V.
/// Exact for closed, consistently oriented surfaces with planar faces, convex or not
/// (e.g. Zhang & Chen 2001, "Efficient feature extraction for 2D/3D objects in mesh representation").
MassProperties mass_properties(const std::vector<Vec3>& vertices, const FaceList& faces);

/// Vertices closer than `tol` are one vertex, and so are chains of them (single linkage): maps
/// every vertex to the smallest index of its class. O(n log n): the vertices are sorted into grid
/// cells of side h = tol / 1.75. A cell's diagonal, sqrt(3) h, is below tol, so a cell's vertices
/// are one class without a test; two vertices within tol lie at most ceil(1.75) = 2 cells apart
/// along each axis, so each cell is compared with the 62 cells ahead of it in a 5x5x5 block (once
/// a pair is joined, the two cells are one class and the comparison stops). A sweep along one
/// axis, as before, was quadratic when many vertices share a coordinate (a finely meshed face).
/// When tol is below 2^-50 of the vertices' extent the cells are made coarser and tested pairwise.
std::vector<int> merge_close_vertices(const std::vector<Vec3>& vertices, double tol);

/// Result of checking that the faces close a volume with a consistent orientation.
struct ClosureCheck {
  bool closed = true;        // every edge is matched by an edge of opposite direction
  bool consistent = true;    // no edge is used twice in the same direction
  bool needed_t_junction_split = false;  // matched only after splitting edges at vertices on them
  std::string detail;        // the first offending edge, in vertex indices of the input
};

/// Corners of one block closer than this fraction of its bounding-box diagonal are one vertex: an
/// export that writes each face with copies of its own (a triangle soup) rounds them apart by far
/// less. The closure check and the merging of split faces (face_patches.cpp) weld by it alike,
/// with merge_close_vertices. The merging had a tolerance of 1e-9 and a welding of its own: copies
/// 1e-9 of the block apart stayed apart, and a wall's 344 interfaces became 1242, its cracked
/// joints 130 became 444 (same α).
inline constexpr double kVertexWeldRelative = 1e-6;

/// Combinatorial closure after merging vertices closer than `tol`: each directed edge (u,v) must be
/// matched by (v,u). CAD meshes often have T-junctions (a vertex of one face lying on an edge of
/// another); when the plain check fails, edges are split at the vertices lying on them and the
/// check is repeated.
ClosureCheck check_closure(const std::vector<Vec3>& vertices, const FaceList& faces, double tol);

}  // namespace rbla::geometry
