#include "rbla/conic/problem.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rbla::conic {

Eigen::Index ConeSpec::dimension() const {
  Eigen::Index n = num_nonneg;
  for (Eigen::Index q : soc_dims) n += q;
  return n;
}

Eigen::Index ConeSpec::degree() const {
  return num_nonneg + static_cast<Eigen::Index>(soc_dims.size());
}

std::vector<std::string> ConicProblem::validate() const {
  std::vector<std::string> messages;
  auto say = [&messages](const std::string& text) { messages.push_back(text); };
  const Eigen::Index m = A.rows();
  const Eigen::Index n = A.cols();
  if (b.size() != m) {
    say("b has " + std::to_string(b.size()) + " entries but A has " + std::to_string(m) + " rows");
  }
  if (c.size() != n) {
    say("c has " + std::to_string(c.size()) + " entries but A has " + std::to_string(n) +
        " columns");
  }
  if (cones.num_nonneg < 0) say("cones.num_nonneg is negative");
  for (std::size_t k = 0; k < cones.soc_dims.size(); ++k) {
    if (cones.soc_dims[k] < 2) {
      say("cones.soc_dims[" + std::to_string(k) + "] = " + std::to_string(cones.soc_dims[k]) +
          ": a second-order cone needs dimension >= 2");
    }
  }
  if (cones.dimension() != n) {
    say("cones cover " + std::to_string(cones.dimension()) + " variables but A has " +
        std::to_string(n) + " columns");
  }
  if (n == 0) say("the problem has no variables");
  for (Eigen::Index i = 0; i < b.size(); ++i) {
    if (!std::isfinite(b[i])) {
      say("b[" + std::to_string(i) + "] is not finite");
      break;
    }
  }
  for (Eigen::Index j = 0; j < c.size(); ++j) {
    if (!std::isfinite(c[j])) {
      say("c[" + std::to_string(j) + "] is not finite");
      break;
    }
  }
  if (!A.isCompressed()) say("A must be compressed (call A.makeCompressed())");
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    bool reported = false;
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it) {
      if (!std::isfinite(it.value())) {
        say("A(" + std::to_string(it.row()) + ", " + std::to_string(j) + ") is not finite");
        reported = true;
        break;
      }
    }
    if (reported) break;
  }
  return messages;
}

ConicSetupError ConicSetupError::from_messages(const std::string& prefix,
                                               const std::vector<std::string>& messages) {
  std::ostringstream text;
  text << prefix << ": ";
  for (std::size_t k = 0; k < messages.size(); ++k) text << (k ? "; " : "") << messages[k];
  return ConicSetupError(text.str());
}

bool same_shape(const ConicProblem& a, const ConicProblem& b) {
  const auto& A = a.A;
  const auto& B = b.A;
  if (A.rows() != B.rows() || A.cols() != B.cols() || A.nonZeros() != B.nonZeros()) return false;
  if (!A.isCompressed() || !B.isCompressed()) return false;
  if (a.cones.num_nonneg != b.cones.num_nonneg || a.cones.soc_dims != b.cones.soc_dims) return false;
  return std::equal(A.outerIndexPtr(), A.outerIndexPtr() + A.cols() + 1, B.outerIndexPtr()) &&
         std::equal(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros(), B.innerIndexPtr());
}

}  // namespace rbla::conic
