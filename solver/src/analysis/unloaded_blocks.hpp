// The motion of blocks that no load acts on, made definite.
//
// A free block with no weight and no point load does no work in any motion, so its velocity
// enters neither the objective bᵀy of the dual (its rows have b = 0) nor anything but its own
// contacts' dual cones. Where it can move off freely (a weightless block on top of a wall lifts
// off by any amount) the optimal face of the dual is unbounded along its motion, and an
// interior-point dual, which lies in the relative interior of that face, carries some arbitrary
// amount of it: on a 811-block church façade under out-of-plane load with one weightless block at
// the top corner, that block moved 90 times more than the overturning façade, so the mechanism
// read "1 block moves, 2 interfaces crack" instead of the façade's 810 and 28.
//
// Each such block is given instead the smallest of a few candidate motions (at rest, or moving
// rigidly with one of its neighbours) that keeps every cone of its contacts dual feasible. The
// dual objective is unchanged and the dual stays feasible, so the multipliers stay optimal: the
// mechanism is still an exact collapse mechanism of the same value. A block that already moves
// less than every candidate keeps its motion, as does one whose smaller candidates are all
// infeasible; if it then moves more than every loaded block it is returned as unsettled.
#pragma once

#include "analysis/formulation.hpp"
#include "model/model.hpp"

#include <Eigen/Core>

#include <vector>

namespace rbla::analysis {

struct UnloadedBlocks {
  std::vector<int> settled;    ///< blocks given a smaller feasible motion
  /// Kept the solver's motion (no smaller candidate was feasible) and move more than every loaded
  /// block: they set the mechanism's scale and their motion is arbitrary.
  std::vector<int> unsettled;
};

/// Free blocks whose equilibrium rows have no load (b = 0 on every row of the block).
std::vector<int> unloaded_blocks(const model::Model& m, const Formulation& f);

/// Replaces, in y, the multipliers of every unloaded block by the smallest dual-feasible candidate
/// motion (see above): y is a dual solution of f.problem with objective `cost` (the problem's own
/// c, or a non-associative step's shifted one). Does nothing, at no cost, when the model has no
/// unloaded block.
UnloadedBlocks settle_unloaded_blocks(const model::Model& m, const Formulation& f, const Eigen::VectorXd& cost,
                                      Eigen::VectorXd& y);

}  // namespace rbla::analysis
