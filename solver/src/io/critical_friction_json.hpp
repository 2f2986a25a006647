// The `critical_friction` section of the result JSON (schema/result.schema.json) and the
// alpha(mu) picture, for `rbla critical-friction`.
#pragma once

#include "analysis/critical_friction.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace rbla::io {

/// Factors (dimensionless) scale every interface's friction coefficient, or those of the chosen
/// interfaces (listed by id); `friction` gives the coefficient itself when all scaled interfaces
/// share one.
nlohmann::json critical_friction_json(const model::Model& model, const analysis::CriticalFriction& search,
                                      double tolerance);

/// The load multiplier of every factor evaluated against the friction coefficient (or the
/// factor): passing evaluations filled, failing ones hollow, the critical value marked.
std::string critical_friction_svg(const analysis::CriticalFriction& search);

}  // namespace rbla::io
