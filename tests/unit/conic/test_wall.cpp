// Limit-analysis-shaped problems (tests/unit/conic/wall_problem.hpp): a running-bond wall on a
// fixed base under a horizontal load α W_i on every block.
//
// Oracle (docs/method.md, "An exact check for in-plane loads"): for an in-plane load on a wall symmetric about its
// mid-plane, some optimum has no out-of-plane friction, so the axis-aligned 4-sided pyramid LP
// gives the exact α of the cone problem. The LP is also dumped to MPS and solved by Clp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "rbla/conic/io.hpp"
#include "rbla/conic/solver.hpp"
#include "test_helpers.hpp"
#include "wall_problem.hpp"

using namespace rbla::conic;
using namespace rbla::conic::testing;

namespace {

WallOptions small_wall() {
  WallOptions o;
  o.nx = 8;
  o.ny = 6;
  o.friction = 0.8;
  return o;
}

double alpha_of(const Solution& sol) { return -sol.info.primal_objective; }

}  // namespace

TEST(ConicWall, InPlaneConeEqualsAxisAlignedPyramidLp) {
  WallOptions o = small_wall();
  const Solution cone = solve(make_wall_problem(o).problem);
  o.pyramid = true;
  const Solution pyramid = solve(make_wall_problem(o).problem);
  ASSERT_EQ(cone.info.status, SolveStatus::Solved) << cone.info.brief_report();
  ASSERT_EQ(pyramid.info.status, SolveStatus::Solved) << pyramid.info.brief_report();
  EXPECT_GT(alpha_of(cone), 0.1);
  EXPECT_NEAR(alpha_of(cone), alpha_of(pyramid), 1e-6);
  EXPECT_LE(cone.info.iterations, 40);
}

TEST(ConicWall, OutOfPlanePyramidIsAnUpperBound) {
  WallOptions o = small_wall();
  o.out_of_plane = true;
  const Solution cone = solve(make_wall_problem(o).problem);
  o.pyramid = true;
  const Solution pyramid = solve(make_wall_problem(o).problem);
  ASSERT_EQ(cone.info.status, SolveStatus::Solved);
  ASSERT_EQ(pyramid.info.status, SolveStatus::Solved);
  EXPECT_GE(alpha_of(pyramid), alpha_of(cone) - 1e-7);
}

TEST(ConicWall, PyramidLpAgreesWithClp) {
  if (std::system("command -v clp > /dev/null 2>&1") != 0) GTEST_SKIP() << "clp not on PATH";
  WallOptions o = small_wall();
  o.pyramid = true;
  const ConicProblem p = make_wall_problem(o).problem;
  const auto base =
      std::filesystem::temp_directory_path() / ("rbla_conic_wall_" + std::to_string(::getpid()));
  const std::string mps = base.string() + ".mps", out = base.string() + ".sol";
  write_mps(p, mps);
  const std::string command = "clp " + mps + " -primalS -solu " + out + " > /dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream solution(out);
  std::string first_line;
  std::getline(solution, first_line);
  std::filesystem::remove(mps);
  std::filesystem::remove(out);
  ASSERT_NE(first_line.find("Optimal"), std::string::npos) << first_line;
  const double clp_alpha = -std::stod(first_line.substr(first_line.rfind(' ') + 1));
  const Solution ours = solve(p);
  ASSERT_EQ(ours.info.status, SolveStatus::Solved);
  EXPECT_NEAR(alpha_of(ours), clp_alpha, 1e-6);
}

TEST(ConicWall, DenseLoadColumnHandledOutsideTheFactor) {
  WallOptions o = small_wall();
  o.nx = 10;
  o.ny = 8;
  const ConicProblem p = make_wall_problem(o).problem;
  Settings with;
  with.dense_column_ratio = 2.0;  // the α column has one entry per block (~85), others ≤ 12
  Settings without;
  without.dense_columns = false;
  const Solution a = solve(p, with);
  const Solution b = solve(p, without);
  ASSERT_EQ(a.info.status, SolveStatus::Solved) << a.info.brief_report();
  ASSERT_EQ(b.info.status, SolveStatus::Solved) << b.info.brief_report();
  EXPECT_EQ(a.info.num_dense_columns, 1);
  EXPECT_EQ(b.info.num_dense_columns, 0);
  EXPECT_NEAR(alpha_of(a), alpha_of(b), 1e-7);
  EXPECT_LT(a.info.num_factor_nonzeros, b.info.num_factor_nonzeros);
}

TEST(ConicWall, WeightPointingUpIsInfeasibleWithCertificate) {
  // No tension at the joints: a wall whose weight pulls it off its base cannot be in equilibrium.
  ConicProblem p = make_wall_problem(small_wall()).problem;
  p.b = -p.b;
  const Solution sol = solve(p);
  ASSERT_EQ(sol.info.status, SolveStatus::PrimalInfeasible) << sol.info.brief_report();
  EXPECT_LT(primal_certificate_error(p, sol.y), 1e-7);
}

TEST(ConicWall, DownwardLiveLoadIsUnboundedWithCertificate) {
  // A vertical downward live load is carried for any α (infinite compressive strength): no
  // mechanism, the problem is unbounded, and the certificate is a ray of admissible forces.
  ConicProblem p = make_wall_problem(small_wall()).problem;
  std::vector<Eigen::Triplet<double>> t;
  for (Eigen::Index j = 0; j < p.A.outerSize(); ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(p.A, j); it; ++it) {
      if (j == 0)
        t.emplace_back(it.row() + 2, 0, -it.value());  // x-force row → z-force row, down
      else
        t.emplace_back(it.row(), j, it.value());
    }
  }
  p.A.setFromTriplets(t.begin(), t.end());
  p.A.makeCompressed();
  const Solution sol = solve(p);
  ASSERT_EQ(sol.info.status, SolveStatus::DualInfeasible) << sol.info.brief_report();
  EXPECT_LT(dual_certificate_error(p, sol.x), 1e-7);
}
