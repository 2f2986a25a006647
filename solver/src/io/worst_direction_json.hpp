// The `worst_direction` section of the result JSON (schema/result.schema.json) and its polar
// picture, for `rbla worst-direction`.
#pragma once

#include "analysis/worst_direction.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace rbla::io {

/// Angles in degrees from `axis_x` towards `axis_y` (both written), directions as unit vectors,
/// alpha dimensionless; the bracket only when it is certified by convexity.
nlohmann::json worst_direction_json(const analysis::WorstDirection& search, double tolerance);

/// alpha(theta) as a polar plot seen from above: every evaluated direction, the polygon through
/// them (inside the set of loads carried, by convexity, for associative friction), the circle of
/// radius alpha_min and the weakest direction.
std::string worst_direction_svg(const analysis::WorstDirection& search);

}  // namespace rbla::io
