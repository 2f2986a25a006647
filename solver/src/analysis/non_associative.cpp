#include "analysis/non_associative.hpp"

#include <algorithm>
#include <cmath>

namespace rbla::analysis {

namespace {

/// Non-associative steps whose alpha moved by less than this many times the scheme's tolerance
/// are solved at the requested tolerances (they are likely to be the last step).
constexpr double kTightStepFactor = 30.0;

}  // namespace

void run_non_associative(const model::Model& m, const Formulation& formulation,
                         const FormulationOptions& formulation_options, const conic::Solution& solution,
                         const Deadline& deadline, const AnalysisOptions& options, double& value,
                         AnalysisResult& result) {
  const model::AnalysisRequest& request = m.analysis;
  auto time_left = [&] { return deadline.left(); };
  // Gilbert et al. (2006), Portioli et al. (2014): replace each cone by a cylinder of radius
  // mu N from the previous step, so sliding does not dilate; damp the radii
  // (r <- d mu N + (1 - d) r), which stops the plain fixed point from oscillating
  // (METHOD.md: alpha 0.37 -> 0.21 -> 0.25 ... undamped).
  result.non_associative.push_back({0, value, 0.0, solution.info.iterations});
  FormulationOptions cylinder_options = formulation_options;
  cylinder_options.friction_set = FrictionSet::Cylinder;
  const auto assemble_start = Clock::now();
  const Formulation cylinder = build_formulation(m, cylinder_options);
  result.assemble_seconds += seconds_since(assemble_start);
  record_size(cylinder, result);

  const std::vector<Vec3> forces = formulation.point_forces(solution.x);
  std::vector<double> normals = normal_forces(m, formulation, forces);
  // A small floor keeps every cylinder with an interior (METHOD.md). It is shear capacity that
  // needs no normal force, so it is relative to the load of the lighter block at the point: a
  // floor relative to one scale for the whole model was larger than a very light block's weight.
  std::vector<double> floor(normals.size());
  for (std::size_t p = 0; p < floor.size(); ++p) floor[p] = 1e-9 * cylinder.points[p].load;
  std::vector<double> radii(normals.size());
  for (std::size_t p = 0; p < radii.size(); ++p) radii[p] = std::max(floor[p], cylinder.points[p].friction * normals[p]);

  // Steps are solved only as accurately as the scheme can use: a tenth of the last relative
  // change of alpha, within [a tenth of the convergence tolerance, 1e-3]. The converged step
  // is then re-solved at the requested tolerances.
  auto step_tolerance = [&](double last_relative_change) {
    const double tol = std::clamp(0.1 * last_relative_change, 0.1 * request.non_associative_tolerance, 1e-3);
    return std::max(tol, request.tol_relative_gap);
  };
  double step_tol = step_tolerance(1.0);
  double reported_step_tol = step_tol;  // tolerance of the step that will be reported
  conic::Settings settings = solver_settings(request, options, time_left());
  settings.tol_gap_rel = step_tol;
  // Loose steps resolve every block's own load as well as an O(1) right-hand side is resolved
  // (a block with its own force scale may have a right-hand side far below 1).
  auto step_feasibility = [&](double tol) {
    return std::max(request.tol_feasibility, 0.1 * tol * cylinder.rhs_resolution);
  };
  settings.tol_feas = step_feasibility(step_tol);
  conic::ConicProblem first = cylinder.problem;
  first.b = cylinder.rhs_with_radii(radii);
  const auto cylinder_start = Clock::now();
  conic::ConicSolver cylinder_solver(std::move(first), settings);
  if (options.progress) cylinder_solver.set_progress_callback(options.progress);
  result.solve_seconds += seconds_since(cylinder_start);

  std::vector<double> used_radii = radii;
  double damping = request.non_associative_damping;
  double previous_change = 0.0;
  conic::Solution step;
  bool have_step = false;
  for (int iteration = 1; iteration <= request.non_associative_max_iterations; ++iteration) {
    if (time_left() <= 0.0) {
      result.verdict = Verdict::TimeLimit;
      break;
    }
    cylinder_solver.settings().time_limit_seconds = std::max(time_left(), 1e-6);
    cylinder_solver.settings().tol_gap_rel = step_tol;
    cylinder_solver.settings().tol_feas = step_feasibility(step_tol);
    reported_step_tol = step_tol;
    const auto step_start = Clock::now();
    conic::Solution next = cylinder_solver.solve();
    result.solve_seconds += seconds_since(step_start);
    if (!conic::has_solution(next.info.status)) {
      result.warnings.push_back({"non_associative_step_failed",
                                 "non-associative step " + std::to_string(iteration) + " ended with " +
                                     conic::to_string(next.info.status) + "; the last completed step is reported",
                                 ""});
      if (next.info.status == conic::SolveStatus::TimeLimit) result.verdict = Verdict::TimeLimit;
      if (next.info.status == conic::SolveStatus::Cancelled) result.verdict = Verdict::Cancelled;
      break;
    }
    const double next_value = multiplier_value(cylinder, next.x);
    const std::vector<double> next_normals = normal_forces(m, cylinder, cylinder.point_forces(next.x));
    double change = 0.0;
    for (std::size_t p = 0; p < next_normals.size(); ++p) change = std::max(change, std::abs(next_normals[p] - normals[p]));
    result.non_associative.push_back({iteration, next_value, change, next.info.iterations});
    const double previous = value;
    step = std::move(next);
    have_step = true;
    used_radii = radii;
    value = next_value;
    normals = next_normals;
    const double scale = formulation.settlement ? std::max(std::abs(value), 1e-12 * formulation.force_scale)
                                                : std::max(std::abs(value), 1e-12);
    // Converged when the change is below the tolerance and so is the distance to the limit
    // that a linearly converging sequence implies (|d_k| rho / (1 - rho), rho = |d_k / d_k-1|):
    // with strong damping the steps shrink slowly and a small step alone can stop far from
    // the fixed point (a 1-degree slope stopped 5.5e-5 away with a 1e-6 tolerance).
    const double step_change = std::abs(value - previous);
    const double rho = std::abs(previous_change) > 0.0 ? step_change / std::abs(previous_change) : 0.0;
    const double remaining = rho < 1.0 ? step_change * rho / (1.0 - rho) : step_change;
    if (step_change <= request.non_associative_tolerance * scale &&
        remaining <= request.non_associative_tolerance * scale) {
      result.non_associative_converged = true;
      break;
    }
    step_tol = step_tolerance(std::abs(value - previous) / scale);
    // Near convergence, solve at the requested tolerances at once: a tight solve costs a few
    // more interior-point iterations than a loose one (façade: 22-24 against 17-20), while a
    // loose step that passes the test is solved again from the start (22 more). The radii and
    // so the path of the scheme are unchanged.
    if (step_change <= kTightStepFactor * request.non_associative_tolerance * scale) step_tol = request.tol_relative_gap;
    // Adaptive damping: when alpha turns back (the iteration overshoots), halve the weight of
    // the new radii, down to an eighth of the requested damping. A floor at one half left
    // period-4 cycles (a 1:1000 column, a block 1e6 lighter than the one below it); the
    // stopping test above accounts for the slower steps.
    if (previous_change * (value - previous) < 0.0) damping = std::max(damping * 0.5, request.non_associative_damping / 8.0);
    previous_change = value - previous;
    const double d = damping;
    for (std::size_t p = 0; p < radii.size(); ++p) {
      radii[p] = std::max(floor[p], d * cylinder.points[p].friction * normals[p] + (1.0 - d) * radii[p]);
    }
    cylinder_solver.update_b(cylinder.rhs_with_radii(radii));
    // Consecutive steps differ only in the radii: start the next one near this solution.
    if (request.non_associative_warm_start) cylinder_solver.set_warm_start(step.x, step.y, step.z);
  }
  // The reported step is always solved at the requested tolerances, converged or not.
  if (have_step && reported_step_tol > request.tol_relative_gap && time_left() > 0.0) {
    cylinder_solver.settings().tol_gap_rel = request.tol_relative_gap;
    cylinder_solver.settings().tol_feas = request.tol_feasibility;
    cylinder_solver.settings().time_limit_seconds = std::max(time_left(), 1e-6);
    cylinder_solver.update_b(cylinder.rhs_with_radii(used_radii));
    if (request.non_associative_warm_start) cylinder_solver.set_warm_start(step.x, step.y, step.z);
    const auto final_start = Clock::now();
    conic::Solution tight = cylinder_solver.solve();
    result.solve_seconds += seconds_since(final_start);
    if (conic::has_solution(tight.info.status)) {
      step = std::move(tight);
      value = multiplier_value(cylinder, step.x);
    }
  }
  if (!result.non_associative_converged && have_step) {
    result.warnings.push_back({"non_associative_not_converged",
                               "the non-associative scheme did not converge in " +
                                   std::to_string(request.non_associative_max_iterations) +
                                   " steps; the last step is reported",
                               "/analysis/non_associative/max_iterations"});
  }
  if (have_step) {
    result.solver_info = step.info;
    result.interior_point_history = step.info.history;
    result.mechanism = Mechanism{};
    result.mechanism_seconds = 0.0;
    read_solution(m, cylinder, step, false, used_radii, result);
  }
}

}  // namespace rbla::analysis
