// The interfaces COMPAS stored in its assemblies (tests/data/compas: detected by another tool)
// are found by rbla's detection at its default settings: for each stored polygon, a detected
// interface between the same two blocks with the same area (within 3 %) and centroid (within 3 %
// of the polygon's size). The load multipliers are compared by tests/scripts/compas_agreement.py.
#include "io/load_model.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;

namespace {

/// The model the converter writes (its messages go to standard error, not into the text).
std::string convert(const fs::path& file, const std::string& options) {
  const std::string command = "cd '" + (fs::path(RBLA_SOURCE_DIR) / "plugin").string() +
                              "' && python3 -m rbla_cad.compas_import '" + file.string() + "' " + options +
                              " 2>/dev/null";
  std::string text;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return text;
  std::array<char, 65536> buffer{};
  std::size_t n = 0;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) text.append(buffer.data(), n);
  pclose(pipe);
  return text;
}

struct Case {
  const char* file;
  const char* options;
  std::size_t stored;
};

// Every file with stored interfaces; compas_cra fixes node 0 of the concave pieces in its
// examples (both lie on the ground, so the ground rule fixes neither).
const Case kCases[] = {
    {"compas_assembly/arch_assembly.json", "", 29},     {"compas_assembly/stack_assembly.json", "", 9},
    {"compas_assembly/two-blocks_assembly.json", "", 1}, {"compas_assembly/wall_assembly.json", "", 80},
    {"compas_cra/concave-long.json", "--support 0", 7},   {"compas_cra/concave-short.json", "--support 0", 7},
};

}  // namespace

TEST(CompasAssemblies, DetectionFindsTheInterfacesCompasStored) {
  const fs::path data = fs::path(RBLA_SOURCE_DIR) / "tests" / "data" / "compas";
  for (const Case& c : kCases) {
    const std::string options = std::string(c.options);
    const auto detected = rbla::io::load_model_text(convert(data / c.file, options)).model;
    const auto stored = rbla::io::load_model_text(convert(data / c.file, options + " --interfaces")).model;
    ASSERT_EQ(stored.interfaces.size(), c.stored) << c.file;
    std::size_t found = 0;
    for (const auto& s : stored.interfaces) {
      double size = 0.0;
      for (const auto& p : s.polygon) size = std::max(size, (p - s.centroid).norm());
      for (const auto& d : detected.interfaces) {
        const bool same_blocks = (d.block_a == s.block_a && d.block_b == s.block_b) ||
                                 (d.block_a == s.block_b && d.block_b == s.block_a);
        if (same_blocks && std::abs(d.area - s.area) <= 0.03 * s.area &&
            (d.centroid - s.centroid).norm() <= 0.03 * size) {
          ++found;
          break;
        }
      }
    }
    EXPECT_GE(static_cast<double>(found), 0.95 * c.stored) << c.file << ": " << found << " of " << c.stored;
    EXPECT_TRUE(detected.near_misses.empty()) << c.file;
  }
}
