// Bytes to a JSON document under InputLimits, checked while the parser reads: nesting depth,
// string length and the counts of blocks, vertices and interfaces stop the parse at the first
// value beyond them, so the document in memory never grows past what the limits allow. Also
// refuses a name repeated in one object (nlohmann would keep the last value silently), and reads
// numbers written with a zero fraction (3.0) as the integers they are (JSON Schema draft 6 on:
// "1.0" is an integer).
#pragma once

#include "io/input_limits.hpp"
#include "model/errors.hpp"

#include <nlohmann/json.hpp>

#include <istream>
#include <string_view>

namespace rbla::io {

/// Parses one JSON document from `in` (which may itself stop the parse by throwing, as the
/// size-capped input of io/input_file.hpp does). Throws model::ModelError naming the JSON pointer
/// of the place reached, and for malformed JSON its line and column.
nlohmann::json read_json(std::istream& in, const InputLimits& limits);
/// As above, from text in memory; text longer than limits.max_bytes is refused before parsing.
nlohmann::json read_json(std::string_view text, const InputLimits& limits);

}  // namespace rbla::io
