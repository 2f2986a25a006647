#include "rbla/conic/info.hpp"

#include <cstdio>

namespace rbla::conic {

const char* to_string(SolveStatus status) {
  switch (status) {
    case SolveStatus::Solved:
      return "solved";
    case SolveStatus::SolvedInaccurate:
      return "solved (reduced accuracy)";
    case SolveStatus::PrimalInfeasible:
      return "primal infeasible";
    case SolveStatus::DualInfeasible:
      return "dual infeasible (primal unbounded)";
    case SolveStatus::IterationLimit:
      return "iteration limit";
    case SolveStatus::TimeLimit:
      return "time limit";
    case SolveStatus::NumericalFailure:
      return "numerical failure";
    case SolveStatus::Cancelled:
      return "cancelled";
  }
  return "unknown";
}

bool has_solution(SolveStatus status) {
  return status == SolveStatus::Solved || status == SolveStatus::SolvedInaccurate;
}

std::string Info::brief_report() const {
  char line[256];
  std::snprintf(
      line, sizeof line, "%s after %d iterations: primal %.10g, dual %.10g, gap_rel %.2e, %.3f s",
      to_string(status), iterations, primal_objective, dual_objective, gap_rel, total_seconds);
  return line;
}

}  // namespace rbla::conic
