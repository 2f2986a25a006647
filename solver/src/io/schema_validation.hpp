// JSON Schema (draft-07) validation with valijson against the schemas compiled into the binary.
#pragma once

#include "model/errors.hpp"

#include <nlohmann/json.hpp>

#include <vector>

namespace rbla::io {

enum class SchemaKind { Model, Result };

/// Validates `document`; returns one issue per failing place, most specific first, at most
/// `max_issues`. An empty vector means the document is valid.
std::vector<model::InputIssue> validate_against_schema(const nlohmann::json& document, SchemaKind kind,
                                                       std::size_t max_issues = 20);

}  // namespace rbla::io
