#include "analysis/limit_analysis.hpp"

#include "analysis/formulation.hpp"
#include "analysis/initial_reaction.hpp"
#include "analysis/mechanism.hpp"
#include "model/errors.hpp"
#include "rbla/conic/io.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace rbla::analysis {

const char* to_string(Verdict verdict) {
  switch (verdict) {
    case Verdict::Collapse: return "collapse";
    case Verdict::NoMechanism: return "no_mechanism";
    case Verdict::CannotStand: return "cannot_stand";
    case Verdict::SolverFailure: return "solver_failure";
    case Verdict::TimeLimit: return "time_limit";
    case Verdict::IterationLimit: return "iteration_limit";
    case Verdict::Cancelled: return "cancelled";
  }
  return "?";
}

const char* to_string(ContactState state) {
  switch (state) {
    case ContactState::Closed: return "closed";
    case ContactState::Opening: return "opening";
    case ContactState::Sliding: return "sliding";
    case ContactState::OpeningSliding: return "opening_sliding";
  }
  return "?";
}

const char* to_string(InterfaceState state) {
  switch (state) {
    case InterfaceState::Closed: return "closed";
    case InterfaceState::Opening: return "opening";
    case InterfaceState::Sliding: return "sliding";
    case InterfaceState::OpeningSliding: return "opening_sliding";
    case InterfaceState::Hinge: return "hinge";
  }
  return "?";
}

namespace {

using Clock = std::chrono::steady_clock;
/// Non-associative steps whose alpha moved by less than this many times the scheme's tolerance
/// are solved at the requested tolerances (they are likely to be the last step).
constexpr double kTightStepFactor = 30.0;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::string format(double value, int precision = 6) {
  std::ostringstream out;
  out.precision(precision);
  out << value;
  return out.str();
}

Verdict verdict_of(conic::SolveStatus status, bool settlement) {
  switch (status) {
    case conic::SolveStatus::Solved:
    case conic::SolveStatus::SolvedInaccurate: return Verdict::Collapse;
    case conic::SolveStatus::PrimalInfeasible: return Verdict::CannotStand;
    // Minimising a reaction that is >= 0 cannot be unbounded: that would be a solver failure.
    case conic::SolveStatus::DualInfeasible: return settlement ? Verdict::SolverFailure : Verdict::NoMechanism;
    case conic::SolveStatus::IterationLimit: return Verdict::IterationLimit;
    case conic::SolveStatus::TimeLimit: return Verdict::TimeLimit;
    case conic::SolveStatus::NumericalFailure: return Verdict::SolverFailure;
    case conic::SolveStatus::Cancelled: return Verdict::Cancelled;
  }
  return Verdict::SolverFailure;
}

/// Virtual power of the dead and live loads for the block motions (kN m per unit time).
void load_work(const model::Model& m, const std::vector<BlockMotion>& motions, bool settlement, double& dead,
               double& live) {
  dead = live = 0.0;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    const model::Block& block = m.blocks[b];
    if (block.is_support()) continue;
    dead += block.weight() * m.gravity.dot(motions[b].translation);
    if (!settlement && m.analysis.seismic_direction) {
      live += block.weight() * m.analysis.seismic_direction->dot(motions[b].translation);
    }
  }
  auto power = [&](const model::PointLoad& load) {
    return load.force.dot(point_velocity(m, motions, load.block, load.point)) + load.moment.dot(motions[load.block].rotation);
  };
  for (const auto& load : m.dead_loads) dead += power(load);
  if (!settlement) {
    for (const auto& load : m.live_loads) live += power(load);
  }
}

/// Largest force imbalance over the blocks' force rows, in kN, of A x - b.
double equilibrium_residual(const Formulation& f, const Eigen::VectorXd& x) {
  const Eigen::VectorXd r = f.problem.A * x - f.problem.b;
  double worst = 0.0;
  for (std::size_t b = 0; b < f.block_row.size(); ++b) {
    const int row = f.block_row[b];
    if (row < 0) continue;
    const int force_rows = f.rows_per_block == 6 ? 3 : 2;
    for (int k = 0; k < force_rows && row + k < f.first_radius_row; ++k) {
      worst = std::max(worst, std::abs(r[row + k]));
    }
  }
  return worst * f.force_scale;
}

conic::Settings solver_settings(const model::AnalysisRequest& request, const AnalysisOptions& options,
                                double time_left) {
  conic::Settings settings;
  settings.tol_gap_rel = request.tol_relative_gap;
  settings.tol_feas = request.tol_feasibility;
  settings.tol_infeas = std::max(request.tol_feasibility, 1e-10);
  // The caller checks for an exhausted budget first; a positive floor keeps the settings valid
  // when the clock runs out in between (the solver then stops at once with TimeLimit).
  settings.time_limit_seconds = std::max(time_left, 1e-6);
  settings.verbose = options.log != nullptr;
  settings.log_stream = options.log;
  settings.threads = options.threads;
  return settings;
}

double multiplier_value(const Formulation& f, const Eigen::VectorXd& x) {
  const double value = x[f.multiplier_variable];
  return f.settlement ? value * f.force_scale : value;
}

std::vector<double> normal_forces(const model::Model& m, const Formulation& f, const std::vector<Vec3>& forces) {
  std::vector<double> normals(forces.size());
  for (std::size_t p = 0; p < forces.size(); ++p) {
    normals[p] = std::max(0.0, forces[p].dot(m.interfaces[f.points[p].interface_index].normal));
  }
  return normals;
}

/// Fills the mechanism, work balance and accuracy of a solved problem.
void read_solution(const model::Model& m, const Formulation& f, const conic::Solution& solution, bool associative,
                   const std::vector<double>& radii, AnalysisResult& result) {
  const auto start = Clock::now();
  const std::vector<Vec3> forces = f.point_forces(solution.x);
  result.mechanism.blocks = block_velocities(m, f, solution.y);
  result.mechanism.normalisation = f.settlement ? Normalisation::UnitSettlement : Normalisation::MaxTranslation;
  // One unit of the user's length: displacements read in the user's units come out as 1.
  normalise(m, f, result.mechanism.normalisation, m.units.length_to_m, result.mechanism.blocks);
  fill_interfaces(m, f, forces, associative, result.mechanism);

  double dissipation = 0.0;
  if (!radii.empty()) {
    // Cylinder step: the fixed shear capacity r_k works against the slip (no dilatancy).
    for (std::size_t p = 0; p < f.points.size(); ++p) {
      const auto& interface_result = result.mechanism.interfaces[f.points[p].interface_index];
      double slip = 0.0;
      for (int k : f.points[p].corners) {
        const Vec3& dv = interface_result.points[k].relative_velocity;
        slip += std::hypot(dv[1], dv[2]) / static_cast<double>(f.points[p].corners.size());
      }
      dissipation += radii[p] * slip;
    }
  }
  double dead = 0.0, live = 0.0;
  load_work(m, result.mechanism.blocks, f.settlement, dead, live);
  WorkBalance& work = result.work;
  work.dead_work = dead;
  work.live_work = live;
  work.dissipation = dissipation;
  const double value = multiplier_value(f, solution.x);
  if (f.settlement) {
    // Virtual power: dead + (-R d).(v_s d) = dissipation, with v_s the normalised settlement.
    work.kinematic_value = (dead - dissipation) / m.units.length_to_m;
    work.relative_error = std::abs(value - work.kinematic_value) / std::max(std::abs(value), f.force_scale * 1e-12);
  } else if (live != 0.0) {
    work.kinematic_value = (dissipation - dead) / live;
    work.relative_error = std::abs(value - work.kinematic_value) / std::max(1.0, std::abs(value));
  }
  result.accuracy.relative_gap = solution.info.gap_rel;
  result.accuracy.primal_residual = solution.info.res_primal;
  result.accuracy.dual_residual = solution.info.res_dual;
  result.accuracy.equilibrium_residual = equilibrium_residual(f, solution.x);
  result.mechanism_seconds += seconds_since(start);
}

/// Which blocks fall, from a primal infeasibility certificate y (b^T y > 0, -A^T y in K*): a
/// kinematically admissible motion on which the dead loads do positive work.
void read_certificate(const model::Model& m, const Formulation& f, const conic::Solution& solution,
                      AnalysisResult& result) {
  result.mechanism.blocks = block_velocities(m, f, solution.y);
  result.mechanism.normalisation = Normalisation::MaxTranslation;
  normalise(m, f, Normalisation::MaxTranslation, m.units.length_to_m, result.mechanism.blocks);
  const std::vector<Vec3> no_forces(f.points.size(), Vec3::Zero());
  fill_interfaces(m, f, no_forces, true, result.mechanism);
}

void record_size(const Formulation& f, AnalysisResult& result) {
  result.size.num_variables = f.problem.A.cols();
  result.size.num_equality_rows = f.problem.A.rows();
  result.size.num_cones = static_cast<long>(f.problem.cones.num_nonneg + f.problem.cones.soc_dims.size());
  result.size.num_nonzeros = f.problem.A.nonZeros();
}

std::string count(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// The loss of base reaction at collapse needs the reaction before settlement; see
// initial_reaction.hpp for the definition used and why one is needed.
void record_initial_reaction(const model::Model& m, AnalysisResult& result) {
  const InitialReaction initial = initial_base_reaction(m, m.analysis.settlement_direction);
  if (!initial.value) {
    result.warnings.push_back({"initial_reaction_undefined",
                               "the base reaction before settlement (and so its loss) is not reported: " +
                                   initial.why_not,
                               "/analysis"});
    return;
  }
  result.initial_base_reaction = *initial.value;
  result.initial_base_lifts = initial.base_lifts;
  const double at_collapse = result.base_reaction.value_or(0.0);
  // R at collapse is the smallest admissible reaction; the rigid-body estimate ignores the joints
  // inside the structure, so it can fall below it when the structure could not carry that state.
  if (*initial.value < at_collapse - 1e-6 * std::max(1.0, std::abs(at_collapse))) {
    result.warnings.push_back({"initial_reaction_below_collapse",
                               "the base reaction before settlement, estimated with the structure as one rigid "
                               "body on elastic ground, is below the reaction at collapse: the joints cannot "
                               "carry that initial state, and the reported loss is negative",
                               "/analysis"});
  }
}

void write_verdict_text(const model::Model& m, AnalysisResult& result) {
  const std::string force_unit = m.units.force_name;
  std::size_t falling = 0;
  for (const auto& motion : result.mechanism.blocks) falling += motion.moving ? 1 : 0;
  const std::size_t cracked = result.mechanism.cracked_interfaces.size();
  switch (result.verdict) {
    case Verdict::Collapse:
      if (result.base_reaction) {
        std::string loss;
        if (result.initial_base_reaction) {
          const double r0 = *result.initial_base_reaction;
          loss = " (before settlement " + format(r0 / m.units.force_to_kN) + " " + force_unit + ", loss " +
                 format((r0 - *result.base_reaction) / m.units.force_to_kN) + " " + force_unit;
          if (r0 > 0) loss += " = " + format(100.0 * (r0 - *result.base_reaction) / r0, 3) + " %";
          loss += ")";
        }
        result.verdict_text = "Collapse under settlement: base reaction at collapse R = " +
                              format(*result.base_reaction / m.units.force_to_kN) + " " + force_unit + loss + "; " +
                              count(cracked, "interface cracks", "interfaces crack") + ".";
      } else {
        result.verdict_text = "Collapse at load multiplier alpha = " + format(result.load_multiplier.value_or(0.0)) +
                              "; " + count(falling, "block moves", "blocks move") + ", " +
                              count(cracked, "interface cracks", "interfaces crack") + ".";
      }
      break;
    case Verdict::NoMechanism:
      result.verdict_text = "No mechanism: the live load can grow without bound (alpha unbounded).";
      break;
    case Verdict::CannotStand:
      result.verdict_text = "Cannot stand under dead load alone: " + count(falling, "block falls", "blocks fall") + ".";
      break;
    case Verdict::SolverFailure:
      result.verdict_text = "No answer: the conic solver failed (" +
                            std::string(conic::to_string(result.solver_info.status)) + ").";
      break;
    case Verdict::TimeLimit: result.verdict_text = "No answer: the time limit ran out."; break;
    case Verdict::IterationLimit: result.verdict_text = "No answer: the iteration limit ran out."; break;
    case Verdict::Cancelled: result.verdict_text = "Cancelled before an answer."; break;
  }
}

// The admissible multipliers form an interval [alpha_min, alpha_max] (the problem is convex).
// Maximising alpha answers "collapse at alpha_max" only if alpha = 0 is in it: a block resting
// off-centre on a narrow post can be held by a push of 0.59 to 0.6 of its weight and by nothing
// less. So alpha_min is found with the same solver (objective reversed, symbolic analysis kept);
// above the threshold the structure cannot stand under its dead load, and the dual of that solve
// (a mechanism on which the dead load does positive work) names the falling blocks.
// analysis.check_dead_load = false skips this solve.
bool stands_only_when_pushed(const model::Model& m, const model::AnalysisRequest& request,
                             const Formulation& formulation, conic::ConicSolver& solver,
                             double alpha_max, double time_left, AnalysisResult& result) {
  if (!request.check_dead_load || time_left <= 0.0) return false;
  const auto start = Clock::now();
  const Eigen::VectorXd c_max = solver.problem().c;
  solver.update_c(-c_max);
  conic::Settings& settings = solver.settings();
  const conic::Settings saved = settings;
  // Only alpha_min against the threshold below matters: a gap of a tenth of it is enough.
  const double threshold = std::max(1e-5, 1e-3 * alpha_max);
  settings.tol_gap_rel = settings.tol_gap_abs = 0.1 * threshold;
  settings.time_limit_seconds = std::max(time_left, 1e-6);
  const conic::Solution low = solver.solve();
  settings = saved;
  solver.update_c(c_max);
  result.solve_seconds += seconds_since(start);
  if (!conic::has_solution(low.info.status)) return false;
  const double alpha_min = multiplier_value(formulation, low.x);
  // Ten times the solve's accuracy and a visible share of alpha_max: 1e-5 absolute or 1e-3 of
  // alpha_max.
  if (!(alpha_min > threshold)) return false;
  read_certificate(m, formulation, low, result);
  result.warnings.push_back({"stands_only_when_pushed",
                             "the structure is in equilibrium only for load multipliers from " +
                                 format(alpha_min) + " up: without the live load it cannot stand",
                             ""});
  return true;
}

// analysis.pyramid_bracket: solves the other pyramid (same faces) and records both values. In a
// planar scene both pyramids are the exact two-edge cone, so the value is the bracket.
void bracket_pyramids(const model::Model& m, const model::AnalysisRequest& request,
                      const FormulationOptions& options_used, double value, double time_left,
                      const AnalysisOptions& options, AnalysisResult& result) {
  if (request.cone == model::ConeKind::Exact || request.friction_model != model::FrictionModel::Associative) {
    result.warnings.push_back({"pyramid_bracket_not_computed",
                               "the pyramid bracket needs a pyramid cone and associative friction",
                               "/analysis/pyramid_bracket"});
    return;
  }
  const bool inscribed = request.cone == model::ConeKind::PyramidInscribed;
  if (result.planar) {
    result.accuracy.pyramid_bracket = std::make_pair(value, value);
    return;
  }
  FormulationOptions other = options_used;
  other.cone = inscribed ? model::ConeKind::PyramidCircumscribed : model::ConeKind::PyramidInscribed;
  const auto start = Clock::now();
  const Formulation formulation = build_formulation(m, other);
  result.assemble_seconds += seconds_since(start);
  const auto solve_start = Clock::now();
  conic::ConicSolver solver(formulation.problem, solver_settings(request, options, time_left));
  const conic::Solution solution = solver.solve();
  result.solve_seconds += seconds_since(solve_start);
  if (solution.info.status != conic::SolveStatus::Solved &&
      solution.info.status != conic::SolveStatus::SolvedInaccurate) {
    result.warnings.push_back({"pyramid_bracket_not_computed",
                               std::string("the other pyramid's solve ended with ") +
                                   conic::to_string(solution.info.status),
                               "/analysis/pyramid_bracket"});
    return;
  }
  const double other_value = multiplier_value(formulation, solution.x);
  result.accuracy.pyramid_bracket =
      inscribed ? std::make_pair(value, other_value) : std::make_pair(other_value, value);
}

}  // namespace

AnalysisResult analyse(const model::Model& m, const AnalysisOptions& options) {
  const auto start = Clock::now();
  const model::AnalysisRequest& request = m.analysis;
  AnalysisResult result;
  result.type = request.type;
  result.friction_model = request.friction_model;
  result.cone = request.cone;
  result.pyramid_faces = request.cone == model::ConeKind::Exact ? 0 : request.pyramid_faces;
  result.settlement_direction = request.settlement_direction;

  const PlanarFrame frame = detect_planar(m);
  if (request.formulation == model::Formulation::Planar && !frame.planar) {
    throw model::ModelError("/analysis/formulation", "the scene is not planar: " + frame.reason);
  }
  result.planar = request.formulation == model::Formulation::Planar ||
                  (request.formulation == model::Formulation::Auto && frame.planar);
  result.planar_axis = result.planar ? frame.axis : -1;
  if (result.planar && request.cone != model::ConeKind::Exact) {
    result.warnings.push_back({"pyramid_not_needed",
                               "the scene is planar: its friction cone has exactly two edges, so the pyramid "
                               "setting changes nothing",
                               "/analysis/cone"});
  }

  FormulationOptions formulation_options;
  formulation_options.cone = request.cone;
  formulation_options.pyramid_faces = request.pyramid_faces;
  formulation_options.planar = result.planar;
  formulation_options.frame = frame;
  const Formulation formulation = build_formulation(m, formulation_options);
  record_size(formulation, result);
  result.assemble_seconds = seconds_since(start);
  if (!options.dump_problem_path.empty()) {
    const std::string& path = options.dump_problem_path;
    const bool mps = path.size() > 4 && path.compare(path.size() - 4, 4, ".mps") == 0;
    if (mps) conic::write_mps(formulation.problem, path);
    else conic::write_cbf(formulation.problem, path);
  }

  auto time_left = [&] {
    if (request.time_limit_seconds <= 0.0) return std::numeric_limits<double>::infinity();
    return std::max(0.0, request.time_limit_seconds - seconds_since(start));
  };

  if (time_left() <= 0.0) {
    result.verdict = Verdict::TimeLimit;
    write_verdict_text(m, result);
    return result;
  }
  const auto solve_start = Clock::now();
  conic::ConicSolver solver(formulation.problem, solver_settings(request, options, time_left()));
  if (options.progress) solver.set_progress_callback(options.progress);
  conic::Solution solution = solver.solve();
  result.solve_seconds += seconds_since(solve_start);
  result.solver_info = solution.info;
  result.interior_point_history = solution.info.history;
  result.verdict = verdict_of(solution.info.status, formulation.settlement);
  if (solution.info.status == conic::SolveStatus::SolvedInaccurate) {
    result.warnings.push_back({"inaccurate_solution",
                               "the conic solver met only its reduced tolerances (relative gap " +
                                   format(solution.info.gap_rel, 3) + ")",
                               ""});
  }

  if (result.verdict == Verdict::CannotStand) {
    read_certificate(m, formulation, solution, result);
  } else if (result.verdict == Verdict::Collapse && !formulation.settlement &&
             stands_only_when_pushed(m, request, formulation, solver,
                                     multiplier_value(formulation, solution.x), time_left(), result)) {
    result.verdict = Verdict::CannotStand;
  } else if (result.verdict == Verdict::Collapse) {
    read_solution(m, formulation, solution, true, {}, result);
    double value = multiplier_value(formulation, solution.x);
    if (request.pyramid_bracket) bracket_pyramids(m, request, formulation_options, value, time_left(), options, result);

    if (request.friction_model == model::FrictionModel::NonAssociative) {
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
      // A small floor keeps every cylinder with an interior (METHOD.md).
      const double floor = 1e-9 * formulation.force_scale;
      std::vector<double> radii(normals.size());
      for (std::size_t p = 0; p < radii.size(); ++p) radii[p] = std::max(floor, cylinder.points[p].friction * normals[p]);

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
      settings.tol_feas = std::max(request.tol_feasibility, 0.1 * step_tol);
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
        cylinder_solver.settings().tol_feas = std::max(request.tol_feasibility, 0.1 * step_tol);
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
          radii[p] = std::max(floor, d * cylinder.points[p].friction * normals[p] + (1.0 - d) * radii[p]);
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
    if (result.verdict == Verdict::Collapse) {
      if (formulation.settlement) {
        result.base_reaction = value;
        record_initial_reaction(m, result);
      } else {
        result.load_multiplier = value;
      }
    }
  }
  write_verdict_text(m, result);
  return result;
}

}  // namespace rbla::analysis
