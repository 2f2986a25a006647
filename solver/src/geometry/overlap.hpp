// Blocks whose interiors overlap: two blocks may touch along faces, and CAD exports leave tiny
// overlaps at joints, but two blocks occupying the same space is a modelling error that the
// analysis would otherwise accept ("2 blocks move").
#pragma once

#include "model/model.hpp"

#include <vector>

namespace rbla::geometry {

struct BlockOverlap {
  int block_a = -1, block_b = -1;  ///< block_a < block_b
  /// m^3 the two blocks have in common; NaN when it was not computed (two non-convex blocks of
  /// thousands of faces whose hulls overlap deeply: too many tetrahedron pairs).
  double volume = 0.0;
  /// m: the smallest overlap of their projections over the face normals of both, an upper bound
  /// of how far one must move to free the other (exact for convex blocks meeting face to face;
  /// for a non-convex block only a bound of its convex hull's).
  double depth = 0.0;
  bool convex = true;  ///< both blocks convex
  /// When the volume was not computed: the centroid of one block lies inside the other (an
  /// overlap for certain), from the winding number of its surface.
  bool centroid_inside = false;
};

/// An overlap whose volume exceeds this fraction of the smaller block is an error. 1 %: a 1 m
/// cube may lose a 1 cm slab to a neighbour and still count as a CAD imperfection; a millimetre
/// overlap at the joints of metre blocks is 0.1 %. Smaller overlaps are a warning when their
/// volume exceeds the tolerance times V^(2/3) of the smaller block (a slab as deep as the
/// tolerance over a face of a cube of that volume); below that they are what the tolerance
/// already accepts at a joint (and what rounding leaves of the exact volume of touching blocks).
inline constexpr double kOverlapVolumeFraction = 1e-2;

/// ... unless it is shallow: at most this fraction of the thinner block's thickness deep, and at
/// most kShallowOverlapCap. A fraction of the volume alone refused thin blocks for drawing slack:
/// bricks 65 mm high drawn 1 mm into each other overlap by 1.5 %. A duplicated or misplaced block
/// is as deep as the block is thick.
inline constexpr double kShallowOverlapFraction = 0.1;
/// m: the deepest overlap taken for drawing slack whatever the blocks' size (rounding, snapping, a
/// drawn joint); the volume rule alone already accepts that much on blocks a metre thick.
inline constexpr double kShallowOverlapCap = 0.01;

/// The block's thinnest extent (m): the smallest width of its projection on one of its own face
/// normals (a brick's height, a tile's thickness).
double thinnest_width(const model::Block& block);

/// Every pair of prepared blocks (volumes and centroids known) whose projections overlap by more
/// than `tolerance` (m) along every face normal of both, with the volume they have in common.
/// Broad phase: sweep and prune over the bounding boxes shrunk by the tolerance (O(n log n +
/// pairs)); bound: projections on the face normals of both (any shapes: they are projections of
/// the convex hulls); exact volume: one block clipped by the other's face planes when both are
/// convex, else the signed tetrahedra of each block from its centroid (their signed indicators
/// sum to the block's, so V(A n B) = sum_ij s_i s_j V(T_i n T_j), convex pieces clipped).
/// Pairs of supports are skipped.
/// Pairs whose common volume is at most tolerance x V^(2/3) of the smaller block are left out.
std::vector<BlockOverlap> find_overlaps(const model::Model& model, double tolerance);

}  // namespace rbla::geometry
