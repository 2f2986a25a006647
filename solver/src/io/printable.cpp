#include "io/printable.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>

namespace rbla::io {
namespace {

/// Length of the valid UTF-8 sequence starting at text[at] and its code point; 0 when the bytes
/// there are not valid UTF-8 (stray continuation bytes, overlong forms, surrogates, > U+10FFFF,
/// cut sequences). RFC 3629, section 4.
std::size_t decode(std::string_view text, std::size_t at, std::uint32_t& code) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[at + k]); };
  const unsigned char lead = byte(0);
  std::size_t length = 0;
  std::uint32_t min = 0;
  if (lead < 0x80) {
    code = lead;
    return 1;
  } else if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2, code = lead & 0x1Fu, min = 0x80;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3, code = lead & 0x0Fu, min = 0x800;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4, code = lead & 0x07u, min = 0x10000;
  } else {
    return 0;
  }
  if (at + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(k) & 0xC0u) != 0x80u) return 0;
    code = (code << 6) | (byte(k) & 0x3Fu);
  }
  if (code < min || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return 0;
  return length;
}

/// Characters that act on the terminal or on how a line reads rather than showing a glyph:
/// C0 and C1 controls, DEL, the Unicode line and paragraph separators, and the bidirectional
/// embeddings, overrides and isolates (which can reorder what a line appears to say).
bool is_control(std::uint32_t code) {
  return code < 0x20 || (code >= 0x7F && code <= 0x9F) || code == 0x2028 || code == 0x2029 ||
         (code >= 0x202A && code <= 0x202E) || (code >= 0x2066 && code <= 0x2069);
}

}  // namespace

std::string printable(std::string_view text, std::size_t max_bytes) {
  std::string out;
  out.reserve(std::min(text.size(), max_bytes) + 16);
  std::size_t at = 0;
  while (at < text.size()) {
    std::uint32_t code = 0;
    const std::size_t length = decode(text, at, code);
    char piece[16];
    std::size_t piece_length = 0;
    if (length == 0) {
      piece_length = static_cast<std::size_t>(
          std::snprintf(piece, sizeof piece, "\\x%02X", static_cast<unsigned char>(text[at])));
    } else if (is_control(code)) {
      piece_length = static_cast<std::size_t>(std::snprintf(piece, sizeof piece, "\\u%04X", code));
    }
    const std::size_t grows = piece_length > 0 ? piece_length : length;
    if (out.size() + grows > max_bytes) {
      out += "... (" + std::to_string(text.size()) + " bytes in all)";
      return out;
    }
    if (piece_length > 0) out.append(piece, piece_length);
    else out.append(text.substr(at, length));
    at += length == 0 ? 1 : length;
  }
  return out;
}

}  // namespace rbla::io
