// Reading the model JSON: parse, validate against schema/model.schema.json, check what a schema
// cannot (unique ids, references, index ranges), apply defaults, convert units, and build the
// typed model. Nothing after this stage reads JSON.
#pragma once

#include "model/errors.hpp"
#include "model/model.hpp"

#include <string>

namespace rbla::io {

/// Parses and validates model text. Throws model::ModelError naming JSON pointers on bad input.
/// Geometry (volumes, closure, interfaces) is not computed here: see geometry/prepare_model.hpp.
model::Model parse_model(const std::string& text);

/// Reads a whole file ("-" for standard input). Throws model::ModelError when it cannot be read.
std::string read_text(const std::string& path);

/// Messages of validating `text` against the result schema; empty when valid. Used by tests and
/// by `rbla solve` as a self-check before writing.
std::vector<model::InputIssue> validate_result_text(const std::string& text);

}  // namespace rbla::io
