// The `sensitivities` section of the result JSON (schema/result.schema.json).
#pragma once

#include "analysis/analysis_result.hpp"
#include "model/model.hpp"

#include <nlohmann/json.hpp>

namespace rbla::io {

/// Derivatives in the model's units (unit weights in its force per length cubed), the lists
/// ordered by decreasing magnitude: the joints and blocks that matter most come first.
nlohmann::json sensitivities_json(const model::Model& model, const analysis::Sensitivities& sensitivities);

}  // namespace rbla::io
