// π and the conversions between degrees (the model file's and the messages' unit) and radians
// (the code's), in one place.
#pragma once

namespace rbla::model {

inline constexpr double kPi = 3.14159265358979323846;  // std::numbers::pi from C++20 on
inline constexpr double radians(double degrees) { return degrees * kPi / 180.0; }
inline constexpr double degrees(double radians) { return radians * 180.0 / kPi; }

}  // namespace rbla::model
