#include "analysis/settlement_bound.hpp"

#include "analysis/text.hpp"

#include <string>

namespace rbla::analysis {

bool reaction_on_its_bound(const Formulation& f, const conic::Solution& solution) {
  const int r = f.multiplier_variable;
  const double reduced_cost = f.problem.c[r] - f.problem.A.col(r).dot(solution.y);
  return reduced_cost > kSettlementBoundCost * f.problem.c[r];
}

namespace {

/// The same problem along -d, solved: a solution is a state of S with G . d <= 0.
bool solve_reversed(const model::Model& m, const AnalysisOptions& options, const FormulationOptions& used,
                    const Deadline& deadline, AnalysisResult& result) {
  if (deadline.left() <= 0.0) return false;
  model::Model reversed = m;
  reversed.analysis.settlement_direction = -m.analysis.settlement_direction;
  const auto start = Clock::now();
  const Formulation f = build_formulation(reversed, used);
  result.assemble_seconds += seconds_since(start);
  const auto solve_start = Clock::now();
  conic::ConicSolver solver(f.problem, solver_settings(reversed.analysis, options, deadline.left()));
  const conic::Solution solution = solver.solve();
  result.solve_seconds += seconds_since(solve_start);
  if (!conic::has_solution(solution.info.status)) return false;
  // The result's solver record is of the last solve: this one.
  result.solver_info = solution.info;
  result.interior_point_history = solution.info.history;
  read_solution(reversed, f, solution, true, result);
  return true;
}

}  // namespace

bool settlement_forms_no_mechanism(const model::Model& m, const AnalysisOptions& options,
                                   const FormulationOptions& used, const Formulation& f,
                                   const conic::Solution& solution, const Deadline& deadline,
                                   AnalysisResult& result) {
  if (!f.settlement) return false;
  if (result.verdict == Verdict::Collapse && reaction_on_its_bound(f, solution)) {
    read_solution(m, f, solution, true, result);
  } else if (result.verdict == Verdict::CannotStand && solve_reversed(m, options, used, deadline, result)) {
    result.settlement_pushes_back = true;
  } else {
    return false;
  }
  result.verdict = Verdict::NoMechanism;
  result.mechanism.arbitrary_blocks.clear();  // no mechanism is reported
  return true;
}

std::string no_settlement_collapse_text(const model::Model& m, const AnalysisResult& result) {
  std::string before;
  if (result.initial_base_reaction) {
    before = " (" + format(*result.initial_base_reaction / m.units.force_to_kN) + " " + m.units.force_name +
             " before settlement)";
  }
  if (result.settlement_pushes_back) {
    return "No mechanism under settlement along this direction: in every state that holds the structure it pushes "
           "the moving supports back against the direction, so their reaction along it" + before +
           " is not needed and settling along it forms no mechanism; with the supports held the structure stands.";
  }
  return "No mechanism under settlement along this direction: the moving supports' reaction along it" + before +
         " can fall to 0 with the structure in equilibrium, so settling along it forms no mechanism.";
}

}  // namespace rbla::analysis
