// The `worst_settlement` section of the result JSON (schema/result.schema.json) and its map of
// the directions tried, for `rbla worst-settlement`.
#pragma once

#include "analysis/support_groups.hpp"
#include "analysis/worst_settlement.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace rbla::io {

/// Angles in degrees (tilt from gravity; azimuth from `axis_x` towards `axis_y`, both written),
/// directions as unit vectors, reactions in the model's force unit, the ratio R / R0
/// dimensionless; the upper bound only when it is certified by concavity.
nlohmann::json worst_settlement_json(const model::Model& model, const analysis::WorstSettlement& search,
                                     double tolerance);

/// The `candidate_groups` object of the section: every group's supports (ids), its most harmful
/// direction and R / R0, whether the ranking is certain, and the sentence saying so.
nlohmann::json candidate_groups_json(const model::Model& model, const analysis::SupportGroupRanking& ranking);

/// The directions tried seen from above (distance from the centre: tilt from gravity; angle:
/// azimuth), coloured by R / R0 from low (blue) to high (red), the cone's rim and the most
/// harmful direction marked.
std::string worst_settlement_svg(const analysis::WorstSettlement& search);

}  // namespace rbla::io
