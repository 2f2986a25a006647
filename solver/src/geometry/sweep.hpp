// Sweep and prune (Baraff 1992), shared by interface detection and the overlap check: blocks are
// visited in the order of their boxes' lower ends along the model's longest axis, so each block
// is paired only with those whose boxes start before its own ends.
#pragma once

#include "model/model.hpp"

#include <algorithm>
#include <numeric>
#include <vector>

namespace rbla::geometry {

/// The axis (0, 1, 2) along which the model's bounding box is longest: the sweep's.
inline int sweep_axis(const model::Model& m) {
  const model::BoundingBox extent = m.bounding_box();
  int axis = 0;
  (extent.max - extent.min).maxCoeff(&axis);
  return axis;
}

/// Indices 0 .. n-1 sorted by `lower_end(i)` (the lower end of box i along the sweep axis), ties
/// by index so that the order, and everything found in it, is deterministic.
template <class LowerEnd>
std::vector<int> sweep_order(int n, LowerEnd lower_end) {
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const double la = lower_end(a), lb = lower_end(b);
    return la < lb || (la == lb && a < b);
  });
  return order;
}

}  // namespace rbla::geometry
