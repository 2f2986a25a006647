#include "analysis/unloaded_blocks.hpp"

#include "analysis/mechanism.hpp"

#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>

namespace rbla::analysis {

namespace {

/// A violation of a contact's dual cone this small, relative to the largest multiplier of the
/// loaded blocks, is within what the interior-point solution itself carries (its dual residual
/// is of this order at the default tolerances).
constexpr double kDualConeTolerance = 1e-8;

/// The dual cones of the conic problem, reached from the equilibrium rows of a block.
class DualCones {
 public:
  DualCones(const conic::ConicProblem& problem, const Eigen::VectorXd& cost)
      : problem_(problem), cost_(cost), by_row_(problem.A) {
    Eigen::Index start = problem.cones.num_nonneg;
    for (Eigen::Index dim : problem.cones.soc_dims) {
      soc_starts_.push_back(start);
      start += dim;
    }
  }

  /// First columns of the cones whose variables appear in rows [row, row + count).
  std::vector<Eigen::Index> cones_of_rows(int row, int count) const {
    std::vector<Eigen::Index> starts;
    for (int r = row; r < row + count; ++r) {
      for (RowMajor::InnerIterator it(by_row_, r); it; ++it) starts.push_back(cone_start(it.col()));
    }
    std::sort(starts.begin(), starts.end());
    starts.erase(std::unique(starts.begin(), starts.end()), starts.end());
    return starts;
  }

  /// Largest violation of z = c − Aᵀy ∈ K* over the given cones (0 when all hold).
  double worst_violation(const std::vector<Eigen::Index>& starts, const Eigen::VectorXd& y) const {
    double worst = 0.0;
    for (Eigen::Index start : starts) worst = std::max(worst, violation(start, y));
    return worst;
  }

 private:
  using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;

  Eigen::Index cone_start(Eigen::Index column) const {
    if (column < problem_.cones.num_nonneg) return column;
    return *(std::upper_bound(soc_starts_.begin(), soc_starts_.end(), column) - 1);
  }

  double dual_slack(Eigen::Index column, const Eigen::VectorXd& y) const {
    return cost_[column] - problem_.A.col(column).dot(y);
  }

  /// Nonnegative: max(0, −z); second-order cone (t, u): max(0, ‖u‖ − t).
  double violation(Eigen::Index start, const Eigen::VectorXd& y) const {
    const double t = dual_slack(start, y);
    if (start < problem_.cones.num_nonneg) return std::max(0.0, -t);
    const auto k = std::lower_bound(soc_starts_.begin(), soc_starts_.end(), start) - soc_starts_.begin();
    double u2 = 0.0;
    for (Eigen::Index j = start + 1; j < start + problem_.cones.soc_dims[k]; ++j) {
      const double z = dual_slack(j, y);
      u2 += z * z;
    }
    return std::max(0.0, std::sqrt(u2) - t);
  }

  const conic::ConicProblem& problem_;
  const Eigen::VectorXd& cost_;
  RowMajor by_row_;
  std::vector<Eigen::Index> soc_starts_;
};

/// At rest, and moving rigidly with each neighbour (its motion carried to b's centroid), smallest
/// first.
std::vector<BlockMotion> candidate_motions(const model::Model& m, const std::vector<BlockMotion>& motions,
                                           const std::vector<int>& neighbours, int b) {
  std::vector<BlockMotion> candidates(1);
  for (int o : neighbours) {
    BlockMotion carried;
    carried.rotation = motions[o].rotation;
    carried.translation =
        motions[o].translation + motions[o].rotation.cross(m.blocks[b].centroid - m.blocks[o].centroid);
    candidates.push_back(carried);
  }
  const model::Block& block = m.blocks[b];
  std::stable_sort(candidates.begin(), candidates.end(), [&](const BlockMotion& p, const BlockMotion& q) {
    return block_speed(block, p) < block_speed(block, q);
  });
  return candidates;
}

/// The unloaded blocks in breadth-first order from the loaded ones, so a block's loaded or already
/// settled neighbours come before it; groups joined to no loaded block last.
std::vector<int> settling_order(const model::Model& m, const std::vector<std::vector<int>>& neighbours,
                                const std::vector<int>& unloaded) {
  std::vector<char> pending(m.blocks.size(), 0);
  for (int b : unloaded) pending[b] = 1;
  std::vector<int> order;
  auto visit_from = [&](std::size_t head) {
    for (; head < order.size(); ++head) {
      for (int o : neighbours[order[head]]) {
        if (pending[o]) pending[o] = 0, order.push_back(o);
      }
    }
  };
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    if (pending[b]) continue;
    for (int o : neighbours[b]) {
      if (pending[o]) pending[o] = 0, order.push_back(o);
    }
  }
  visit_from(0);
  for (int b : unloaded) {
    if (pending[b]) pending[b] = 0, order.push_back(b), visit_from(order.size() - 1);
  }
  return order;
}

/// The loaded free blocks' scales: their largest multiplier (the dual's scale) and their largest
/// vertex speed.
void loaded_scales(const model::Model& m, const Formulation& f, const std::vector<int>& unloaded,
                   const Eigen::VectorXd& y, const std::vector<BlockMotion>& motions, double& multiplier,
                   double& speed) {
  std::vector<char> is_unloaded(m.blocks.size(), 0);
  for (int b : unloaded) is_unloaded[b] = 1;
  multiplier = speed = 0.0;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    if (is_unloaded[b] || m.blocks[b].is_support() || f.block_row[b] < 0) continue;
    multiplier = std::max(multiplier, y.segment(f.block_row[b], f.rows_per_block).cwiseAbs().maxCoeff());
    speed = std::max(speed, block_speed(m.blocks[b], motions[b]));
  }
}

}  // namespace

std::vector<int> unloaded_blocks(const model::Model& m, const Formulation& f) {
  std::vector<int> unloaded;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    const int row = f.block_row[b];
    if (m.blocks[b].is_support() || row < 0) continue;
    if (f.problem.b.segment(row, f.rows_per_block).isZero(0.0)) unloaded.push_back(static_cast<int>(b));
  }
  return unloaded;
}

UnloadedBlocks settle_unloaded_blocks(const model::Model& m, const Formulation& f, const Eigen::VectorXd& cost,
                                      Eigen::VectorXd& y) {
  UnloadedBlocks result;
  const std::vector<int> unloaded = unloaded_blocks(m, f);
  if (unloaded.empty()) return result;
  const DualCones dual(f.problem, cost);
  const std::vector<std::vector<int>> neighbours = m.neighbours();
  std::vector<BlockMotion> motions = block_velocities(m, f, y);
  double loaded_multiplier = 0.0, loaded_speed = 0.0;
  loaded_scales(m, f, unloaded, y, motions, loaded_multiplier, loaded_speed);
  const double tolerance = kDualConeTolerance * loaded_multiplier;
  for (int b : settling_order(m, neighbours, unloaded)) {
    const int row = f.block_row[b];
    const std::vector<Eigen::Index> cones = dual.cones_of_rows(row, f.rows_per_block);
    const double allowed = std::max(tolerance, dual.worst_violation(cones, y));
    const Eigen::VectorXd original = y.segment(row, f.rows_per_block);
    const double original_speed = block_speed(m.blocks[b], motions[b]);
    bool settled = false;
    for (const BlockMotion& candidate : candidate_motions(m, motions, neighbours[b], b)) {
      if (block_speed(m.blocks[b], candidate) >= original_speed) break;
      set_block_multipliers(f, b, candidate, y);
      if (dual.worst_violation(cones, y) <= allowed) {
        motions[b] = candidate;
        settled = true;
        break;
      }
    }
    if (settled) {
      result.settled.push_back(b);
      continue;
    }
    y.segment(row, f.rows_per_block) = original;
    if (original_speed > loaded_speed) result.unsettled.push_back(b);
  }
  return result;
}

}  // namespace rbla::analysis
