// Inputs the fuzzer (tests/fuzz, docs/fuzzing.md) found to escape the model stage's documented
// error channel. Each must now be rejected with model::ModelError whose issue names the place
// and the cause. The fuzz_replay test replays the same files for crashes; this checks the words.
#include "io/load_model.hpp"
#include "model/errors.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

namespace {

std::string read_regression(const std::string& name) {
  const std::string path = std::string(RBLA_SOURCE_DIR) + "/tests/fuzz/regressions/" + name;
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in.is_open()) << path;
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The issues load_model_text threw for `text`; fails the test when it accepted the input or
/// threw anything other than ModelError.
std::vector<rbla::model::InputIssue> rejection_of(const std::string& text) {
  try {
    rbla::io::load_model_text(text);
  } catch (const rbla::model::ModelError& error) {
    return error.issues();
  } catch (const std::exception& other) {
    ADD_FAILURE() << "escaped as a non-ModelError exception: " << other.what();
    return {};
  }
  ADD_FAILURE() << "accepted";
  return {};
}

}  // namespace

// A number beyond double range made nlohmann::json throw out_of_range (406), not parse_error,
// and it escaped parse_model: `rbla` ended with exit 3 ("failure") instead of invalid input.
TEST(FuzzRegressions, NumberOverflowIsMalformedJson) {
  const auto issues = rejection_of(read_regression("number_overflow.json"));
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].pointer, "/blocks/0/vertices/0/0");  // where the literal is
  EXPECT_NE(issues[0].message.find("malformed JSON"), std::string::npos) << issues[0].message;
  EXPECT_NE(issues[0].message.find("1e999"), std::string::npos) << issues[0].message;
}
