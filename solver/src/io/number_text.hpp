// One number as printf would print it, for the SVG pictures' coordinates and labels.
#pragma once

#include <cstdio>
#include <string>

namespace rbla::io {

/// `format` is a printf conversion for one double ("%.1f", "%.6g"); the text is at most 63 bytes.
inline std::string number_text(double value, const char* format = "%.1f") {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

}  // namespace rbla::io
