// Text from the user (ids, labels, property names, number literals, paths) made safe to print on
// a terminal or in a log: one function, applied where a message quotes such text and again where
// the program prints its messages.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace rbla::io {

/// How much of one user string a message quotes by default, in bytes.
inline constexpr std::size_t kPrintableMaxBytes = 200;

/// `text` with every control character (C0, DEL and the C1 range U+0080..U+009F) written as
/// \uXXXX, as JSON writes it, and every byte that is not part of valid UTF-8 as \xNN, so that no
/// input can move the cursor, change colours or forge a line of its own. Longer than `max_bytes`,
/// it is cut at a character boundary and ends with "... (N bytes in all)".
/// Backslashes are left alone: applying the function twice gives the same text as once, so a
/// message escaped where it was built can be escaped again where it is printed.
std::string printable(std::string_view text, std::size_t max_bytes = kPrintableMaxBytes);

}  // namespace rbla::io
