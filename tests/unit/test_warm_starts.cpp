// The interior points a search keeps between analyses (analysis/warm_starts.hpp): the nearest
// within reach, nothing beyond it, nothing kept that is empty.
#include "analysis/warm_starts.hpp"

#include <gtest/gtest.h>

namespace {

using rbla::analysis::WarmStarts;
using rbla::conic::Iterate;

Iterate point(double value) {
  Iterate p;
  p.x = Eigen::VectorXd::Constant(2, value);
  p.y = Eigen::VectorXd::Constant(1, value);
  p.z = Eigen::VectorXd::Constant(2, value);
  return p;
}

Eigen::VectorXd at(double a) { return Eigen::VectorXd::Constant(1, a); }

TEST(WarmStarts, TheNearestWithinReachOrNone) {
  WarmStarts points(0.5);
  EXPECT_TRUE(points.nearest(at(0.0)).empty());
  points.keep(at(0.0), point(1.0));
  points.keep(at(1.0), point(2.0));
  points.keep(at(0.7), Iterate{});  // an analysis that kept no point
  EXPECT_EQ(points.nearest(at(0.3)).x[0], 1.0);
  EXPECT_EQ(points.nearest(at(0.8)).x[0], 2.0);
  EXPECT_TRUE(points.nearest(at(-0.6)).empty());
  EXPECT_TRUE(points.nearest(at(1.6)).empty());
}

}  // namespace
