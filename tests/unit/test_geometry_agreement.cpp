// One block geometry per language, and they agree: the solver's volume and centroid
// (geometry::mass_properties) of the irregular blocks in tests/data/geometry/irregular_blocks.json
// equal those of the Python core, which wrote the file (tests/scripts/geometry_fixture.py;
// tests/plugin/test_geometry_agreement.py keeps it current). The two use different reference
// points, so they agree to round-off, not bit for bit.
#include "geometry/polyhedron.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <string>
#include <vector>

namespace {

using nlohmann::json;
using rbla::geometry::mass_properties;
using rbla::geometry::Vec3;

json fixture() {
  std::ifstream in(std::string(RBLA_SOURCE_DIR) + "/tests/data/geometry/irregular_blocks.json");
  return json::parse(in);
}

}  // namespace

TEST(GeometryAgreement, SolverAndPythonCoreGiveTheSameVolumeAndCentroid) {
  const json blocks = fixture()["blocks"];
  ASSERT_GE(blocks.size(), 6u);
  for (const json& b : blocks) {
    SCOPED_TRACE(b["id"].get<std::string>());
    std::vector<Vec3> vertices;
    for (const json& v : b["vertices"]) vertices.emplace_back(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
    const auto faces = b["faces"].get<std::vector<std::vector<int>>>();
    const auto mass = mass_properties(vertices, faces);
    const double volume = b["volume"].get<double>();
    EXPECT_NEAR(mass.volume, volume, 1e-12 * volume);
    // Relative to the block's size (the far block sits 1e3 m from the origin).
    const double size = std::cbrt(volume);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(mass.centroid[i], b["centroid"][i].get<double>(), 1e-10 * size);
  }
}
