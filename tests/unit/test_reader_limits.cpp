// The model reader under limits and with honest messages (issue 19, items 2 and 4): escaping of
// user text, limits checked while reading, repeated interfaces found in O(n log n) and reported
// once, and the messages that misled (an index of 2^64 - 1, a direction of length 1e-170,
// integers written as 3.0, an unknown property shown at the document).
#include "analysis/limit_analysis.hpp"
#include "io/input_limits.hpp"
#include "io/load_model.hpp"
#include "io/printable.hpp"
#include "model/errors.hpp"
#include "support/model_builder.hpp"
#include "support/model_issues.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace rbla::testing;
using rbla::io::InputLimits;
using rbla::io::load_model_text;
using rbla::io::printable;
using rbla::model::InputIssue;
using rbla::model::ModelError;

namespace {

json two_boxes() {
  return model_with(json::array({box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"), box_block("B1", 0, 0, 0, 1, 1, 2)}));
}

const json kSquare = json::array({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});

json interface_between(const std::string& a, const std::string& b, const json& polygon) {
  return json{{"blocks", {a, b}}, {"polygon", polygon}};
}

}  // namespace

// ---- io::printable ---------------------------------------------------------------------------------

TEST(Printable, ControlCharactersBecomeEscapes) {
  EXPECT_EQ(printable("B1\n\x1b[31mFAKE\x1b[0m\t\r"), "B1\\u000A\\u001B[31mFAKE\\u001B[0m\\u0009\\u000D");
  EXPECT_EQ(printable(std::string("a\0b", 3)), "a\\u0000b");
  EXPECT_EQ(printable("\x7f"), "\\u007F");
  EXPECT_EQ(printable("\xc2\x85"), "\\u0085");            // NEL, a C1 control
  EXPECT_EQ(printable("\xe2\x80\xa8"), "\\u2028");        // line separator
  EXPECT_EQ(printable("\xe2\x80\xae" "abc"), "\\u202Eabc");  // right-to-left override
}

TEST(Printable, InvalidUtf8BytesAreShownAsHex) {
  EXPECT_EQ(printable("B\xff" "1"), "B\\xFF1");
  EXPECT_EQ(printable("\xc0\xaf"), "\\xC0\\xAF");      // overlong '/'
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xED\\xA0\\x80");  // a surrogate
  EXPECT_EQ(printable("\xe2\x82"), "\\xE2\\x82");      // cut sequence
}

TEST(Printable, TextThatIsFineStaysAsItIs) {
  const std::string text = "Façade ‘Nord’ — block 12 \\ 3 €";
  EXPECT_EQ(printable(text), text);
  EXPECT_EQ(printable(printable("a\nb\x1b")), printable("a\nb\x1b"));  // escaping twice changes nothing more
}

TEST(Printable, LongTextIsCutAtACharacterWithItsLength) {
  const std::string text = std::string(199, 'x') + "é" + std::string(1000, 'y');  // é is 2 bytes, at 199-200
  const std::string shown = printable(text, 200);
  EXPECT_EQ(shown, std::string(199, 'x') + "... (1201 bytes in all)");
  EXPECT_EQ(printable(std::string(10'000'000, 'z')).size(), 200u + std::string("... (10000000 bytes in all)").size());
}

// ---- Limits while reading ------------------------------------------------------------------------

TEST(ReaderLimits, DefaultsAcceptAModelAndEachLimitStopsAtItsPlace) {
  json m = two_boxes();
  m["interfaces"] = json::array({interface_between("base", "B1", kSquare)});  // {x} alone is x under clang
  const std::string text = m.dump();
  EXPECT_TRUE(model_issues(text).empty()) << describe_issues(model_issues(text));

  InputLimits blocks;
  blocks.max_blocks = 1;
  EXPECT_TRUE(has_issue_at(model_issues(text, blocks), "/blocks/1", "--max-blocks")) << describe_issues(model_issues(text, blocks));
  InputLimits vertices;
  vertices.max_vertices = 15;
  EXPECT_TRUE(has_issue_at(model_issues(text, vertices), "/blocks/1/vertices/7", "--max-vertices"));
  InputLimits interfaces;
  interfaces.max_interfaces = 0;
  EXPECT_TRUE(has_issue_at(model_issues(text, interfaces), "/interfaces/0", "--max-interfaces"));
  InputLimits depth;
  depth.max_depth = 5;  // a face, a vertex and a polygon's corner are 5 deep: the model needs 5
  EXPECT_TRUE(model_issues(text, depth).empty()) << describe_issues(model_issues(text, depth));
  depth.max_depth = 4;
  EXPECT_TRUE(has_issue_at(model_issues(text, depth), "/blocks/0/faces/0", "deeper than the limit of 4 levels"))
      << describe_issues(model_issues(text, depth));
  // Every value counts, containers too (the text's members in name order): the root, /blocks,
  // /blocks/0, and the fourth, /blocks/0/faces, is one too many.
  InputLimits values;
  values.max_values = 3;
  EXPECT_TRUE(has_issue_at(model_issues(text, values), "/blocks/0/faces", "--max-values"))
      << describe_issues(model_issues(text, values));
  InputLimits bytes;
  bytes.max_bytes = text.size() - 1;
  EXPECT_TRUE(has_issue_at(model_issues(text, bytes), "", "--max-input-bytes"));
}

TEST(ReaderLimits, LongStringsAndNamesAreRefusedWithAShortQuote) {
  json m = two_boxes();
  m["title"] = std::string(20000, 't');
  const auto issues = model_issues(m.dump());
  ASSERT_EQ(issues.size(), 1u) << describe_issues(issues);
  EXPECT_EQ(issues[0].pointer, "/title");
  EXPECT_NE(issues[0].message.find("a string of 20000 bytes"), std::string::npos) << issues[0].message;
  EXPECT_LT(issues[0].message.size(), 300u);
}

// ---- Repeated interfaces --------------------------------------------------------------------------

TEST(RepeatedInterfaces, TwentyThousandCopiesAreKeptOnceWithOneWarning) {
  // Written as text: building the JSON objects in the test would cost more than reading them.
  // Larger counts take the same path; 20000 keeps the test fast.
  std::string text = two_boxes().dump();
  text.pop_back();
  text += R"(,"interfaces":[)";
  const std::string one = interface_between("base", "B1", kSquare).dump();
  for (int i = 0; i < 20000; ++i) text += (i ? "," : "") + one;
  text += "]}";
  const auto loaded = load_model_text(text);
  ASSERT_EQ(loaded.model.interfaces.size(), 1u);
  EXPECT_EQ(loaded.model.interfaces[0].id, "I0");
  ASSERT_EQ(loaded.model.warnings.size(), 1u);
  const auto& warning = loaded.model.warnings[0];
  EXPECT_EQ(warning.code, "repeated_interfaces");
  EXPECT_EQ(warning.pointer, "/interfaces/1");
  EXPECT_NE(warning.message.find("19999 interfaces repeat an earlier one"), std::string::npos) << warning.message;
}

TEST(RepeatedInterfaces, SameJointFromAnyCornerEitherWayOrBlockOrderIsARepeat) {
  json m = two_boxes();
  const json rotated = json::array({{1, 1, 0}, {0, 1, 0}, {0, 0, 0}, {1, 0, 0}});
  const json reversed = json::array({{0, 1, 0}, {1, 1, 0}, {1, 0, 0}, {0, 0, 0}});
  const json other = json::array({{0, 0, 0}, {0.5, 0, 0}, {0.5, 1, 0}, {0, 1, 0}});  // half of it: not a repeat
  m["interfaces"] = {interface_between("base", "B1", kSquare), interface_between("B1", "base", rotated),
                     interface_between("base", "B1", reversed), interface_between("base", "B1", other)};
  const auto loaded = load_model_text(m.dump());
  ASSERT_EQ(loaded.model.interfaces.size(), 2u);
  EXPECT_EQ(loaded.model.interfaces[0].id, "I0");
  EXPECT_EQ(loaded.model.interfaces[1].id, "I3");
  ASSERT_EQ(loaded.model.warnings.size(), 1u);
  EXPECT_NE(loaded.model.warnings[0].message.find("2 interfaces repeat"), std::string::npos);
}

TEST(RepeatedInterfaces, RepeatsWithAnotherFrictionAreAmbiguous) {
  json m = two_boxes();
  json second = interface_between("base", "B1", kSquare);
  second["friction"] = 0.3;
  m["interfaces"] = {interface_between("base", "B1", kSquare), second};
  const auto issues = model_issues(m.dump());
  EXPECT_TRUE(has_issue_at(issues, "/interfaces/1", "repeats /interfaces/0")) << describe_issues(issues);
  EXPECT_TRUE(has_issue_at(issues, "/interfaces/1", "0.3 against 0.6")) << describe_issues(issues);
}

TEST(RepeatedInterfaces, LaterMessagesStillNameTheInterfaceInTheFile) {
  json m = two_boxes();
  m["interfaces"] = {interface_between("base", "B1", kSquare), interface_between("base", "B1", kSquare),
                     interface_between("base", "B1", {{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}})};  // zero area
  const auto issues = model_issues(m.dump());
  EXPECT_TRUE(has_issue_at(issues, "/interfaces/2/polygon", "zero area")) << describe_issues(issues);
}

TEST(RepeatedInterfaces, TheCollapseMultiplierIsThatOfOneJoint) {
  // One 1 x 1 x 2 block on its base: alpha = b/h = 0.5 (rocking, mu = 0.6); a thousand copies of
  // the joint must not change it.
  json m = two_boxes();
  json list = json::array();
  for (int i = 0; i < 1000; ++i) list.push_back(interface_between("base", "B1", kSquare));
  m["interfaces"] = list;
  m["analysis"] = {{"seismic", {{"direction", {1, 0, 0}}}}};
  const auto loaded = load_model_text(m.dump());
  const auto result = rbla::analysis::analyse(loaded.model);
  ASSERT_EQ(result.verdict, rbla::analysis::Verdict::Collapse);
  EXPECT_NEAR(*result.load_multiplier, 0.5, 1e-6);
  EXPECT_EQ(loaded.model.num_contact_points(), 4u);
}

// ---- Messages that misled -------------------------------------------------------------------------

TEST(HonestMessages, IntegersWrittenWithAZeroFractionAreIntegers) {
  json m = two_boxes();
  for (auto& face : m["blocks"][1]["faces"]) {
    for (auto& index : face) index = index.get<double>() + 0.0;
  }
  m["analysis"] = {{"seismic", {{"direction", {1, 0, 0}}}}, {"cone", "pyramid_inscribed"}, {"pyramid_faces", 8.0}};
  const std::string text = m.dump();
  ASSERT_NE(text.find("[4.0,5.0,6.0,7.0]"), std::string::npos) << text;
  EXPECT_TRUE(model_issues(text).empty()) << describe_issues(model_issues(text));
  EXPECT_EQ(load_model_text(text).model.analysis.pyramid_faces, 8);
}

TEST(HonestMessages, AFractionalIndexSaysWhatWasExpectedAndFound) {
  json m = two_boxes();
  m["blocks"][1]["faces"][1][3] = 7.5;
  const auto issues = model_issues(m.dump());
  EXPECT_TRUE(has_issue_at(issues, "/blocks/1/faces/1/3", "expected an integer, found the number 7.5")) << describe_issues(issues);
}

TEST(HonestMessages, AnIndexOfTwoToTheSixtyFourIsNotCalledNegative) {
  json m = two_boxes();
  m["blocks"][1]["faces"][1][3] = 18446744073709551615ull;
  const auto issues = model_issues(m.dump());
  EXPECT_TRUE(has_issue_at(issues, "/blocks/1/faces/1/3", "expected an integer, found the number 1.8446744073709552e+19"))
      << describe_issues(issues);
  for (const auto& issue : issues) EXPECT_EQ(issue.message.find("greater than or equal to 0"), std::string::npos);
}

TEST(HonestMessages, ATinyDirectionIsADirection) {
  for (const double tiny : {1e-170, 5e-324}) {
    json m = two_boxes();
    m["analysis"] = {{"seismic", {{"direction", {tiny, 0, 0}}}}};
    const auto issues = model_issues(m.dump());
    ASSERT_TRUE(issues.empty()) << tiny << ": " << describe_issues(issues);
    EXPECT_EQ(*load_model_text(m.dump()).model.analysis.seismic_direction, rbla::model::Vec3::UnitX());
  }
  json m = two_boxes();
  m["analysis"] = {{"seismic", {{"direction", {0, 0, 0}}}}};
  const auto issues = model_issues(m.dump());
  ASSERT_EQ(issues.size(), 1u) << describe_issues(issues);  // not also "needs a seismic direction"
  EXPECT_TRUE(has_issue_at(issues, "/analysis/seismic/direction", "all three components are 0"));
}

// An analysis section that only sets how to analyse (friction model, cone...) gets the default of
// what to analyse, as a file without the section does: seismic along +x when there are no live
// loads. One that asks for a load multiplier without saying of what is still refused.
TEST(HonestMessages, SettingsAloneTakeTheDefaultAnalysis) {
  json m = two_boxes();
  m.erase("analysis");
  const auto absent = load_model_text(m.dump()).model.analysis;
  m["analysis"] = {{"friction_model", "non_associative"}};
  ASSERT_TRUE(model_issues(m.dump()).empty()) << describe_issues(model_issues(m.dump()));
  const auto settings_only = load_model_text(m.dump()).model.analysis;
  ASSERT_TRUE(absent.seismic_direction && settings_only.seismic_direction);
  EXPECT_EQ(*settings_only.seismic_direction, *absent.seismic_direction);
  EXPECT_EQ(*settings_only.seismic_direction, rbla::model::Vec3::UnitX());
  EXPECT_EQ(settings_only.friction_model, rbla::model::FrictionModel::NonAssociative);

  m["analysis"] = {{"type", "load_multiplier"}};
  EXPECT_TRUE(has_issue_at(model_issues(m.dump()), "/analysis", "needs live loads"));
}

TEST(HonestMessages, AnUnknownPropertyIsNamedAtItsPlace) {
  json m = two_boxes();
  m["colour"] = "red";
  const auto issues = model_issues(m.dump());
  EXPECT_TRUE(has_issue_at(issues, "/colour", "unknown property")) << describe_issues(issues);
  for (const auto& issue : issues) EXPECT_FALSE(issue.pointer.empty()) << describe_issues(issues);
}

TEST(HonestMessages, UserTextInMessagesIsEscaped) {
  json m = two_boxes();
  m["blocks"][1]["id"] = "B\x1b[2J";
  m["blocks"][0]["id"] = "B\x1b[2J";
  const auto issues = model_issues(m.dump());
  EXPECT_TRUE(has_issue_at(issues, "/blocks/1/id", "duplicate block id 'B\\u001B[2J'")) << describe_issues(issues);
}
