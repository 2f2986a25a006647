// rbla_conic_wall_bench: a facade-scale synthetic limit-analysis problem (see
// tests/unit/conic/wall_problem.hpp for the exact construction) to measure the conic solver's
// iterations and time per phase.
//
//   rbla_conic_wall_bench [nx ny] [--out-of-plane] [--pyramid] [--no-dense-columns]
//                         [--metis | --cholmod-default] [--friction 0.6] [--verbose]
//                         [--dump problem.cbf] [--tol 1e-8 (gap and feasibility)]
// Default 38 x 50 courses: 1925 blocks, 22548 contact points.

#include <cstdio>
#include <string>
#include <vector>

#include "../../tests/unit/conic/wall_problem.hpp"
#include "rbla/conic/io.hpp"
#include "rbla/conic/solver.hpp"

int main(int argc, char** argv) {
  rbla::conic::testing::WallOptions wall;
  rbla::conic::Settings settings;
  std::string dump;
  std::vector<std::string> positional;
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--out-of-plane")
      wall.out_of_plane = true;
    else if (arg == "--pyramid")
      wall.pyramid = true;
    else if (arg == "--no-dense-columns")
      settings.dense_columns = false;
    else if (arg == "--metis")
      settings.ordering = rbla::conic::Ordering::Metis;
    else if (arg == "--cholmod-default")
      settings.ordering = rbla::conic::Ordering::CholmodDefault;
    else if (arg == "--verbose")
      settings.verbose = true;
    else if (arg == "--dump" && k + 1 < argc)
      dump = argv[++k];
    else if (arg == "--tol" && k + 1 < argc)
      settings.tol_gap_abs = settings.tol_gap_rel = settings.tol_feas = std::stod(argv[++k]);
    else if (arg == "--friction" && k + 1 < argc)
      wall.friction = std::stod(argv[++k]);
    else if (!arg.empty() && arg[0] != '-')
      positional.push_back(arg);
    else {
      std::fprintf(stderr, "unknown option %s\n", arg.c_str());
      return 2;
    }
  }
  if (positional.size() == 2) {
    wall.nx = std::stoi(positional[0]);
    wall.ny = std::stoi(positional[1]);
  }
  const auto generated = rbla::conic::testing::make_wall_problem(wall);
  const auto& p = generated.problem;
  std::printf(
      "wall %d x %d: %d blocks, %d interfaces, %d contact points (%s); rows %ld, variables %ld, "
      "nnz(A) %ld\n",
      wall.nx, wall.ny, generated.num_blocks, generated.num_interfaces, generated.num_points,
      wall.pyramid ? "pyramid LP" : "cones", static_cast<long>(p.A.rows()),
      static_cast<long>(p.A.cols()), static_cast<long>(p.A.nonZeros()));
  if (!dump.empty()) rbla::conic::write_cbf(p, dump);

  rbla::conic::ConicSolver solver(p, settings);
  const rbla::conic::Solution sol = solver.solve();
  const auto& info = sol.info;
  std::printf(
      "status %s, iterations %d, alpha %.10g (dual %.10g), gap_rel %.2e, res_pri %.2e, res_dual "
      "%.2e\n",
      rbla::conic::to_string(info.status), info.iterations, -info.primal_objective,
      -info.dual_objective, info.gap_rel, info.res_primal, info.res_dual);
  std::printf("dense columns %d%s, nnz(L) %ld, refactor retries %d, backend %s\n",
              info.num_dense_columns, info.dense_column_fallback ? " (fallback used)" : "",
              info.num_factor_nonzeros, info.num_refactor_retries, info.backend.c_str());
  std::printf(
      "time [s]: setup %.3f (symbolic %.3f) | assembly %.3f, factor %.3f, solve %.3f | solve() "
      "total %.3f\n",
      info.setup_seconds, info.symbolic_seconds, info.assembly_seconds, info.factor_seconds,
      info.solve_seconds, info.total_seconds);
  return rbla::conic::has_solution(info.status) ? 0 : 1;
}
