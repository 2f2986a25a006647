#include "iteration_log.hpp"

#include <cstdio>

namespace rbla::conic::detail {

void print_banner(std::ostream& out, const ConicProblem& p, const NormalEquations& normal,
                  const Info& info) {
  char line[512];
  std::snprintf(
      line, sizeof line,
      "rbla conic interior point (HSDE, NT scaling, Mehrotra predictor-corrector)\n"
      "  rows %lld, variables %lld, nnz(A) %lld, nonnegative %lld, second-order cones %zu\n"
      "  dense columns %d, fixed rows eliminated %d, nnz(M) %ld, nnz(L) %ld, factor %.2e flops "
      "%.0f MB, %s\n",
      static_cast<long long>(p.A.rows()), static_cast<long long>(p.A.cols()),
      static_cast<long long>(p.A.nonZeros()), static_cast<long long>(p.cones.num_nonneg),
      p.cones.soc_dims.size(), info.num_dense_columns, normal.num_fixed_rows(),
      normal.num_matrix_nonzeros(),
      info.num_factor_nonzeros, normal.factor_flops(), info.factor_bytes / 1e6,
      info.backend.c_str());
  out << line
      << "iter  primal obj       dual obj         gap_rel   res_pri   res_dual  mu        "
         "tau       kappa     step    sigma   ref\n";
}

void print_row(std::ostream& out, const IterationRow& r) {
  char line[256];
  std::snprintf(line, sizeof line,
                "%4d  %+.9e  %+.9e  %8.2e  %8.2e  %8.2e  %8.2e  %8.2e  %8.2e  %6.4f  %6.4f  %3d\n",
                r.iteration, r.primal_objective, r.dual_objective, r.gap_rel, r.res_primal,
                r.res_dual, r.mu, r.tau, r.kappa, r.step, r.sigma, r.refine_steps);
  out << line;
}

void print_footer(std::ostream& out, const Info& info, long solves, long multiplies) {
  char line[512];
  std::snprintf(line, sizeof line,
                "status: %s%s%s\niterations %d from the %s point, primal %.12g, dual %.12g\n"
                "time [s]: setup %.3f (symbolic %.3f), assembly %.3f, factor %.3f, solve %.3f, "
                "total %.3f; refactor retries %d\n"
                "solves with the factor %ld, products with M %ld, centrality correctors %d "
                "(%d kept)\n",
                to_string(info.status), info.failure_reason.empty() ? "" : " - ",
                info.failure_reason.c_str(), info.iterations,
                info.warm_started ? "warm-start" : info.least_squares_start ? "least-squares" : "unit",
                info.primal_objective,
                info.dual_objective, info.setup_seconds, info.symbolic_seconds,
                info.assembly_seconds, info.factor_seconds, info.solve_seconds,
                info.total_seconds, info.num_refactor_retries, solves, multiplies,
                info.num_centrality_correctors, info.num_centrality_correctors_accepted);
  out << line;
}

}  // namespace rbla::conic::detail
