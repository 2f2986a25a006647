// Numbers and wall times for the analysis layer's messages: one place for both, shared by the
// pipeline and the searches that wrap it.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace rbla::analysis {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// A number for messages, `precision` significant digits.
std::string format(double value, int precision = 6);

/// "1 step", "3 steps": n with the singular or the plural.
std::string count(std::size_t n, const char* one, const char* many);

}  // namespace rbla::analysis
