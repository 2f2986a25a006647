// Distance from a point to the surface of a polyhedral block: where a given interface lies
// relative to the blocks it names.
#pragma once

#include "model/model.hpp"

namespace rbla::geometry {

/// Distance (m) from `p` to the nearest face of `block`, each face taken as the planar polygon
/// of its vertices in its mean plane (face_geometry): the distance to the plane when the
/// projection of p falls inside the polygon (crossing number, so non-convex faces too), else the
/// distance to the nearest edge. O(vertices of the block).
double distance_to_surface(const model::Block& block, const model::Vec3& p);

}  // namespace rbla::geometry
