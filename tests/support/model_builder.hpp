// Small helpers that write model JSON for tests, as the CAD side would.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace rbla::testing {

using nlohmann::json;

/// An axis-aligned box [x0,x1]x[y0,y1]x[z0,z1] with outward counter-clockwise faces.
inline json box_block(const std::string& id, double x0, double y0, double z0, double x1, double y1, double z1,
                      const std::string& role = "free") {
  json vertices = json::array({{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0},
                               {x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}});
  json faces = json::array({{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}});
  return json{{"id", id}, {"vertices", vertices}, {"faces", faces}, {"role", role}};
}

/// A right prism over a counter-clockwise polygon in the x-y plane, from z0 to z1.
inline json prism_block(const std::string& id, const std::vector<std::pair<double, double>>& outline, double z0,
                        double z1, const std::string& role = "free") {
  const int n = static_cast<int>(outline.size());
  json vertices = json::array();
  for (const auto& [x, y] : outline) vertices.push_back({x, y, z0});
  for (const auto& [x, y] : outline) vertices.push_back({x, y, z1});
  json faces = json::array();
  json bottom = json::array(), top = json::array();
  for (int i = n - 1; i >= 0; --i) bottom.push_back(i);
  for (int i = 0; i < n; ++i) top.push_back(n + i);
  faces.push_back(bottom);
  faces.push_back(top);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    faces.push_back({i, j, n + j, n + i});
  }
  return json{{"id", id}, {"vertices", vertices}, {"faces", faces}, {"role", role}};
}

inline json model_with(json blocks, const std::string& length_unit = "m") {
  return json{{"schema_version", "1.0.0"}, {"units", {{"length", length_unit}}}, {"blocks", std::move(blocks)}};
}

/// Multiplies every coordinate in a model by `factor` (for unit-invariance tests).
inline json scaled(json model, double factor) {
  for (auto& block : model["blocks"]) {
    for (auto& v : block["vertices"]) {
      for (auto& c : v) c = c.get<double>() * factor;
    }
  }
  return model;
}

/// A running-bond wall: `courses` courses of bricks lb x d x hb, `bricks` bricks long; odd
/// courses start and end with half bricks. Lies on [0, bricks lb] x [0, d] x [0, courses hb], on a
/// fixed base slab; every coordinate is multiplied by `scale` (the same wall in other file units).
inline json running_bond_blocks(int bricks, int courses, double scale = 1.0, double lb = 0.4,
                                double hb = 0.2, double d = 0.2) {
  auto box = [scale](const std::string& id, double x0, double y0, double z0, double x1, double y1,
                     double z1, const std::string& role = "free") {
    return box_block(id, scale * x0, scale * y0, scale * z0, scale * x1, scale * y1, scale * z1, role);
  };
  json blocks = json::array({box("base", -0.5, -0.3, -0.3, bricks * lb + 0.5, d + 0.3, 0.0, "fixed")});
  for (int c = 0; c < courses; ++c) {
    std::vector<double> joints;
    if (c % 2 == 0) {
      for (int i = 0; i <= bricks; ++i) joints.push_back(i * lb);
    } else {
      joints.push_back(0.0);
      for (int i = 0; i < bricks; ++i) joints.push_back((i + 0.5) * lb);
      joints.push_back(bricks * lb);
    }
    for (std::size_t i = 0; i + 1 < joints.size(); ++i) {
      blocks.push_back(box("W" + std::to_string(c) + "_" + std::to_string(i), joints[i], 0.0, c * hb,
                           joints[i + 1], d, (c + 1) * hb));
    }
  }
  return blocks;
}

}  // namespace rbla::testing
