#include "analysis/text.hpp"

#include <sstream>

namespace rbla::analysis {

std::string format(double value, int precision) {
  std::ostringstream out;
  out.precision(precision);
  out << value;
  return out.str();
}

std::string count(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace rbla::analysis
