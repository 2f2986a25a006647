// Model JSON for a barrel vault laid in running bond, with the CAD imperfections of an export:
// every vertex of every voussoir moved by independent noise, so faces are warped and joints
// neither exactly planar nor exactly closed.
//
// The vault's cross-section is the semicircular arch of samples/arch.json (16 radial rings,
// centreline radius 5 m, thickness 0.8 m, on fixed abutments, springing at z = 0): each ring is
// cut along the vault's axis y into units of `unit_length`, the odd rings shifted by half a unit
// (half units at both ends). Under a horizontal load across the axis every ring of the same
// angle moves alike, so the vault collapses as the arch does (samples/expected.json: alpha =
// 0.1774597765, CLP on the arch's LP) along four hinge lines, each a whole row of bed joints
// between two rings; head joints (between units of one ring) stay closed.
#pragma once

#include "support/model_builder.hpp"

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace rbla::testing {

struct VaultSpec {
  int rings = 16;            ///< voussoir rings across the span (radial joints between them)
  double radius = 5.0;       ///< centreline radius R (m)
  double thickness = 0.8;    ///< radial thickness t (m)
  int units = 4;             ///< units per even ring along the axis
  double unit_length = 1.0;  ///< m
  double noise = 0.0;        ///< each vertex coordinate of a voussoir moves by up to +- noise (m)
  unsigned seed = 7;
};

/// Voussoir ids: "v<ring>_<unit>" (ring 0 at x < 0, unit 0 at y = 0); abutments "AL", "AR".
inline std::string voussoir_id(int ring, int unit) { return "v" + std::to_string(ring) + "_" + std::to_string(unit); }

inline json vault_blocks(const VaultSpec& spec) {
  const double ri = spec.radius - 0.5 * spec.thickness, re = spec.radius + 0.5 * spec.thickness;
  const double length = spec.units * spec.unit_length;
  std::mt19937 random(spec.seed);
  // Uniform in [-1, 1] from the raw 32-bit draws: the same numbers on every standard library.
  auto jitter = [&]() { return spec.noise * (2.0 * static_cast<double>(random()) / 4294967295.0 - 1.0); };
  json blocks = json::array();
  blocks.push_back(box_block("AL", -re - 0.3, -0.3, -0.5, -ri + 0.3, length + 0.3, 0.0, "fixed"));
  blocks.push_back(box_block("AR", ri - 0.3, -0.3, -0.5, re + 0.3, length + 0.3, 0.0, "fixed"));
  for (int i = 0; i < spec.rings; ++i) {
    // Ring i between the radial planes at angles phi0 > phi1 from +x; the springings exactly flat.
    const double phi0 = M_PI * (1.0 - static_cast<double>(i) / spec.rings);
    const double phi1 = M_PI * (1.0 - static_cast<double>(i + 1) / spec.rings);
    const double c0 = i == 0 ? -1.0 : std::cos(phi0), s0 = i == 0 ? 0.0 : std::sin(phi0);
    const double c1 = i + 1 == spec.rings ? 1.0 : std::cos(phi1), s1 = i + 1 == spec.rings ? 0.0 : std::sin(phi1);
    // Section corners counter-clockwise seen from -y (x right, z up).
    const std::vector<std::pair<double, double>> section = {
        {ri * c1, ri * s1}, {re * c1, re * s1}, {re * c0, re * s0}, {ri * c0, ri * s0}};
    std::vector<double> cuts{0.0};
    for (int k = 1; k <= spec.units; ++k) {
      if (i % 2 == 1) cuts.push_back((k - 0.5) * spec.unit_length);
      else if (k < spec.units) cuts.push_back(k * spec.unit_length);
    }
    cuts.push_back(length);
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      json vertices = json::array();
      for (const double y : {cuts[k], cuts[k + 1]}) {
        for (const auto& [x, z] : section) vertices.push_back({x + jitter(), y + jitter(), z + jitter()});
      }
      // Vertices 0-3 at y0, 4-7 at y1; outward faces: y0 cap, y1 cap, then the four sides.
      json faces = json::array({{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1}, {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}});
      blocks.push_back(json{{"id", voussoir_id(i, static_cast<int>(k))}, {"vertices", vertices}, {"faces", faces}});
    }
  }
  return blocks;
}

/// The vault with unit weight 18 kN/m3, friction 0.6, seismic along +x (across the axis).
inline json vault_model(const VaultSpec& spec) {
  json model = model_with(vault_blocks(spec));
  model["defaults"] = {{"unit_weight", 18.0}, {"friction", 0.6}};
  model["analysis"] = {{"type", "load_multiplier"}, {"seismic", {{"direction", {1.0, 0.0, 0.0}}}}};
  return model;
}

/// The ring of a voussoir id "v<ring>_<unit>", -1 for an abutment.
inline int ring_of(const std::string& id) {
  return id.size() > 1 && id[0] == 'v' ? std::stoi(id.substr(1, id.find('_') - 1)) : -1;
}

}  // namespace rbla::testing
