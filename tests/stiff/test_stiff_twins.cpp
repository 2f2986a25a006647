// Well-conditioned twins: the same mechanics drawn at another scale or with every weight scaled
// must give the same multiplier (the problem rbla solves is the same once non-dimensionalised,
// docs/method.md, "Scaling"); and a large model under a tiny time limit ends with the
// time-limit verdict, not a number.
#include "stiff_cases.hpp"
#include "stiff_checks.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace rbla::stiff {
namespace {

using analysis::Verdict;

double alpha_of(const StiffRun& run) {
  EXPECT_EQ(run.result.verdict, Verdict::Collapse) << run.result.verdict_text;
  EXPECT_TRUE(non_finite_fields(run.result).empty());
  return run.result.load_multiplier.value_or(std::nan(""));
}

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

std::vector<TwinCase> fast_twins() {
  std::vector<TwinCase> out;
  for (auto& c : twin_cases()) {
    if (!c.slow) out.push_back(std::move(c));
  }
  return out;
}

class StiffTwinTest : public ::testing::TestWithParam<TwinCase> {};

// Each twin pair (tests/stiff/stiff_cases.hpp, twin_cases): same verdict, same alpha within
// the stated tolerance, no NaN in either result.
TEST_P(StiffTwinTest, SameAlphaAsTheWellConditionedTwin) {
  const TwinCase& c = GetParam();
  SCOPED_TRACE(c.varies + " | " + c.source + " | tolerance: " + c.tol_reason);
  const double reference = alpha_of(run_model(c.twin));
  const double a = alpha_of(run_model(c.model));
  EXPECT_LE(rel(a, reference), c.rel_tol) << std::setprecision(12) << a << " vs twin " << reference;
}

INSTANTIATE_TEST_SUITE_P(Stiff, StiffTwinTest, ::testing::ValuesIn(fast_twins()),
                         [](const ::testing::TestParamInfo<TwinCase>& info) { return info.param.name; });

// A 1:1000 column of 10 blocks at two sizes (0.01 x 10 m and 1 x 1000 m): the same alpha
// (closed form b/H = 1e-3), to the absolute accuracy of a small alpha (1e-7, see StiffCase).
TEST(StiffTwins, SlenderColumnAtTwoSizes) {
  for (const std::string formulation : {"auto", "3d"}) {
    SCOPED_TRACE(formulation);
    Opt o{"associative", formulation};
    const double a1 = alpha_of(run_model(model_of(column_blocks(0.01, std::vector<double>(10, 1.0)), o)));
    const double a2 = alpha_of(run_model(model_of(column_blocks(1.0, std::vector<double>(10, 100.0), 1.0), o)));
    EXPECT_NEAR(a1, a2, 1e-7) << "1:1000 column at 10 m and at 1 km";
    EXPECT_NEAR(a1, 1e-3, 1e-7);
  }
}

// A big model with a 0.05 s limit: the analysis returns, with the time-limit verdict and no
// number. (Nothing about how long it took is asserted: machines are noisy.)
TEST(StiffTimeLimit, LargeStackHonoursASmallTimeLimit) {
  for (const std::string friction : {"associative", "non_associative"}) {
    SCOPED_TRACE(friction);
    Opt o{friction, "3d"};
    json m = model_of(column_blocks(1, std::vector<double>(1000, 0.1)), o);
    m["analysis"]["time_limit"] = 0.05;
    const auto start = std::chrono::steady_clock::now();
    const StiffRun run = run_model(m);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "[ limit    ] 1000-block stack 3-D " << friction << ", limit 0.05 s: " << run.result.verdict_text
              << " after " << seconds << " s (load + analysis)\n";
    EXPECT_EQ(run.result.verdict, Verdict::TimeLimit) << run.result.verdict_text;
    EXPECT_FALSE(run.result.load_multiplier.has_value());
    EXPECT_NE(run.result.verdict_text.find("time limit"), std::string::npos) << run.result.verdict_text;
    EXPECT_TRUE(non_finite_fields(run.result).empty());
  }
}

// The same through the program: exit code 3 (README: solver failure, time or iteration limit),
// a message saying so, and a result file whose status is time_limit, valid against the schema.
TEST(StiffTimeLimit, ProgramReportsTheTimeLimit) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("rbla_stiff_limit_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  Opt o{"associative", "3d"};
  json m = model_of(column_blocks(1, std::vector<double>(1000, 0.1)), o);
  m["analysis"]["time_limit"] = 0.05;
  std::ofstream(dir / "model.json") << m.dump();
  const std::string command = std::string(RBLA_BINARY) + " solve -q " + (dir / "model.json").string() + " -o " +
                              (dir / "result.json").string() + " 2>&1";
  std::string output;
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) output.append(buffer.data(), n);
  const int status = pclose(pipe);
  EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 3) << output;
  EXPECT_NE(output.find("time limit"), std::string::npos) << output;
  std::ifstream in(dir / "result.json");
  std::stringstream text;
  text << in.rdbuf();
  ASSERT_FALSE(text.str().empty()) << "no result file";
  const json result = json::parse(text.str());
  EXPECT_EQ(result.value("status", ""), "time_limit");
  EXPECT_FALSE(result.contains("load_multiplier"));
  const auto issues = io::validate_result_text(text.str());
  EXPECT_TRUE(issues.empty()) << issues.front().pointer << ": " << issues.front().message;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rbla::stiff
