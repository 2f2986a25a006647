// Limits on what the model reader accepts, checked while the bytes are read so that a hostile or
// broken file is refused before it costs more than a small multiple of its own size in memory.
// The defaults fit every model rbla can solve on a workstation (the largest benchmarked model,
// 30323 blocks, is about 9 MB of JSON); each is raised by the option named in kInputLimits, up to
// the schema's own maximum where the schema has one.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace rbla::io {

struct InputLimits {
  /// Bytes of model JSON (a file, or standard input until its end).
  std::uint64_t max_bytes = 256ull << 20;
  /// Nesting of arrays and objects; a valid model nests 5 deep (/interfaces/i/polygon/j/k).
  std::uint64_t max_depth = 64;
  /// Bytes of one string or property name (the schema's longest text, a label, is 1000 characters).
  std::uint64_t max_string_bytes = 10000;
  /// Entries of /blocks (schema: 1 000 000).
  std::uint64_t max_blocks = 200000;
  /// Vertices of all blocks together (schema: 100 000 per block).
  std::uint64_t max_vertices = 10000000;
  /// Entries of /interfaces (schema: 10 000 000).
  std::uint64_t max_interfaces = 1000000;
  /// JSON values of every kind (numbers, strings, arrays, objects): the parsed document takes
  /// about 16 bytes a value, more than the two or three bytes of text a number may take, so the
  /// byte limit alone let 240 MB of "1," grow to 4 GB. A 30 000-block model has 2.1 million.
  std::uint64_t max_values = 50000000;
};

/// One limit as the command line offers it: its option, what it counts, its field and the largest
/// value that means anything (beyond it the schema refuses the model anyway).
struct InputLimitInfo {
  const char* option;
  const char* counts;
  std::uint64_t InputLimits::*field;
  std::uint64_t ceiling;
};

inline constexpr std::array<InputLimitInfo, 7> kInputLimits{{
    {"--max-input-bytes", "bytes of model JSON", &InputLimits::max_bytes, UINT64_MAX},
    {"--max-depth", "levels of nested arrays and objects", &InputLimits::max_depth, 1000000},
    {"--max-string-bytes", "bytes in one string or property name", &InputLimits::max_string_bytes, UINT64_MAX},
    {"--max-blocks", "blocks", &InputLimits::max_blocks, 1000000},
    {"--max-vertices", "vertices of all blocks together", &InputLimits::max_vertices, UINT64_MAX},
    {"--max-interfaces", "interfaces", &InputLimits::max_interfaces, 10000000},
    {"--max-values", "JSON values (numbers, strings, arrays and objects)", &InputLimits::max_values, UINT64_MAX},
}};

/// The entry of kInputLimits for `field` (every field has one).
inline const InputLimitInfo& limit_info(std::uint64_t InputLimits::*field) {
  for (const InputLimitInfo& info : kInputLimits) {
    if (info.field == field) return info;
  }
  return kInputLimits[0];
}

/// "the limit of 64 levels of nested arrays and objects (raise it with --max-depth)".
inline std::string limit_text(std::uint64_t InputLimits::*field, std::uint64_t value) {
  const InputLimitInfo& info = limit_info(field);
  return "the limit of " + std::to_string(value) + " " + info.counts + " (raise it with " + info.option + ")";
}

/// The refusal of a NUL byte at `offset` of `source` (a quoted path, "standard input", "the
/// text"): JSON text never holds one (in a string it is written \u0000), and the parser would take
/// it for the end of the text, ignoring whatever follows.
inline std::string nul_byte_text(const std::string& source, std::uint64_t offset) {
  return "malformed JSON: " + source + " holds a NUL byte at byte " + std::to_string(offset) + "; a model is JSON text";
}

}  // namespace rbla::io
