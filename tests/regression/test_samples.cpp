// Every bundled sample is valid against the model schema and passes the whole model stage
// with no warnings; the counts are those of the geometry the generator wrote.
#include "io/load_model.hpp"
#include "io/model_reader.hpp"
#include "io/schema_validation.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>

namespace fs = std::filesystem;

namespace {

struct Expected {
  std::size_t blocks;
  std::size_t interfaces;
};

// Interface counts by hand: block: 1 bed joint. column: 4 stacked bed joints. arch: 16 voussoirs
// give 15 radial joints + 2 springings. The two walls: counted by the independent brute-force
// pair check the generator's author ran (all face pairs, no spatial index).
const std::map<std::string, Expected> kExpected = {
    {"block.json", {2, 1}},
    {"column.json", {5, 4}},
    {"arch.json", {18, 17}},
    {"wall_opening.json", {118, 308}},
    {"wall_settlement.json", {127, 344}},
};

}  // namespace

TEST(Samples, AllBundledSamplesValidateAndLoad) {
  const fs::path dir = fs::path(RBLA_SOURCE_DIR) / "samples";
  std::size_t seen = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".json") continue;
    ++seen;
    const std::string name = entry.path().filename().string();
    SCOPED_TRACE(name);
    const std::string text = rbla::io::read_text(entry.path().string());
    const auto issues = rbla::io::validate_against_schema(nlohmann::json::parse(text), rbla::io::SchemaKind::Model);
    EXPECT_TRUE(issues.empty()) << issues.front().pointer << ": " << issues.front().message;
    const auto loaded = rbla::io::load_model_text(text);
    EXPECT_TRUE(loaded.model.warnings.empty()) << loaded.model.warnings.front().message;
    const auto expected = kExpected.find(name);
    ASSERT_NE(expected, kExpected.end()) << "a new sample needs its expected counts here";
    EXPECT_EQ(loaded.model.blocks.size(), expected->second.blocks);
    EXPECT_EQ(loaded.model.interfaces.size(), expected->second.interfaces);
  }
  EXPECT_EQ(seen, kExpected.size());
}
