#include "analysis/compatible_states.hpp"

#include "analysis/mechanism.hpp"

#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>

namespace rbla::analysis {

namespace {

/// How closely a state found must match its pattern, over the largest normal force: far above the
/// solves' tolerances (1e-8). An independent review found no state within 3e-4 of matching on the
/// mechanisms where none matches.
constexpr double kFoundTolerance = 1e-6;

/// The friction a point can carry against a slip along the unit tangent t, per unit normal
/// force: mu for the exact cone, the reach of the pyramid (or of the planar cone's edges) in
/// that direction, max_j (-g_j . t) / (g_j . n) over its edge generators.
double reach_against(const Formulation& f, const FormulationPoint& point, const Vec3& n, const Vec3& t) {
  double reach = 0.0;
  for (const Generator& g : point.generators) {
    if (g.variable >= f.problem.cones.num_nonneg) return point.friction;  // a second-order cone
    const double normal = g.force.dot(n);
    if (normal > 0.0) reach = std::max(reach, -g.force.dot(t) / normal);
  }
  return reach;
}

/// The rows that make a state compatible with the pattern: N = 0 at opening points, and
/// T . t + reach N = 0 at sliding points (with T in the friction set, that is T = -mu N t for a
/// cone: the full friction against the slip), each in its point's force units.
std::vector<Eigen::Triplet<double>> pattern_rows(const model::Model& m, const Formulation& f,
                                                 const PointPattern& pattern, Eigen::Index first_row, Eigen::Index& rows) {
  std::vector<Eigen::Triplet<double>> triplets;
  rows = 0;
  for (std::size_t p = 0; p < f.points.size(); ++p) {
    if (pattern.motion[p] == PointPattern::Motion::Closed) continue;
    const FormulationPoint& point = f.points[p];
    const Vec3& n = m.interfaces[point.interface_index].normal;
    const bool opens = pattern.motion[p] == PointPattern::Motion::Opens;
    const Vec3& t = pattern.slip_direction[p];
    const double reach = opens ? 0.0 : reach_against(f, point, n, t);
    for (const Generator& g : point.generators) {
      const double entry = opens ? g.force.dot(n) : g.force.dot(t) + reach * g.force.dot(n);
      if (entry != 0.0) triplets.emplace_back(static_cast<int>(first_row + rows), g.variable, entry);
    }
    ++rows;
  }
  return triplets;
}

/// `f`'s problem with the pattern's rows appended (right-hand side 0).
conic::ConicProblem problem_with_pattern(const model::Model& m, const Formulation& f, const PointPattern& pattern) {
  conic::ConicProblem problem = f.problem;
  const Eigen::SparseMatrix<double>& A = f.problem.A;
  Eigen::Index extra = 0;
  std::vector<Eigen::Triplet<double>> triplets = pattern_rows(m, f, pattern, A.rows(), extra);
  triplets.reserve(triplets.size() + static_cast<std::size_t>(A.nonZeros()));
  for (int col = 0; col < A.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, col); it; ++it) triplets.emplace_back(it.row(), col, it.value());
  }
  problem.A.resize(A.rows() + extra, A.cols());
  problem.A.setFromTriplets(triplets.begin(), triplets.end());
  problem.A.makeCompressed();
  problem.b = Eigen::VectorXd::Zero(A.rows() + extra);
  problem.b.head(A.rows()) = f.problem.b;
  return problem;
}

/// The solution restricted to `f`'s own rows (the pattern's multipliers dropped).
conic::Solution in_formulation_rows(conic::Solution s, Eigen::Index rows) {
  if (s.y.size() > rows) s.y.conservativeResize(rows);
  return s;
}

}  // namespace

PointPattern point_pattern(const model::Model& m, const Formulation& f, const Eigen::VectorXd& y) {
  const std::vector<Vec3> d = formulation_point_velocities(m, f, y);
  double largest = 0.0;
  for (const Vec3& v : d) largest = std::max(largest, v.norm());
  PointPattern pattern;
  pattern.motion.assign(d.size(), PointPattern::Motion::Closed);
  pattern.slip_direction.assign(d.size(), Vec3::Zero());
  const double threshold = kMovingPointFraction * largest;
  for (std::size_t p = 0; p < d.size(); ++p) {
    const Vec3& n = m.interfaces[f.points[p].interface_index].normal;
    const double opening = d[p].dot(n);
    const Vec3 slip = d[p] - opening * n;
    if (opening > threshold) {
      pattern.motion[p] = PointPattern::Motion::Opens;
      ++pattern.opening;
    } else if (slip.norm() > threshold) {
      pattern.motion[p] = PointPattern::Motion::Slides;
      pattern.slip_direction[p] = slip.normalized();
      ++pattern.sliding;
    }
  }
  return pattern;
}

PatternViolation pattern_violation(const model::Model& m, const Formulation& f, const PointPattern& pattern,
                                   const Eigen::VectorXd& x) {
  const std::vector<Vec3> forces = f.point_forces(x);
  double largest = 0.0;
  PatternViolation v;
  for (std::size_t p = 0; p < forces.size(); ++p) {
    const Vec3& n = m.interfaces[f.points[p].interface_index].normal;
    const double normal = forces[p].dot(n);
    largest = std::max(largest, normal);
    if (pattern.motion[p] == PointPattern::Motion::Opens) v.open_force = std::max(v.open_force, normal);
    if (pattern.motion[p] == PointPattern::Motion::Slides) {
      const Vec3& t = pattern.slip_direction[p];
      const double shortfall = reach_against(f, f.points[p], n, t) * normal + forces[p].dot(t);
      v.friction_shortfall = std::max(v.friction_shortfall, shortfall);
    }
  }
  if (largest > 0.0) {
    v.open_force /= largest;
    v.friction_shortfall /= largest;
  }
  return v;
}

CompatibleStates compatible_states(const model::Model& m, const Formulation& f, const PointPattern& pattern,
                                   const Eigen::VectorXd& cost, const conic::Settings& settings) {
  CompatibleStates states;
  conic::Settings s = settings;
  s.snapshot_gap_rel = 0.0;
  conic::ConicSolver solver(problem_with_pattern(m, f, pattern), s);
  const Eigen::Index rows = f.problem.A.rows();
  // The analysis minimises `cost` (-alpha, or R): its conservative end minimises -cost.
  solver.update_c(-cost);
  states.conservative = in_formulation_rows(solver.solve(), rows);
  states.iterations += states.conservative.info.iterations;
  if (states.conservative.info.status == conic::SolveStatus::PrimalInfeasible) {
    states.outcome = CompatibleStates::Outcome::None;
    return states;
  }
  if (!conic::has_solution(states.conservative.info.status)) return states;
  solver.update_c(cost);
  states.other = in_formulation_rows(solver.solve(), rows);
  states.iterations += states.other.info.iterations;
  if (!conic::has_solution(states.other.info.status)) return states;
  // A solve that met only its reduced tolerances may leave the rows loosely satisfied: the state is
  // kept only if it matches the pattern to kFoundTolerance of the largest normal force.
  const PatternViolation v = pattern_violation(m, f, pattern, states.conservative.x);
  if (std::max(v.open_force, v.friction_shortfall) <= kFoundTolerance) states.outcome = CompatibleStates::Outcome::Found;
  return states;
}

}  // namespace rbla::analysis
