// Hostile input (issue 7, item 2): what tests/unit/test_model_reader.cpp and test_cli.cpp did not
// cover yet. Every case must be rejected with a message that names the field (its JSON pointer),
// by the library (ModelError) and by the program (exit code 2, no output file), never a crash,
// a hang or an answer.
//
// Covered: NaN / Infinity / overflowing literals, duplicate names in an object, wrong types,
// huge values, duplicate interface ids, an interface joining a block to itself, self-intersecting
// faces and interface polygons, zero-area faces with distinct collinear corners, collinear and
// non-planar interface polygons, one face flipped, all vertices coincident, empty documents and
// models, every truncation of a model, trailing garbage, invalid UTF-8, and deep nesting.
#include "io/input_limits.hpp"
#include "io/load_model.hpp"
#include "model/errors.hpp"
#include "support/model_builder.hpp"

#include <gtest/gtest.h>

#include "support/cli_runner.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace rbla::testing;
using rbla::io::load_model_text;
using rbla::model::InputIssue;
using rbla::model::ModelError;

namespace {

namespace fs = std::filesystem;

json two_boxes() {
  return model_with(json::array({box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"), box_block("B1", 0, 0, 0, 1, 1, 2)}));
}

/// A right prism over `outline` (x, y) from z = 0 to 2, faces as prism_block builds them.
json prism_model(const std::vector<std::pair<double, double>>& outline) {
  return model_with(json::array({box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"), prism_block("B1", outline, 0, 2)}));
}

struct Hostile {
  std::string name;
  std::string text;
  std::string pointer;  ///< where the issue must be ("" = the whole document)
  std::string words;    ///< part of the message
};

/// Text with the first occurrence of `from` replaced.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::vector<Hostile> hostile_cases() {
  std::vector<Hostile> out;
  const std::string good = two_boxes().dump();
  // B1's far top corner (dump() writes no spaces; it is the first [1,1,2] in the text).
  const std::string b1_vertex = "[1.0,1.0,2.0]";

  out.push_back({"nan_literal", replaced(good, b1_vertex, "[1.0,NaN,2.0]"), "/blocks/1/vertices/6/1", "malformed JSON"});
  out.push_back({"infinity_literal", replaced(good, b1_vertex, "[1.0,Infinity,2.0]"), "/blocks/1/vertices/6/1", "malformed JSON"});
  out.push_back({"overflowing_number", replaced(good, b1_vertex, "[1.0,1e400,2.0]"), "/blocks/1/vertices/6/1", "malformed JSON"});
  out.push_back({"negative_overflowing_number", replaced(good, b1_vertex, "[1.0,-1e400,2.0]"), "/blocks/1/vertices/6/1", "malformed JSON"});
  out.push_back({"trailing_garbage", good + " x", "", "malformed JSON"});
  out.push_back({"two_documents", good + good, "", "malformed JSON"});
  out.push_back({"comment", "// exported by CAD\n" + good, "", "malformed JSON"});
  out.push_back({"whitespace_only", " \n\t ", "", "malformed JSON"});
  {
    std::string bad = good;
    bad.replace(bad.find("\"B1\""), 4, "\"B\xff" "1\"");
    out.push_back({"invalid_utf8_in_id", bad, "/blocks/1/id", "UTF-8"});
  }
  out.push_back({"null_document", "null", "", ""});
  out.push_back({"string_document", "\"model\"", "", ""});
  out.push_back({"empty_object", "{}", "", "blocks"});

  // Duplicate names in one object: nlohmann would keep the last silently.
  out.push_back({"duplicate_top_level_name",
                 replaced(good, "\"schema_version\":\"1.0.0\"", "\"schema_version\":\"1.0.0\",\"schema_version\":\"1.0.0\""),
                 "/schema_version", "appears twice"});
  {
    json m = two_boxes();
    m["blocks"][1]["unit_weight"] = 18.0;
    out.push_back({"duplicate_unit_weight", replaced(m.dump(), "\"unit_weight\":18.0", "\"unit_weight\":18.0,\"unit_weight\":1.8e7"),
                   "/blocks/1/unit_weight", "appears twice"});
  }

  // Wrong types.
  {
    json m = two_boxes();
    m["blocks"][1]["id"] = 5;
    out.push_back({"id_is_a_number", m.dump(), "/blocks/1/id", ""});
  }
  {
    json m = two_boxes();
    m["blocks"] = "all of them";
    out.push_back({"blocks_is_a_string", m.dump(), "/blocks", ""});
  }
  {
    json m = two_boxes();
    m["blocks"][1]["role"] = true;
    out.push_back({"role_is_a_boolean", m.dump(), "/blocks/1/role", ""});
  }
  {
    json m = two_boxes();
    m["blocks"][1]["faces"][1][3] = 7.5;
    out.push_back({"fractional_face_index", m.dump(), "/blocks/1/faces/1/3", ""});
  }
  {
    json m = two_boxes();
    m["blocks"][1]["faces"][1][3] = "7";
    out.push_back({"face_index_is_a_string", m.dump(), "/blocks/1/faces/1/3", ""});
  }

  // Huge values.
  {
    json m = two_boxes();
    m["blocks"][1]["faces"][1][3] = 18446744073709551615ull;  // 2^64 - 1: read as int64 it would be -1
    out.push_back({"face_index_2_to_64", m.dump(), "/blocks/1/faces/1/3", ""});
  }
  {
    json m = two_boxes();
    m["defaults"] = {{"unit_weight", 1e300}};
    out.push_back({"huge_unit_weight", m.dump(), "/defaults/unit_weight", ""});
  }
  {
    json m = two_boxes();
    m["defaults"] = {{"friction", 1e300}};
    out.push_back({"huge_friction", m.dump(), "/defaults/friction", ""});
  }
  {
    json m = two_boxes();
    m["analysis"] = {{"time_limit", 1e300}};
    out.push_back({"huge_time_limit", m.dump(), "/analysis/time_limit", ""});
  }
  {
    json m = two_boxes();
    m["blocks"][1]["vertices"][6] = {1.0, 1.0, 1e16};
    out.push_back({"coordinate_beyond_1e15", m.dump(), "/blocks/1/vertices/6/2", ""});
  }
  {
    json m = two_boxes();
    m["detection"] = {{"distance_tolerance", 1e300}};
    out.push_back({"distance_tolerance_larger_than_the_model", m.dump(), "/detection/distance_tolerance", "tenth"});
  }

  // References and ids.
  {
    json m = two_boxes();
    const json square = json::array({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    m["interfaces"] = {{{"id", "a"}, {"blocks", {"base", "B1"}}, {"polygon", square}},
                       {{"id", "a"}, {"blocks", {"base", "B1"}}, {"polygon", square}}};
    out.push_back({"duplicate_interface_id", m.dump(), "/interfaces/1/id", "duplicate"});
    m["interfaces"] = {{{"blocks", {"B1", "B1"}}, {"polygon", square}}};
    out.push_back({"interface_joins_a_block_to_itself", m.dump(), "/interfaces/0/blocks", "two different blocks"});
    m["interfaces"] = {{{"blocks", {"nowhere", "B1"}}, {"polygon", square}}};
    out.push_back({"dangling_first_interface_block", m.dump(), "/interfaces/0/blocks/0", "nowhere"});
  }

  // Geometry.
  {
    // A pentagram prism: its top and bottom faces cross themselves; their signed area is positive
    // (winding number 2 in the middle), so volume alone would not notice.
    std::vector<std::pair<double, double>> star;
    for (int k = 0; k < 5; ++k) {
      const double a = M_PI / 2 + 4 * M_PI * k / 5;
      star.emplace_back(0.5 + 0.5 * std::cos(a), 0.5 + 0.5 * std::sin(a));
    }
    out.push_back({"pentagram_prism", prism_model(star).dump(), "/blocks/1/faces/0", "self-intersecting"});
    // A bow tie with unequal lobes (non-zero signed area).
    out.push_back({"bow_tie_prism", prism_model({{0, 0}, {1, 1}, {1, 0}, {0, 0.5}}).dump(), "/blocks/1/faces/0",
                   "self-intersecting"});
  }
  {
    json m = two_boxes();
    m["interfaces"] = {{{"blocks", {"base", "B1"}}, {"polygon", {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 0.5, 0}}}}};
    out.push_back({"bow_tie_interface", m.dump(), "/interfaces/0/polygon", "self-intersecting"});
    m["interfaces"] = {{{"blocks", {"base", "B1"}}, {"polygon", {{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}}}}};
    out.push_back({"collinear_interface", m.dump(), "/interfaces/0/polygon", "zero area"});
    m["interfaces"] = {{{"blocks", {"base", "B1"}}, {"polygon", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5}, {0, 1, 0}}}}};
    out.push_back({"non_planar_interface", m.dump(), "/interfaces/0/polygon", "not planar"});
  }
  {
    // Three distinct but collinear corners: zero area, though no index repeats.
    json m = two_boxes();
    m["blocks"][1]["vertices"].push_back({0.5, 0.0, 0.0});
    m["blocks"][1]["faces"].push_back({0, 8, 1});
    out.push_back({"face_with_collinear_corners", m.dump(), "/blocks/1/faces/6", "zero area"});
  }
  {
    json m = two_boxes();
    auto& face = m["blocks"][1]["faces"][2];
    std::reverse(face.begin(), face.end());
    out.push_back({"one_face_flipped", m.dump(), "/blocks/1/faces", "inconsistently oriented"});
  }
  {
    json m = two_boxes();
    for (auto& v : m["blocks"][1]["vertices"]) v = {0.25, 0.25, 0.25};
    out.push_back({"all_vertices_coincide", m.dump(), "/blocks/1/vertices", "coincide"});
  }
  {
    json m = two_boxes();
    m["blocks"] = json::array();
    out.push_back({"no_blocks", m.dump(), "/blocks", ""});
  }

  // Deep nesting: refused while reading, at the first level beyond the limit (64 by default), its
  // pointer 64 steps deep, without exhausting the stack or building the rest.
  const auto repeated = [](const std::string& token, std::size_t n) {
    std::string text;
    for (std::size_t i = 0; i < n; ++i) text += token;
    return text;
  };
  const std::size_t depth = rbla::io::InputLimits{}.max_depth;
  const std::string head = R"({"schema_version":"1.0.0","units":{"length":"m"},"blocks":)";
  out.push_back({"deep_array_in_blocks", head + std::string(100000, '[') + std::string(100000, ']') + "}",
                 "/blocks" + repeated("/0", depth - 1), "deeper than the limit of 64 levels"});
  {
    std::string deep = R"({"title":)";
    for (int i = 0; i < 100000; ++i) deep += R"({"a":)";
    deep += "1" + std::string(100000, '}');
    deep += R"(,"schema_version":"1.0.0","units":{"length":"m"},"blocks":[]})";
    out.push_back({"deep_object_in_title", deep, "/title" + repeated("/a", depth - 1), "--max-depth"});
  }
  out.push_back({"a_million_unclosed_brackets", std::string(1000000, '['), repeated("/0", depth), "deeper than"});
  return out;
}

std::vector<InputIssue> issues_of(const std::string& text) {
  try {
    load_model_text(text);
  } catch (const ModelError& error) {
    return error.issues();
  }
  return {};
}

std::string describe(const std::vector<InputIssue>& issues) {
  std::string text;
  for (const auto& issue : issues) text += "[" + issue.pointer + "] " + issue.message + "\n";
  return text.empty() ? "(accepted)" : text;
}

class HostileInput : public ::testing::TestWithParam<Hostile> {};

TEST_P(HostileInput, RejectedNamingTheField) {
  const Hostile& h = GetParam();
  const auto issues = issues_of(h.text);
  ASSERT_FALSE(issues.empty()) << "accepted";
  bool found = false;
  for (const auto& issue : issues) {
    found |= issue.pointer == h.pointer && issue.message.find(h.words) != std::string::npos;
  }
  EXPECT_TRUE(found) << "expected an issue at '" << h.pointer << "' mentioning '" << h.words << "'; got\n"
                     << describe(issues);
}

std::string case_name(const ::testing::TestParamInfo<Hostile>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Hostile, HostileInput, ::testing::ValuesIn(hostile_cases()), case_name);

// Every prefix of a valid model (cut at 200 places, and the whole-file cuts at the ends) is
// malformed JSON, never a crash or an accepted model.
TEST(HostileInputTruncation, EveryCutIsMalformed) {
  const std::string text = two_boxes().dump(1);
  for (std::size_t k = 0; k < 200; ++k) {
    const std::size_t cut = k * (text.size() - 1) / 199;
    const auto issues = issues_of(text.substr(0, cut));
    ASSERT_FALSE(issues.empty()) << "a model cut at " << cut << " of " << text.size() << " was accepted";
    EXPECT_NE(issues.front().message.find("malformed JSON"), std::string::npos)
        << "cut at " << cut << ": " << describe(issues);
  }
}

// The self-intersection check must not refuse what CAD exports legitimately: a non-convex face,
// a T-junction (a vertex on another face's edge) and a vertex repeated at the same place.
TEST(HostileInputNotHostile, NonConvexTJunctionAndRepeatedVertexAreAccepted) {
  {
    const json l_shape = prism_model({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}});
    const auto issues = issues_of(l_shape.dump());
    EXPECT_TRUE(issues.empty()) << describe(issues);
  }
  {
    json m = two_boxes();
    auto& b = m["blocks"][1];
    b["vertices"].push_back({1.0, 0.5, 2.0});  // 8: on the top face's edge 5-6 only
    b["faces"][1] = {4, 5, 8, 6, 7};
    const auto issues = issues_of(m.dump());
    EXPECT_TRUE(issues.empty()) << describe(issues);
  }
  {
    json m = two_boxes();
    auto& b = m["blocks"][1];
    b["vertices"].push_back({0.0, 0.0, 2.0});  // 8: a second copy of vertex 4
    b["faces"][1] = {4, 8, 5, 6, 7};
    const auto issues = issues_of(m.dump());
    EXPECT_TRUE(issues.empty()) << describe(issues);
  }
}

// ---- The program: exit code 2, the pointer in the message, no output file ---------------------

using rbla::testing::RunResult;
using rbla::testing::run_rbla;

class HostileCli : public ::testing::TestWithParam<Hostile> {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rbla_hostile_" + std::to_string(::getpid()) + "_" + GetParam().name);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_P(HostileCli, SolveExitsWithTwoAndWritesNothing) {
  const Hostile& h = GetParam();
  const fs::path model = dir_ / "model.json", result = dir_ / "result.json", svg = dir_ / "svg";
  std::ofstream(model, std::ios::binary) << h.text;
  const auto r = run_rbla("solve -q " + model.string() + " -o " + result.string() + " --svg " + svg.string());
  EXPECT_EQ(r.exit_code, 2) << r.output.substr(0, 2000);
  EXPECT_NE(r.output.find("invalid input"), std::string::npos) << r.output.substr(0, 2000);
  EXPECT_NE(r.output.find(h.pointer.empty() ? std::string("(document)") : h.pointer + ":"), std::string::npos)
      << r.output.substr(0, 2000);
  EXPECT_FALSE(fs::exists(result)) << "a result file was written for invalid input";
  EXPECT_FALSE(fs::exists(svg / "mechanism.svg"));
  for (const auto& entry : fs::directory_iterator(dir_)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  }
}

INSTANTIATE_TEST_SUITE_P(Hostile, HostileCli, ::testing::ValuesIn(hostile_cases()), case_name);

}  // namespace
