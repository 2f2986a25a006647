// Non-associative Coulomb friction: joints that slide do not dilate.
//
// A non-associative collapse state is a pair (forces c, mechanism v) with c in equilibrium at the
// load value and inside every friction cone, v a mechanism whose sliding points do not open, and
// the two compatible: points that open carry no force, points that slide carry mu N against the
// slip. There is no convex problem whose solutions are exactly these states; the scheme below
// finds one and proves it is one.
//
// Steps (the kinematic shift; De Saxce & Feng 1991, the bipotential; Acary, Cadoux, Lemarechal &
// Malick 2011, ZAMM 91(2), "A formulation of the linear discrete Coulomb friction problem via
// convex optimization"). A point obeys the law above when its force is in the cone K and its
// relative velocity d, shifted along the normal by s = mu |d_t|, is in the dual cone and
// orthogonal to the force: for a sliding point with N > 0 that leaves d_n = mu |d_t| - s = 0. For
// fixed shifts s these are the optimality conditions of the associative problem with the cost of
// each normal force raised by s_k:
//
//     minimise  -alpha + sum_k s_k N_k   (settlement: R + sum_k s_k N_k)
//     subject to the associative constraints (equilibrium, c_k in the Coulomb cone),
//
// so each step is that convex problem, with s_k = mu_k |d_t,k| from the previous step's mechanism
// (Anderson-mixed). Every step has the associative feasible set: its forces satisfy Coulomb's
// condition, its alpha is never above the associative one (its R never below), no step can be
// infeasible where the associative problem is not, and the associative solver is reused (only the
// cost changes).
//
// Test (the fixed point of Gilbert, Casapulla & Ahmed 2006). A candidate state c is certified
// when it stays optimal with every point's shear capped at mu N_k of c itself (a cylinder, which
// cannot dilate): c satisfies the caps, so the capped problem's value is at least c's; equal means
// the capped problem's mechanism is compatible with c. The candidate is the conservative end of
// the step's optimal face (below), so a certified state is reported with its mechanism.
//
// Non-associative collapse is not unique: states compatible with one mechanism form a range of
// values (the drawer of tests/validation: 26.68 to 44.55 kN): the optimal face of the problem
// shifted by that mechanism's own slip rates. Its conservative end is reported (the lowest alpha,
// the highest R), with the range. Different
// mechanisms give different states too, and which one a run certifies depends on when it tests
// (docs/benchmark/non_associative_states.md): analysis.non_associative.trajectories runs the
// scheme with several test schedules and reports the most conservative certified state.
//
// Why not Gilbert's own iteration (each step caps |T_k| at mu N_k of the previous step): a step
// lets a point carry the previous step's mu N of shear after its normal force dropped, so its
// states violate Coulomb's condition until the radii converge, and the radii converged far more
// slowly than alpha on walls (docs/method.md, "Non-associative friction").
#pragma once

#include "analysis/analysis_result.hpp"
#include "analysis/formulation.hpp"
#include "analysis/solve_steps.hpp"
#include "model/model.hpp"
#include "rbla/conic/solver.hpp"

namespace rbla::analysis {

/// The relative gap at which a solve keeps its iterate to warm-start the scheme's next solve
/// (Gondzio & Grothey 2008): the associative solve that precedes the scheme keeps one too.
inline constexpr double kNonAssociativeSnapshotGap = 1e-2;

/// Runs the scheme from the associative solution `associative` of `formulation`, solved by
/// `solver` (reused: only its cost changes; restored before returning), each run's first step
/// warm-started from `associative.snapshot` when there is one. On return `value` is the
/// non-associative alpha (or base reaction, kN) and `result` holds its state, mechanism, history,
/// range and warnings, those of the run reported when several ran (all runs' values are in
/// result.non_associative_trajectories); when no step completes, `value` and the associative state
/// are kept.
void run_non_associative(const model::Model& m, const Formulation& formulation, conic::ConicSolver& solver,
                         const conic::Solution& associative, const Deadline& deadline, double& value,
                         AnalysisResult& result);

}  // namespace rbla::analysis
