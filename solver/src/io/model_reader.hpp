// Reading the model JSON: parse, validate against schema/model.schema.json, check what a schema
// cannot (unique ids, references, index ranges), apply defaults, convert units, and build the
// typed model. Nothing after this stage reads JSON.
#pragma once

#include "io/input_limits.hpp"
#include "model/errors.hpp"
#include "model/model.hpp"

#include <nlohmann/json.hpp>

#include <istream>
#include <string>

namespace rbla::io {

/// Parses and validates model text under `limits` (io/input_limits.hpp). Throws model::ModelError
/// naming JSON pointers on bad input. Geometry (volumes, closure, interfaces) is not computed
/// here: see geometry/prepare_model.hpp.
model::Model parse_model(const std::string& text, const InputLimits& limits = {});
/// As above, reading the JSON from `in` as it comes (no copy of the whole text is kept).
model::Model parse_model(std::istream& in, const InputLimits& limits);
/// The typed model of a parsed document: schema validation, then what a schema cannot check.
model::Model model_from_json(const nlohmann::json& document);

/// Reads a whole file ("-" for standard input) of at most limits.max_bytes. Throws io::FileError
/// when it cannot be read, model::ModelError when it is too long.
std::string read_text(const std::string& path, const InputLimits& limits = {});

/// Messages of validating `text` against the result schema; empty when valid. Used by tests and
/// by `rbla solve` as a self-check before writing.
std::vector<model::InputIssue> validate_result_text(const std::string& text);

}  // namespace rbla::io
