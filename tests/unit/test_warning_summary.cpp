// Warnings aggregated (issue 17): one line per kind on standard error with the count and the
// worst instance, a bounded list and every count in the result JSON.
#include "io/result_writer.hpp"
#include "io/warning_summary.hpp"
#include "support/cli_runner.hpp"
#include "support/vault_builder.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace {

namespace fs = std::filesystem;
using rbla::model::Warning;

std::vector<Warning> faces(int n, int worst) {
  std::vector<Warning> warnings;
  for (int i = 0; i < n; ++i) {
    warnings.push_back({"non_planar_face", "face " + std::to_string(i), "/blocks/" + std::to_string(i),
                        i == worst ? 0.01 : 0.001});
  }
  return warnings;
}

TEST(WarningSummary, OneKindPerCodeWithCountAndWorst) {
  std::vector<Warning> warnings = faces(5, 3);
  warnings.insert(warnings.begin() + 1, Warning{"isolated_block", "block 'b' touches no other block", "/blocks/9"});
  const auto kinds = rbla::io::summarise_warnings(warnings);
  ASSERT_EQ(kinds.size(), 2u);
  EXPECT_EQ(kinds[0].code, "non_planar_face");
  EXPECT_EQ(kinds[0].count, 5u);
  EXPECT_EQ(warnings[kinds[0].worst].message, "face 3");
  EXPECT_EQ(kinds[1].code, "isolated_block");
  EXPECT_EQ(kinds[1].count, 1u);

  const auto lines = rbla::io::warning_lines(warnings, false);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].rfind("[non_planar_face] 5 times; the worst at /blocks/3: face 3", 0), 0u) << lines[0];
  EXPECT_EQ(lines[1], "[isolated_block] at /blocks/9: block 'b' touches no other block");
  EXPECT_EQ(rbla::io::warning_lines(warnings, true).size(), 6u);
}

TEST(WarningSummary, ResultListIsBoundedPerCodeAndKeepsTheWorst) {
  const std::size_t n = 3 * rbla::io::kMaxWarningsPerCode;
  const int worst = static_cast<int>(n) - 7;  // after the first kMaxWarningsPerCode
  std::vector<Warning> warnings = faces(static_cast<int>(n), worst);
  warnings.push_back({"isolated_block", "block 'b' touches no other block", "/blocks/9"});
  const auto listed = rbla::io::listed_warnings(warnings);
  ASSERT_EQ(listed.size(), rbla::io::kMaxWarningsPerCode + 1);
  EXPECT_TRUE(std::is_sorted(listed.begin(), listed.end()));
  EXPECT_NE(std::find(listed.begin(), listed.end(), static_cast<std::size_t>(worst)), listed.end());
  EXPECT_EQ(listed.back(), n);  // the other code is still listed
  const nlohmann::json summary = rbla::io::warning_summary_json(warnings);
  ASSERT_EQ(summary.size(), 2u);
  EXPECT_EQ(summary[0]["count"], n);
  EXPECT_EQ(summary[0]["listed"], rbla::io::kMaxWarningsPerCode);
  EXPECT_EQ(summary[1]["count"], 1);
}

// A barrel vault of 184 voussoirs (1104 faces) with every vertex moved by up to +-4 mm: many
// faces are warped. Whatever the verdict, a run prints at most 20 lines on standard error (the
// issue's bound), and the warped faces are at most two warnings (within the joint tolerance,
// beyond it) that count them all, in the result as on standard error.
TEST(WarningSummary, NoisyVaultRunPrintsAtMostTwentyLines) {
  const fs::path dir = fs::temp_directory_path() / ("rbla_warnings_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  rbla::testing::VaultSpec spec;
  spec.units = 11;
  spec.noise = 4e-3;
  const nlohmann::json model = rbla::testing::vault_model(spec);
  std::size_t num_faces = 0;
  for (const auto& block : model["blocks"]) num_faces += block["faces"].size();
  ASSERT_GE(num_faces, 1000u);
  std::ofstream(dir / "vault.json") << model.dump();

  const auto r = rbla::testing::run_rbla("solve " + (dir / "vault.json").string() + " -o " + (dir / "r.json").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  std::size_t lines = 0;
  for (const char c : r.output) lines += c == '\n' ? 1 : 0;
  EXPECT_LE(lines, 21u) << r.output;  // 20 on standard error and the verdict on standard output

  std::ifstream in(dir / "r.json");
  const nlohmann::json result = nlohmann::json::parse(in);
  std::size_t entries = 0, warped = 0;
  for (const auto& warning : result["warnings"]) {
    if (warning["code"] != "non_planar_face") continue;
    ++entries;
    const std::string message = warning["message"];
    warped += std::stoul(message.substr(0, message.find(' ')));  // "N faces are not planar, ..."
    EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
  }
  EXPECT_GE(entries, 1u);
  EXPECT_LE(entries, 2u);
  EXPECT_GT(warped, rbla::io::kMaxWarningsPerCode) << "the noise should warp many faces";
  fs::remove_all(dir);
}

}  // namespace
