// Numbers and wall times for the analysis layer's messages: one place for both, shared by the
// pipeline and the searches that wrap it.
#pragma once

#include <chrono>
#include <string>

namespace rbla::analysis {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// A number for messages, `precision` significant digits.
std::string format(double value, int precision = 6);

}  // namespace rbla::analysis
