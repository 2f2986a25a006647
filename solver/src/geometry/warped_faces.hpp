// Faces that are not planar: CAD exports warp faces by millimetres to centimetres. Detection
// compares their fitted planes; the user hears about them once, not once per face.
#pragma once

#include "model/model.hpp"

#include <vector>

namespace rbla::geometry {

struct WarpedFace {
  int block = -1;
  int face = -1;
  double deviation = 0.0;  ///< m, largest distance of a corner from the face's fitted plane
  double size = 0.0;       ///< m, the face's diameter
};

/// At most two `non_planar_face` warnings for all of `warped`: one for the faces whose warp stays
/// within the joint distance tolerance (detection's fitted planes absorb it), one for those
/// beyond it (contacts on them are approximate); each gives the count, the largest warp and
/// points at the worst face.
void warn_warped_faces(const std::vector<WarpedFace>& warped, model::Model& model);

}  // namespace rbla::geometry
