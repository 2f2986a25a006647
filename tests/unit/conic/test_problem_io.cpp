// CBF round trip, and an MPS dump solved by an independent LP solver (COIN-OR Clp) if present.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "random_problem.hpp"
#include "rbla/conic/io.hpp"
#include "rbla/conic/solver.hpp"
#include "test_helpers.hpp"

using namespace rbla::conic;
using namespace rbla::conic::testing;

namespace {

bool same_problem(const ConicProblem& a, const ConicProblem& b) {
  return a.A.rows() == b.A.rows() && a.A.cols() == b.A.cols() &&
         Eigen::MatrixXd(a.A) == Eigen::MatrixXd(b.A) && a.b == b.b && a.c == b.c &&
         a.cones.num_nonneg == b.cones.num_nonneg && a.cones.soc_dims == b.cones.soc_dims;
}

std::filesystem::path temp_path(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("rbla_conic_" + std::to_string(::getpid()) + "_" + name);
}

}  // namespace

TEST(ConicProblemIo, CbfRoundTripIsExact) {
  RandomProblemOptions o;
  o.rows = 20;
  o.num_nonneg = 15;
  o.num_soc3 = 10;
  const ConicProblem p = random_feasible_problem(o);
  std::stringstream text;
  write_cbf(p, text);
  const ConicProblem q = read_cbf(text);
  EXPECT_TRUE(same_problem(p, q));
}

TEST(ConicProblemIo, CbfUsesTheAxPlusBConvention) {
  const ConicProblem p = make_problem(2, 3, {0, 1, 0, 0, 0, 1}, {3, 4}, {1, 0, 0}, 0, {3});
  std::stringstream text;
  write_cbf(p, text);
  const std::string s = text.str();
  EXPECT_NE(s.find("VAR\n3 1\nQ 3\n"), std::string::npos) << s;
  EXPECT_NE(s.find("CON\n2 1\nL= 2\n"), std::string::npos) << s;
  EXPECT_NE(s.find("BCOORD\n2\n0 -3\n1 -4\n"), std::string::npos) << s;
  // The re-read problem has the same optimum (5).
  const Solution sol = solve(read_cbf(text));
  ASSERT_EQ(sol.info.status, SolveStatus::Solved);
  EXPECT_NEAR(sol.info.primal_objective, 5.0, 1e-7);
}

TEST(ConicProblemIo, CbfReaderRejectsWhatItDoesNotSupport) {
  std::stringstream psd("VER\n3\nPSDVAR\n1\n2\n");
  EXPECT_THROW(read_cbf(psd), ConicSetupError);
  std::stringstream inequality("VER\n3\nVAR\n1 1\nL+ 1\nCON\n1 1\nL+ 1\n");
  EXPECT_THROW(read_cbf(inequality), ConicSetupError);
}

namespace {

/// read_cbf's message for `text`, or "" when it reads; any other exception fails the test.
std::string cbf_error(const std::string& text, const CbfLimits& limits = {}) {
  std::stringstream in(text);
  try {
    read_cbf(in, limits);
  } catch (const ConicSetupError& error) {
    return error.what();
  }
  return "";
}

const char* const kSmallLp = "VER\n3\nOBJSENSE\nMIN\nVAR\n2 1\nL+ 2\nCON\n1 1\nL= 1\n"
                             "OBJACOORD\n2\n0 1\n1 1\nACOORD\n2\n0 0 1\n0 1 1\nBCOORD\n1\n0 -1\n";

}  // namespace

// Found by fuzzing the conic solver (tests/fuzz/regressions_conic/acoord_count_not_a_number.cbf):
// a count that is not a number escaped as std::invalid_argument from std::stol. Every malformed
// field is now a ConicSetupError naming its line.
TEST(ConicProblemIo, CbfReaderRejectsMalformedNumbersWithTheLine) {
  ASSERT_EQ(cbf_error(kSmallLp), "");
  const std::string lp = kSmallLp;
  auto with = [&](const std::string& from, const std::string& to) {
    std::string text = lp;
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  EXPECT_NE(cbf_error(with("\nACOORD\n2\n", "\nACOORD\n\xd4\n")).find("line 16: ACOORD count: '?' is not an integer"), std::string::npos);
  EXPECT_NE(cbf_error(with("VER\n3", "VER\nthree")).find("line 2: version"), std::string::npos);
  EXPECT_NE(cbf_error(with("0 0 1\n", "0 0 1e999\n")).find("not a finite number"), std::string::npos);
  EXPECT_NE(cbf_error(with("0 0 1\n", "0 0 nan\n")).find("not a finite number"), std::string::npos);
  EXPECT_NE(cbf_error(with("0 0 1\n", "0 0\n")).find("expected 3 fields"), std::string::npos);
  EXPECT_NE(cbf_error(with("0 0 1\n", "0 5 1\n")).find("ACOORD column 5 is out of range"), std::string::npos);
  EXPECT_NE(cbf_error(with("0 0 1\n", "-1 0 1\n")).find("ACOORD row -1 is out of range"), std::string::npos);
  EXPECT_NE(cbf_error(with("OBJACOORD\n2", "OBJACOORD\n-2")).find("OBJACOORD count -2"), std::string::npos);
  EXPECT_NE(cbf_error(with("2 1\nL+ 2", "2 1\nL+ 3")).find("cone size 3 is out of range"), std::string::npos);
  EXPECT_NE(cbf_error(with("2 1\nL+ 2", "2 1\nL+ 1")).find("the VAR cones cover 1 of 2 variables"), std::string::npos);
  EXPECT_NE(cbf_error(with("VAR\n2 1", "VAR\n99999999999999999999 1")).find("not an integer"), std::string::npos);
  EXPECT_NE(cbf_error(lp + "VAR\n1 1\nL+ 1\n").find("a second VAR section"), std::string::npos);
  // A long field is cut in the message.
  EXPECT_LT(cbf_error(with("VER\n3", "VER\n" + std::string(100000, '7') + "x")).size(), 200u);
  EXPECT_NE(cbf_error("VER\n3\nACOORD\n0\n").find("ACOORD before VAR and CON"), std::string::npos);
}

TEST(ConicProblemIo, CbfReaderRefusesSizesOverItsLimitsBeforeAllocating) {
  CbfLimits limits;
  limits.max_variables = 10;
  // A header alone may not allocate for a billion variables.
  EXPECT_NE(cbf_error("VER\n3\nVAR\n1000000000 1\nL+ 1000000000\n", limits).find("number of variables"),
            std::string::npos);
  // The default limits are what Eigen's int indices can hold.
  EXPECT_NE(cbf_error("VER\n3\nVAR\n3000000000 1\nL+ 3000000000\n").find("out of range"), std::string::npos);
  limits = {};
  limits.max_nonzeros = 1;
  EXPECT_NE(cbf_error(kSmallLp, limits).find("OBJACOORD count 2 is out of range [0, 1]"), std::string::npos);
}

TEST(ConicProblemIo, MpsRefusesSecondOrderCones) {
  const ConicProblem p = make_problem(1, 3, {1, 0, 0}, {1}, {0, -1, -1}, 0, {3});
  std::stringstream text;
  EXPECT_THROW(write_mps(p, text), ConicSetupError);
}

TEST(ConicProblemIo, MpsDumpSolvedByClpMatches) {
  if (std::system("command -v clp > /dev/null 2>&1") != 0) GTEST_SKIP() << "clp not on PATH";
  RandomProblemOptions o;
  o.rows = 40;
  o.num_nonneg = 120;
  o.num_soc3 = 0;
  o.seed = 4;
  const ConicProblem p = random_feasible_problem(o);
  const auto mps = temp_path("lp.mps");
  const auto out = temp_path("lp.sol");
  write_mps(p, mps.string());
  const std::string command =
      "clp " + mps.string() + " -primalS -solu " + out.string() + " > /dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream solution(out);
  std::string first_line;
  std::getline(solution, first_line);
  ASSERT_NE(first_line.find("Optimal"), std::string::npos) << first_line;
  const double clp_objective = std::stod(first_line.substr(first_line.rfind(' ') + 1));
  std::filesystem::remove(mps);
  std::filesystem::remove(out);

  const Solution sol = solve(p);
  ASSERT_EQ(sol.info.status, SolveStatus::Solved);
  EXPECT_NEAR(sol.info.primal_objective, clp_objective,
              1e-6 * std::max(1.0, std::abs(clp_objective)));
}
