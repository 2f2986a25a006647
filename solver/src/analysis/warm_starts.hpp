// Interior points kept between the analyses of a search (critical friction, weakest direction,
// most harmful settlement), so that each solve can start from the point of the nearest model
// already analysed (ConicSolver::set_warm_start; Skajaa, Andersen & Ye 2013).
//
// Each kept point is labelled with where its model sits in the search's parameter space (a log
// friction factor, a unit direction); a new analysis starts from the nearest one within `reach`
// and cold otherwise: far apart, the other problem's point is a worse start than the centre.
#pragma once

#include "rbla/conic/info.hpp"

#include <Eigen/Core>

#include <utility>
#include <vector>

namespace rbla::analysis {

class WarmStarts {
 public:
  explicit WarmStarts(double reach) : reach_(reach) {}

  /// The point kept nearest to `where` within the reach; empty when there is none.
  conic::Iterate nearest(const Eigen::VectorXd& where) const {
    const conic::Iterate* best = nullptr;
    double best_distance = reach_;
    for (const auto& [at, point] : points_) {
      const double distance = (at - where).norm();
      if (distance <= best_distance) {
        best_distance = distance;
        best = &point;
      }
    }
    return best ? *best : conic::Iterate{};
  }

  void keep(const Eigen::VectorXd& where, conic::Iterate point) {
    if (!point.empty()) points_.emplace_back(where, std::move(point));
  }

 private:
  double reach_;
  std::vector<std::pair<Eigen::VectorXd, conic::Iterate>> points_;
};

}  // namespace rbla::analysis
