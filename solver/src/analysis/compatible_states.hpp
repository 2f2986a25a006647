// The force states exactly compatible, point by point, with a given collapse mechanism: what a
// non-associative collapse state is (docs/method.md, "How compatible a certified state is").
//
// The fixed-point test of the non-associative scheme bounds the work the state and its mechanism
// disagree by (a tolerance relative to the value). That does not bound forces: a point that opens
// by a thousandth of the largest motion may keep a tenth of the largest normal force, and no
// state may be exactly compatible with that mechanism at all. This check asks the question
// pointwise: reading from the mechanism which points open and which slide (and which way), is
// there an equilibrated state in which every opening point carries nothing and every sliding
// point carries its full friction against the slip (mu N, or the pyramid's edge of the same
// reach)? Closed points keep their whole friction set. A linear program (a conic one with exact
// cones) answers it, and its two ends are the range of such states.
#pragma once

#include "analysis/formulation.hpp"
#include "model/model.hpp"
#include "rbla/conic/settings.hpp"
#include "rbla/conic/solver.hpp"

#include <Eigen/Core>

#include <vector>

namespace rbla::analysis {

/// A point moves when its relative velocity's normal (opening) or tangential (sliding) part
/// exceeds this fraction of the largest relative velocity of any point in the mechanism; below
/// it the point counts as closed. The mechanisms the scheme certifies leave closed points at
/// 1e-10 of the largest motion; the slow openings that carry force in nearly compatible states
/// lie at 1e-5 to 1e-2 of it (an independent review's LP over 43 planar runs tried 1e-4, 1e-5
/// and 1e-6: all three agreed on 30 of them).
inline constexpr double kMovingPointFraction = 1e-4;

/// How the mechanism moves at each formulation point.
struct PointPattern {
  enum class Motion { Closed, Opens, Slides };
  std::vector<Motion> motion;
  std::vector<Vec3> slip_direction;  ///< unit tangential relative velocity at sliding points
  int opening = 0;
  int sliding = 0;
};

/// Reads the pattern of the mechanism whose equality multipliers (in `f`'s rows) are `y`.
PointPattern point_pattern(const model::Model& m, const Formulation& f, const Eigen::VectorXd& y);

struct CompatibleStates {
  enum class Outcome {
    Found,   ///< both ends solved: the pattern admits exactly compatible states
    None,    ///< no equilibrated state is exactly compatible (primal infeasible)
    Failed,  ///< a solve ended otherwise (time limit, numerical trouble): no verdict
  };
  Outcome outcome = Outcome::Failed;
  conic::Solution conservative;  ///< the lowest alpha (the highest R) of the compatible states
  conic::Solution other;         ///< the other end
  int iterations = 0;
};

/// How far a state is from compatible with a pattern, over the largest normal force of any
/// point: the largest normal force at an opening point, and the largest shortfall of friction
/// (reach N + T . t, the friction it could still carry against the slip) at a sliding point.
struct PatternViolation {
  double open_force = 0.0;
  double friction_shortfall = 0.0;
};
PatternViolation pattern_violation(const model::Model& m, const Formulation& f, const PointPattern& pattern,
                                   const Eigen::VectorXd& x);

/// The range of states of `f` compatible with `pattern`: `cost` is the analysis's own (its optimum
/// is the least conservative end). Solved with `settings`; `f`'s problem is not changed.
CompatibleStates compatible_states(const model::Model& m, const Formulation& f, const PointPattern& pattern,
                                   const Eigen::VectorXd& cost, const conic::Settings& settings);

}  // namespace rbla::analysis
