#pragma once
// Starting points of the embedding (variables.hpp), in the scaled variables with τ = 1:
// x = z = e (the cones' identity), the least-squares point, or a warm start near a known
// solution.

#include "normal_equations.hpp"
#include "rbla/conic/info.hpp"
#include "scaled_problem.hpp"
#include "variables.hpp"

namespace rbla::conic::detail {

/// Least-squares starting point (CVXOPT conelp's default, also ECOS's): x̂ = argmin ‖x‖ s.t.
/// A x = b and (ŷ, ẑ) = argmin ‖z‖ s.t. Aᵀy + z = c, both through M = A Aᵀ (the normal matrix
/// at W = I: one extra factorisation), each shifted into the cone along e by one plus its most
/// negative eigenvalue when it is not interior already. Fewer iterations than x = z = e on most
/// limit-analysis problems, a few more on some small ones. False (v untouched) when the point
/// could not be computed; factorisation timings go into info.
bool least_squares_start(NormalEquations& ne, const ScaledProblem& scaled, const ConeSet& cones,
                         const Settings& settings, int factor_threads, Variables& v, Info& info);

/// The warm-start blend (see ConicSolver::set_warm_start; Skajaa, Andersen & Ye 2013) of the
/// point (x, y, z) in original units: x = λ E⁻¹x̂ s_b + (1 − λ) e, z = λ E ẑ s_c + (1 − λ) e,
/// y = λ D⁻¹ŷ s_c, τ = 1, κ = xᵀz/ν (equilibration.hpp's maps inverted). False when the point
/// is not finite, has the wrong sizes or the blend is not interior (v is then to be reset).
bool warm_start(const ScaledProblem& scaled, ConeSet& cones, const Settings& settings,
                const Vec& warm_x, const Vec& warm_y, const Vec& warm_z, Variables& v);

}  // namespace rbla::conic::detail
