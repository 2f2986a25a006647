// The result's `detection` section: the tolerances interface detection used, the spread of gaps
// and angles over the joints it accepted, and the closest face pairs it rejected (near misses).
#pragma once

#include "model/model.hpp"

#include <nlohmann/json.hpp>

namespace rbla::io {

/// Lengths in the model's unit, angles in degrees; null when detection did not run.
nlohmann::json detection_json(const model::Model& model);

}  // namespace rbla::io
