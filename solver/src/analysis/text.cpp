#include "analysis/text.hpp"

#include <sstream>

namespace rbla::analysis {

std::string format(double value, int precision) {
  std::ostringstream out;
  out.precision(precision);
  out << value;
  return out.str();
}

}  // namespace rbla::analysis
