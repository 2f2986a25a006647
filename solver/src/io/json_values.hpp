// Small values written the same way in every section of the result JSON.
#pragma once

#include "model/angles.hpp"
#include "model/model.hpp"

#include <nlohmann/json.hpp>

namespace rbla::io {

/// [x, y, z].
inline nlohmann::json vec3_json(const model::Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

/// Angles are written in degrees.
using model::degrees;

}  // namespace rbla::io
