// The geometric stage of the model pipeline, after io::parse_model: block volumes and centroids
// from the faces, checks that every block is a closed, outward-oriented, non-degenerate
// polyhedron, comparison with the CAD's own volume and centroid, local frames of given
// interfaces, and interface detection where the model asks for it.
#pragma once

#include "geometry/interface_detection.hpp"
#include "model/errors.hpp"
#include "model/model.hpp"

namespace rbla::geometry {

struct PrepareReport {
  double geometry_seconds = 0.0;
  double detect_seconds = 0.0;
  DetectionStats detection;
  bool detection_ran = false;
};

/// Completes `model` in place. Throws model::ModelError naming each bad block or interface by
/// its JSON pointer; adds warnings to model.warnings for what is suspicious but usable.
PrepareReport prepare_model(model::Model& model);

/// Relative tolerance on the CAD's volume (|V_cad - V| / V) before a warning is given.
inline constexpr double kCadVolumeTolerance = 1e-3;
/// Tolerance on the CAD's centroid, as a fraction of the block's bounding-box diagonal.
inline constexpr double kCadCentroidTolerance = 1e-3;

}  // namespace rbla::geometry
