// rbla_conic_cbf_solve: solves a CBF file (the subset rbla::conic::write_cbf writes) and prints
// one JSON object with the outcome. Used by tests/crosscheck/crosscheck_cvxopt.py.
//   rbla_conic_cbf_solve problem.cbf [--verbose] [--no-equilibrate] [--central-start]
//                        [--no-dense-columns] [--ordering best|amd|metis|default] [--correctors K]
//                        [--blas-threads N] [--threads 1|2] [--split-min-rows R]
//                        [--reg-static D] [--refine-tol T] [--step-fraction F] [--sigma-skip F]
//                        [--perturb-b E] [--perturb-c E] [--write-solution FILE]
// --central-start starts from x = z = e instead of the least-squares point; --perturb-b and
// --perturb-c add seeded noise to b and c (a test of whether ties slow a solve).
// --write-solution writes x, y and z, one number per line after a line "x n", "y m", "z n", for
// a check of the solution by another program (bench/conic/highs_lp.py --check).

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <exception>
#include <iostream>

#include "rbla/conic/io.hpp"
#include "rbla/conic/solver.hpp"

namespace {

void write_vector(std::FILE* file, const char* name, const Eigen::VectorXd& v) {
  std::fprintf(file, "%s %ld\n", name, static_cast<long>(v.size()));
  for (Eigen::Index i = 0; i < v.size(); ++i) std::fprintf(file, "%.17g\n", v[i]);
}

void write_solution(const char* path, const rbla::conic::Solution& solution) {
  std::FILE* file = std::fopen(path, "w");
  if (!file) {
    std::fprintf(stderr, "error: cannot write %s\n", path);
    std::exit(1);
  }
  write_vector(file, "x", solution.x);
  write_vector(file, "y", solution.y);
  write_vector(file, "z", solution.z);
  if (std::fclose(file) != 0) {
    std::fprintf(stderr, "error: cannot write %s\n", path);
    std::exit(1);
  }
}

// Adds uniform noise of relative size eps_b (of ‖b‖∞) to every b_i and of absolute size eps_c
// to every c_j, from a fixed seed: ties between optimal solutions (a degenerate optimal face)
// are broken, the problem is otherwise the same to that size.
void perturb(double eps_b, double eps_c, rbla::conic::ConicProblem& problem) {
  std::mt19937_64 random(1);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double b_size = problem.b.lpNorm<Eigen::Infinity>();
  if (eps_b != 0.0)
    for (Eigen::Index i = 0; i < problem.b.size(); ++i) problem.b[i] += eps_b * b_size * unit(random);
  if (eps_c != 0.0)
    for (Eigen::Index j = 0; j < problem.c.size(); ++j) problem.c[j] += eps_c * unit(random);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: %s problem.cbf [--verbose] [--no-equilibrate] [--central-start] [--no-dense-columns] [--ordering best|amd|metis|default] [--correctors K] [--blas-threads N] [--threads 1|2] [--split-min-rows R] [--reg-static D] [--refine-tol T] [--step-fraction F] [--sigma-skip F] [--perturb-b E] [--perturb-c E] [--write-solution FILE]\n",
                 argv[0]);
    return 2;
  }
  rbla::conic::Settings settings;
  const char* solution_path = nullptr;
  double perturb_b = 0.0, perturb_c = 0.0;
  for (int k = 2; k < argc; ++k) {
    if (std::strcmp(argv[k], "--verbose") == 0) {
      settings.verbose = true;
      settings.log_stream = &std::cerr;
    } else if (std::strcmp(argv[k], "--no-equilibrate") == 0) {
      settings.equilibrate = false;
    } else if (std::strcmp(argv[k], "--central-start") == 0) {
      settings.least_squares_start = false;
    } else if (std::strcmp(argv[k], "--no-dense-columns") == 0) {
      settings.dense_columns = false;
    } else if (std::strcmp(argv[k], "--blas-threads") == 0 && k + 1 < argc) {
      settings.blas_threads = std::atoi(argv[++k]);
    } else if (std::strcmp(argv[k], "--threads") == 0 && k + 1 < argc) {
      settings.threads = std::atoi(argv[++k]);
    } else if (std::strcmp(argv[k], "--split-min-rows") == 0 && k + 1 < argc) {
      settings.split_min_rows = std::atoi(argv[++k]);
    } else if (std::strcmp(argv[k], "--correctors") == 0 && k + 1 < argc) {
      settings.max_centrality_correctors = std::atoi(argv[++k]);
    } else if (std::strcmp(argv[k], "--ordering") == 0 && k + 1 < argc) {
      const char* name = argv[++k];
      settings.ordering = std::strcmp(name, "metis") == 0     ? rbla::conic::Ordering::Metis
                          : std::strcmp(name, "default") == 0 ? rbla::conic::Ordering::CholmodDefault
                          : std::strcmp(name, "amd") == 0     ? rbla::conic::Ordering::Amd
                                                              : rbla::conic::Ordering::Best;
    } else if (std::strcmp(argv[k], "--reg-static") == 0 && k + 1 < argc) {
      settings.reg_static = std::atof(argv[++k]);
    } else if (std::strcmp(argv[k], "--refine-tol") == 0 && k + 1 < argc) {
      settings.refine_tol_rel = std::atof(argv[++k]);
    } else if (std::strcmp(argv[k], "--write-solution") == 0 && k + 1 < argc) {
      solution_path = argv[++k];
    } else if (std::strcmp(argv[k], "--perturb-b") == 0 && k + 1 < argc) {
      perturb_b = std::atof(argv[++k]);
    } else if (std::strcmp(argv[k], "--perturb-c") == 0 && k + 1 < argc) {
      perturb_c = std::atof(argv[++k]);
    } else if (std::strcmp(argv[k], "--sigma-skip") == 0 && k + 1 < argc) {
      settings.sigma_skip_fraction = std::atof(argv[++k]);
    } else if (std::strcmp(argv[k], "--step-fraction") == 0 && k + 1 < argc) {
      settings.step_fraction = std::atof(argv[++k]);
    } else {
      std::fprintf(stderr, "unknown option %s\n", argv[k]);
      return 2;
    }
  }
  try {
    rbla::conic::ConicProblem problem = rbla::conic::read_cbf_file(argv[1]);
    perturb(perturb_b, perturb_c, problem);
    const rbla::conic::Solution solution = rbla::conic::solve(problem, settings);
    const auto& info = solution.info;
    std::printf(
        "{\"status\": \"%s\", \"primal_objective\": %.17g, \"dual_objective\": %.17g, "
        "\"iterations\": %d, \"res_primal\": %.3e, \"res_dual\": %.3e, \"gap_rel\": %.3e, "
        "\"total_seconds\": %.6f}\n",
        rbla::conic::to_string(info.status), info.primal_objective, info.dual_objective,
        info.iterations, info.res_primal, info.res_dual, info.gap_rel, info.total_seconds);
    if (solution_path) write_solution(solution_path, solution);
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
    return 1;
  }
}
