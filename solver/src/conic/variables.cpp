#include "variables.hpp"

#include <algorithm>

namespace rbla::conic::detail {

void Direction::swap(Direction& other) {
  x.swap(other.x);
  y.swap(other.y);
  z.swap(other.z);
  std::swap(tau, other.tau);
  std::swap(kappa, other.kappa);
}

void Variables::set_identity(const Vec& e, Eigen::Index rows) {
  x = e;
  z = e;
  y = Vec::Zero(rows);
  tau = 1.0;
  kappa = 1.0;
}

double Variables::mu(double degree) const { return (x.dot(z) + tau * kappa) / (degree + 1.0); }

void Variables::take_step(const Direction& d, double alpha) {
  x += alpha * d.x;
  y += alpha * d.y;
  z += alpha * d.z;
  tau += alpha * d.tau;
  kappa += alpha * d.kappa;
}

bool Variables::normalise() {
  const double scale = std::max(tau, kappa);
  if (!(scale < 1e-4 || scale > 1e4)) return false;  // NaN too: left alone
  x /= scale;
  y /= scale;
  z /= scale;
  tau /= scale;
  kappa /= scale;
  return true;
}

}  // namespace rbla::conic::detail
