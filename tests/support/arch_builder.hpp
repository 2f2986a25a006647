// Model JSON for a semicircular arch of radial voussoirs, as the CAD side would write it.
//
// The arch lies in the x-z plane (gravity -z), centred on the origin, springing at z = 0, and is
// extruded along y over [0, depth]. `radius` is the CENTRELINE radius R (the radius of the
// mid-thickness line, as in Milankovitch and Cocchetti-Rizzi); the intrados radius is R - t/2,
// the extrados R + t/2. Voussoir i (0-based, from the right springing at theta = 0 to the left
// one at theta = pi) spans theta in [pi i/N, pi (i+1)/N]: a prism between two radial planes with
// 8 vertices and 6 planar faces (the curved intrados and extrados are replaced by their chords,
// as in any polyhedral block model). Two fixed abutment blocks carry the springing joints.
#pragma once

#include "support/model_builder.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace rbla::testing {

/// A convex polyhedron from its vertices and faces given in any winding: every face is turned so
/// that it is counter-clockwise seen from outside (normal away from the vertex centroid).
inline json convex_block(const std::string& id, const std::vector<std::array<double, 3>>& vertices,
                         std::vector<std::vector<int>> faces, const std::string& role = "free") {
  std::array<double, 3> c{0.0, 0.0, 0.0};
  for (const auto& v : vertices) {
    for (int k = 0; k < 3; ++k) c[k] += v[k] / static_cast<double>(vertices.size());
  }
  for (auto& face : faces) {
    // Newell normal of the face and its centre.
    std::array<double, 3> n{0.0, 0.0, 0.0}, p{0.0, 0.0, 0.0};
    const std::size_t m = face.size();
    for (std::size_t i = 0; i < m; ++i) {
      const auto& a = vertices[face[i]];
      const auto& b = vertices[face[(i + 1) % m]];
      n[0] += (a[1] - b[1]) * (a[2] + b[2]);
      n[1] += (a[2] - b[2]) * (a[0] + b[0]);
      n[2] += (a[0] - b[0]) * (a[1] + b[1]);
      for (int k = 0; k < 3; ++k) p[k] += a[k] / static_cast<double>(m);
    }
    const double outward = n[0] * (p[0] - c[0]) + n[1] * (p[1] - c[1]) + n[2] * (p[2] - c[2]);
    if (outward < 0.0) std::reverse(face.begin(), face.end());
  }
  json jv = json::array();
  for (const auto& v : vertices) jv.push_back({v[0], v[1], v[2]});
  return json{{"id", id}, {"vertices", jv}, {"faces", faces}, {"role", role}};
}

struct ArchSpec {
  int voussoirs = 20;
  double radius = 1.0;     ///< centreline radius R (m)
  double thickness = 0.15; ///< radial thickness t (m)
  double depth = 0.5;      ///< extrusion along y (m)
};

/// The blocks of the arch: voussoirs "V0".."V{N-1}" then fixed abutments "AR" (x > 0), "AL".
inline json arch_blocks(const ArchSpec& spec) {
  const double ri = spec.radius - 0.5 * spec.thickness;
  const double re = spec.radius + 0.5 * spec.thickness;
  const double d = spec.depth;
  json blocks = json::array();
  for (int i = 0; i < spec.voussoirs; ++i) {
    // Joint j at theta = pi j / N; the springing joints (j = 0, N) exactly horizontal.
    auto cs = [&](int j) {
      if (j == 0) return std::array<double, 2>{1.0, 0.0};
      if (j == spec.voussoirs) return std::array<double, 2>{-1.0, 0.0};
      const double theta = M_PI * j / spec.voussoirs;
      return std::array<double, 2>{std::cos(theta), std::sin(theta)};
    };
    const auto ca = cs(i), cb = cs(i + 1);
    std::vector<std::array<double, 3>> v = {
        {ri * ca[0], 0.0, ri * ca[1]}, {re * ca[0], 0.0, re * ca[1]}, {re * cb[0], 0.0, re * cb[1]},
        {ri * cb[0], 0.0, ri * cb[1]}, {ri * ca[0], d, ri * ca[1]},   {re * ca[0], d, re * ca[1]},
        {re * cb[0], d, re * cb[1]},   {ri * cb[0], d, ri * cb[1]}};
    std::vector<std::vector<int>> faces = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                           {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    blocks.push_back(convex_block("V" + std::to_string(i), v, faces));
  }
  const double t = spec.thickness;
  blocks.push_back(box_block("AR", ri - t, 0.0, -t, re + t, d, 0.0, "fixed"));
  blocks.push_back(box_block("AL", -re - t, 0.0, -t, -ri + t, d, 0.0, "fixed"));
  return blocks;
}

/// A whole model: the arch, unit weight `unit_weight` (kN/m3), friction `mu`, seismic along +x.
inline json arch_model(const ArchSpec& spec, double mu = 5.0, double unit_weight = 20.0) {
  json model = model_with(arch_blocks(spec));
  model["defaults"] = {{"unit_weight", unit_weight}, {"friction", mu}};
  model["analysis"] = {{"type", "load_multiplier"}, {"seismic", {{"direction", {1.0, 0.0, 0.0}}}}};
  return model;
}

}  // namespace rbla::testing
