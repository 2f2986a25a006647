#pragma once
// Deterministic random conic problems with a known strictly feasible primal-dual pair:
// b = A x0, c = Aᵀy0 + z0 with x0, z0 in the interior of K, so an optimum exists.

#include <random>

#include "rbla/conic/problem.hpp"

namespace rbla::conic::testing {

struct RandomProblemOptions {
  int rows = 100;
  int num_nonneg = 150;
  int num_soc3 = 60;  ///< number of 3-dimensional cones
  int nnz_per_column = 3;
  int band = 0;           ///< > 0: a column's rows lie within `band` of a position moving
                          ///< with the column index (a banded M, like a structure's)
  int dense_columns = 0;  ///< extra nonnegative columns touching every row (placed first)
  unsigned seed = 1;
};

inline ConicProblem random_feasible_problem(const RandomProblemOptions& o) {
  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<double> uniform(0.5, 2.0);
  std::normal_distribution<double> normal;
  std::uniform_int_distribution<int> pick_row(0, o.rows - 1);
  ConicProblem p;
  p.cones.num_nonneg = o.num_nonneg + o.dense_columns;
  p.cones.soc_dims.assign(static_cast<std::size_t>(o.num_soc3), 3);
  const int n = static_cast<int>(p.cones.dimension());
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < n; ++j) {
    if (j < o.dense_columns) {
      for (int i = 0; i < o.rows; ++i) t.emplace_back(i, j, normal(rng));
    } else {
      const int centre = static_cast<int>(static_cast<long>(j) * o.rows / n);
      for (int k = 0; k < o.nnz_per_column; ++k) {
        const int row = o.band > 0 ? (centre + pick_row(rng) % o.band) % o.rows : pick_row(rng);
        t.emplace_back(row, j, normal(rng));
      }
    }
  }
  for (int i = 0; i < o.rows; ++i)
    t.emplace_back(i, o.dense_columns + (i % std::max(1, o.num_nonneg)), 1.0);
  p.A.resize(o.rows, n);
  p.A.setFromTriplets(t.begin(), t.end());
  p.A.makeCompressed();
  Eigen::VectorXd x0(n), z0(n), y0(o.rows);
  for (int j = 0; j < p.cones.num_nonneg; ++j) {
    x0[j] = uniform(rng);
    z0[j] = uniform(rng);
  }
  for (int k = 0; k < o.num_soc3; ++k) {
    const int j = static_cast<int>(p.cones.num_nonneg) + 3 * k;
    for (Eigen::VectorXd* v : {&x0, &z0}) {
      (*v)[j + 1] = normal(rng);
      (*v)[j + 2] = normal(rng);
      (*v)[j] = std::hypot((*v)[j + 1], (*v)[j + 2]) + uniform(rng);
    }
  }
  for (int i = 0; i < o.rows; ++i) y0[i] = normal(rng);
  p.b = p.A * x0;
  p.c = p.A.transpose() * y0 + z0;
  return p;
}

}  // namespace rbla::conic::testing
