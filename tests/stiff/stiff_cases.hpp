// The stiff and extreme cases (issue 7): models as CAD users write them in millimetres or
// kilometres, with friction from 0.01 to 10, unit weights 1e6 apart, 1:1000 slabs and columns,
// tiny or nearly collinear contacts, duplicated and redundant contacts, 1000-block stacks,
// structures at the edge of stability, that cannot stand, or that have no mechanism.
//
// Every case carries an independent reference: a closed form evaluated here (never rbla's own
// output), with its source. tests/stiff/test_stiff_cases.cpp runs the fast ones;
// bench/stiff/stiff_bench.cpp runs all of them and writes docs/stability.md. This header needs
// only nlohmann::json, so the benchmark can share it without GoogleTest.
//
// Closed forms used (see also tests/validation/test_closed_forms.cpp):
//  [block]   a rigid block b (along the load) x h on a rigid base, horizontal load alpha W at the
//            centroid: rocking about the toe at alpha = b/h, sliding at alpha = mu:
//            alpha = min(b/h, mu).
//  [column]  blocks of equal width b stacked to height H on a rigid base, unit weights gamma_i:
//            the part above the joint at height z_j rocks about its toe when
//            alpha sum W_i (z_i - z_j) = sum W_i b/2, and slides when alpha = mu_j. The static
//            state with each joint's resultant at the toe and T = alpha N shared in proportion
//            to N at the corners is admissible up to the same value, so it is exact:
//            alpha = min_j min(mu_j, (b/2) / (zbar_j - z_j)), zbar_j the weighted centroid
//            height of the blocks above joint j. Equal weights: alpha = min(b/H, mu).
//  [support] a block whose centroid is above a support of half-width e (measured from the
//            centroid's vertical to the toe edge, along the load): rocking about that edge at
//            alpha = e / (h/2); e < 0 (centroid beyond the edge): it cannot stand.
//  [slope]   a squat block on a plane inclined at theta, horizontal load down the slope:
//            sliding at alpha = tan(phi - theta), mu = tan(phi); it cannot stand when theta > phi.
//  [pyramid] an m-sided pyramid with an edge on the load direction (the bed joint's t1 = x,
//            load along x): inscribed alpha = mu, circumscribed alpha = mu / cos(pi/m) for a
//            sliding-governed block (tests/validation/test_invariants.cpp, PyramidClosedForms).
//  [leaning] a staircase stack (block-stacking problem), see leaning_stack_alpha.
//  [settle]  a block of length L on a fixed support under [0, a] and a moving support under
//            [a + g, L]: base reaction at collapse R = W (x_G - a) / (L - a)
//            (Portioli & Cascini 2016; derivation in tests/validation/test_closed_forms.cpp).
#pragma once

#include "support/arch_builder.hpp"
#include "support/model_builder.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace rbla::stiff {

using nlohmann::json;
using rbla::testing::ArchSpec;
using rbla::testing::arch_blocks;
using rbla::testing::box_block;
using rbla::testing::running_bond_blocks;

enum class Expect { Collapse, NoMechanism, CannotStand, TimeLimit };

inline const char* to_string(Expect e) {
  switch (e) {
    case Expect::Collapse: return "collapse";
    case Expect::NoMechanism: return "no_mechanism";
    case Expect::CannotStand: return "cannot_stand";
    case Expect::TimeLimit: return "time_limit";
  }
  return "?";
}

/// Why 1e-6 relative + 1e-7 absolute: the solver stops at a relative duality gap of 1e-8 of
/// max(1, |objective|) in its scaled problem, so a large alpha is accurate to ~1e-8 relative and
/// a small one to ~1e-8 absolute (times the objective's scale); the test allows two orders more
/// on the relative side and one on the absolute side (scale factors of the scaled objective up
/// to ~10 were observed: alpha = 0.01 came out 2.5e-8 high).
inline const char* const kDefaultTolReason =
    "closed form; solver gap 1e-8 of max(1, |alpha|): allow 1e-6 relative + 1e-7 absolute";

struct StiffCase {
  std::string name;    ///< identifier (letters, digits, underscores): the GoogleTest name
  std::string varies;  ///< what is extreme about it
  json model;
  Expect expect = Expect::Collapse;
  /// alpha, or the base reaction in kN for a settlement analysis; NaN when no number is expected.
  double reference = std::numeric_limits<double>::quiet_NaN();
  std::string source;  ///< the closed form and its inputs
  /// Accepted error: |value - reference| <= rel_tol |reference| + abs_tol.
  double rel_tol = 1e-6;
  double abs_tol = 1e-7;
  std::string tol_reason = kDefaultTolReason;
  bool slow = false;  ///< benchmark only (docs/stability.md), not in the GoogleTest suite
};

/// GoogleTest prints a parameter with this instead of its bytes.
inline void PrintTo(const StiffCase& c, std::ostream* os) { *os << c.name; }

/// Analysis options of one case.
struct Opt {
  std::string friction_model = "associative";
  std::string formulation = "auto";
  std::string cone = "exact";
  int pyramid_faces = 8;
  double mu = 0.6;
  double unit_weight = 18.0;  ///< in `unit_weight_unit`
  std::string length_unit = "m";
  std::string force_unit = "kN";
  std::string unit_weight_unit = "kN/m3";
  json seismic = json::array({1.0, 0.0, 0.0});  ///< null: live loads only
  double na_tolerance = 1e-6;  ///< the non-associative scheme's stopping tolerance
  int na_max_iterations = 200;
};

inline std::string tag(const Opt& o) {
  std::string t = o.formulation == "auto" ? "" : "_" + o.formulation;
  if (o.friction_model == "non_associative") t += "_nonassoc";
  if (o.cone == "pyramid_inscribed") t += "_pyrin" + std::to_string(o.pyramid_faces);
  if (o.cone == "pyramid_circumscribed") t += "_pyrout" + std::to_string(o.pyramid_faces);
  return t;
}

inline json analysis_json(const Opt& o) {
  json a = {{"type", "load_multiplier"},
            {"friction_model", o.friction_model},
            {"formulation", o.formulation},
            {"cone", o.cone},
            {"pyramid_faces", o.pyramid_faces},
            {"non_associative", {{"max_iterations", o.na_max_iterations}, {"tolerance", o.na_tolerance}}}};
  if (!o.seismic.is_null()) a["seismic"] = {{"direction", o.seismic}};
  return a;
}

inline json model_of(json blocks, const Opt& o) {
  json m = {{"schema_version", "1.0.0"},
            {"units", {{"length", o.length_unit}, {"force", o.force_unit}, {"unit_weight", o.unit_weight_unit}}},
            {"defaults", {{"unit_weight", o.unit_weight}, {"friction", o.mu}}},
            {"blocks", std::move(blocks)}};
  m["analysis"] = analysis_json(o);
  return m;
}

/// A box scaled by s (all six coordinates).
inline json sbox(const std::string& id, double s, double x0, double y0, double z0, double x1, double y1, double z1,
                 const std::string& role = "free") {
  return box_block(id, s * x0, s * y0, s * z0, s * x1, s * y1, s * z1, role);
}

/// Block b x depth x h on a wider fixed base, everything scaled by s (file units).
inline json block_blocks(double b, double h, double depth = 1.0, double s = 1.0) {
  const double m = std::max({b, depth, h}) * 0.5;
  return json::array({sbox("base", s, -m, -m, -m, b + m, depth + m, 0.0, "fixed"), sbox("B", s, 0, 0, 0, b, depth, h)});
}

/// Column of blocks of width b (and `depth`) with the given heights, on a fixed base.
inline json column_blocks(double b, const std::vector<double>& heights, double depth = 1.0, double s = 1.0) {
  const double m = std::max(b, depth) * 0.5;
  json blocks = json::array({sbox("base", s, -m, -m, -m, b + m, depth + m, 0.0, "fixed")});
  double z = 0.0;
  for (std::size_t i = 0; i < heights.size(); ++i) {
    blocks.push_back(sbox("C" + std::to_string(i), s, 0, 0, z, b, depth, z + heights[i]));
    z += heights[i];
  }
  return blocks;
}

/// [column]: the multiplier of a column of boxes of width b, heights h_i, unit weights g_i and
/// joint frictions mu_j (joint j under block j).
inline double column_alpha(double b, const std::vector<double>& h, const std::vector<double>& g,
                           const std::vector<double>& mu) {
  std::vector<double> z0(h.size());
  double z = 0.0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    z0[i] = z;
    z += h[i];
  }
  double alpha = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < h.size(); ++j) {
    double w = 0.0, wz = 0.0;
    for (std::size_t i = j; i < h.size(); ++i) {
      w += g[i] * h[i];
      wz += g[i] * h[i] * (z0[i] + 0.5 * h[i]);
    }
    alpha = std::min({alpha, mu[j], 0.5 * b / (wz / w - z0[j])});
  }
  return alpha;
}

inline std::string num(double v) {
  std::string s = nlohmann::json(v).dump();
  return s;
}

/// A leaning stack: n unit-wide boxes of height h, block i on [i delta, i delta + 1], on a wide
/// fixed base (the staircase of the block-stacking problem).
inline json leaning_stack_blocks(int n, double delta, double h) {
  json blocks = json::array({box_block("base", -1.0, -0.5, -1.0, n * delta + 2.0, 1.5, 0.0, "fixed")});
  for (int i = 0; i < n; ++i) {
    blocks.push_back(box_block("S" + std::to_string(i), i * delta, 0.0, i * h, i * delta + 1.0, 1.0, (i + 1) * h));
  }
  return blocks;
}

/// [leaning]: the stack is statically determinate, each joint carries the resultant of the part
/// above it; under alpha W along +x that resultant meets joint j (between blocks j-1 and j, at
/// z_j = j h) at xbar_j + alpha (zbar_j - z_j), which must not pass the joint's right edge
/// e_j = (j - 1) delta + 1 (e_0 = 1, block 0 on the wide base); xbar_j = delta (j + n - 1)/2 + 1/2,
/// zbar_j - z_j = h (n - j)/2. So alpha = min(mu, min_j (e_j - xbar_j) / (zbar_j - z_j)), and it
/// cannot stand when some e_j < xbar_j: at j = 1 that is delta > 1/n (the harmonic stacking limit
/// for equal offsets).
inline double leaning_stack_alpha(int n, double delta, double h, double mu) {
  double alpha = mu;
  for (int j = 0; j < n; ++j) {
    const double edge = j == 0 ? 1.0 : (j - 1) * delta + 1.0;
    const double xbar = delta * (j + n - 1) / 2.0 + 0.5;
    alpha = std::min(alpha, (edge - xbar) / (h * (n - j) / 2.0));
  }
  return alpha;
}

/// The catalogue. `slow` cases are for the benchmark only.
inline std::vector<StiffCase> stiff_cases() {
  std::vector<StiffCase> out;

  // ---- Units: 1 mm to 1 km blocks, N to MN forces --------------------------------------------
  // A 1 x 2 block (b/h = 0.5, mu 0.6: rocking, alpha = 0.5) drawn at 1 mm ... 1 km.
  for (const Opt& base : {Opt{}, Opt{"associative", "3d"}, Opt{"non_associative", "3d"}}) {
    {
      Opt o = base;  // a 1 mm x 2 mm block in a millimetre file, unit weight in N/mm3
      o.length_unit = "mm";
      o.force_unit = "N";
      o.unit_weight_unit = "N/mm3";
      o.unit_weight = 18e-6;
      out.push_back({"block_1mm_in_mm" + tag(o), "length 1e-3 m, file in mm and N", model_of(block_blocks(1, 2), o),
                     Expect::Collapse, 0.5, "[block] min(b/h, mu) = min(0.5, 0.6)"});
    }
    {
      Opt o = base;  // the same block in metres: coordinates of 1e-3
      out.push_back({"block_1mm_in_m" + tag(o), "length 1e-3 m, file in m",
                     model_of(block_blocks(1, 2, 1, 1e-3), o), Expect::Collapse, 0.5,
                     "[block] min(b/h, mu) = min(0.5, 0.6)"});
    }
    {
      Opt o = base;  // 1 km x 2 km: weight 3.6e10 kN
      out.push_back({"block_1km" + tag(o), "length 1e3 m (weight 3.6e10 kN)", model_of(block_blocks(1, 2, 1, 1e3), o),
                     Expect::Collapse, 0.5, "[block] min(b/h, mu) = min(0.5, 0.6)"});
    }
    {
      // Live load P = 1 N horizontal at the centroid of a 36 kN block: alpha P = W b/h.
      Opt o = base;
      o.force_unit = "N";
      o.seismic = nullptr;
      json m = model_of(block_blocks(1, 2), o);
      m["loads"] = {{"live", {{{"block", "B"}, {"force", {1.0, 0.0, 0.0}}}}}};
      out.push_back({"live_1N_on_36kN" + tag(o), "force 1 N against 36 kN (alpha 1.8e4)", m, Expect::Collapse,
                     36.0 * 0.5 / 1e-3, "[block] alpha P = W min(b/h, mu): 36 kN x 0.5 / 1 N"});
      Opt p = o;
      p.force_unit = "MN";
      json mp = model_of(block_blocks(1, 2), p);
      mp["loads"] = {{"live", {{{"block", "B"}, {"force", {1.0, 0.0, 0.0}}}}}};
      out.push_back({"live_1MN_on_36kN" + tag(o), "force 1 MN against 36 kN (alpha 1.8e-2)", mp, Expect::Collapse,
                     36.0 * 0.5 / 1e3, "[block] alpha P = W min(b/h, mu): 36 kN x 0.5 / 1 MN"});
    }
  }
  // A 1 km block under a 1 MN live load with unit weight in N/m3: alpha = 3.6e10 kN x 0.5 / 1e3 kN.
  {
    Opt o{"associative", "3d"};
    o.force_unit = "MN";
    o.unit_weight_unit = "N/m3";
    o.unit_weight = 18e3;
    o.seismic = nullptr;
    json m = model_of(block_blocks(1, 2, 1, 1e3), o);
    m["loads"] = {{"live", {{{"block", "B"}, {"force", {1.0, 0.0, 0.0}}}}}};
    out.push_back({"live_1MN_on_1km_block_3d", "1 km block (3.6e10 kN) under 1 MN (alpha 1.8e7)", m, Expect::Collapse,
                   3.6e10 * 0.5 / 1e3, "[block] alpha P = W min(b/h, mu)"});
  }
  // Settlement in mm and N: R = W (x_G - a) / (L - a), W = 18 kN/m3 x 4 x 1 x 1 m3, a = 1 m.
  for (const std::string friction : {"associative", "non_associative"}) {
    for (const double s : {1e-3, 1.0, 1e3}) {
      const double L = 4.0 * s, a = 1.0 * s, g = 1e-3 * s;
      json blocks = json::array({box_block("fixed", -0.5 * s, -0.5 * s, -0.5 * s, a, 1.5 * s, 0.0, "fixed"),
                                 box_block("moving", a + g, -0.5 * s, -0.5 * s, L + 0.5 * s, 1.5 * s, 0.0,
                                           "moving_support"),
                                 box_block("B", 0.0, 0.0, 0.0, L, s, s)});
      // In a millimetre file: coordinates x1000, unit weight 18 kN/m3 = 1.8e-5 N/mm3.
      for (auto& b : blocks) {
        for (auto& v : b["vertices"]) {
          for (auto& c : v) c = c.get<double>() * 1000.0;
        }
      }
      json m = {{"schema_version", "1.0.0"},
                {"units", {{"length", "mm"}, {"force", "N"}, {"unit_weight", "N/mm3"}}},
                {"defaults", {{"unit_weight", 1.8e-5}, {"friction", 0.6}}},
                {"blocks", blocks},
                {"analysis",
                 {{"type", "settlement"},
                  {"friction_model", friction},
                  {"formulation", "3d"},
                  {"non_associative", {{"max_iterations", 200}, {"tolerance", 1e-6}}}}}};
      const double W = 18.0 * 4.0 * s * s * s, xG = 2.0 * s;
      const std::string size = s < 1 ? "4mm" : s > 1 ? "4km" : "4m";
      out.push_back({"settlement_" + size + "_in_mm_N" + (friction == "associative" ? "" : "_nonassoc"),
                     "settlement, length " + size + " (W = " + num(W) + " kN), file in mm and N", m,
                     Expect::Collapse, W * (xG - a) / (L - a), "[settle] W (x_G - a) / (L - a), a = L/4"});
    }
  }

  // ---- Friction 0.01 to 10 -----------------------------------------------------------------
  for (const std::string friction : {"associative", "non_associative"}) {
    for (const double mu : {0.01, 0.1, 1.0, 10.0}) {
      for (const std::string formulation : {"auto", "3d"}) {
        Opt o{friction, formulation};
        o.mu = mu;
        // Squat block b/h = 4: slides for mu < 4, rocks at mu = 10.
        out.push_back({"friction_" + num(mu) + "_squat" + tag(o), "friction mu = " + num(mu) + ", b/h = 4",
                       model_of(block_blocks(4, 1), o), Expect::Collapse, std::min(4.0, mu),
                       "[block] min(b/h, mu) = min(4, " + num(mu) + ")"});
      }
    }
    {
      Opt o{friction, "3d"};
      o.mu = 10.0;  // a slab b/h = 20 slides at mu = 10 (dilatancy 10x the slip when associative)
      out.push_back({"friction_10_slab_b_h_20" + tag(o), "friction mu = 10, sliding", model_of(block_blocks(20, 1), o),
                     Expect::Collapse, 10.0, "[block] min(b/h, mu) = min(20, 10)"});
    }
  }
  // Per-interface friction 10 (lower joint) and 0.02 (upper joint), given interfaces.
  for (const std::string friction : {"associative", "non_associative"}) {
    for (const std::string formulation : {"auto", "3d"}) {
      Opt o{friction, formulation};
      json m = model_of(column_blocks(4, {0.5, 0.5}), o);
      auto square = [](double z) { return json::array({{0, 0, z}, {4, 0, z}, {4, 1, z}, {0, 1, z}}); };
      m["interfaces"] = {{{"id", "bed"}, {"blocks", {"base", "C0"}}, {"polygon", square(0.0)}, {"friction", 10.0}},
                         {{"id", "joint"}, {"blocks", {"C0", "C1"}}, {"polygon", square(0.5)}, {"friction", 0.02}}};
      out.push_back({"friction_10_and_0p02_joints" + tag(o), "joint frictions 10 and 0.02 in one model", m,
                     Expect::Collapse, column_alpha(4, {0.5, 0.5}, {1, 1}, {10.0, 0.02}),
                     "[column] the upper joint slides: mu = 0.02"});
    }
  }
  // Pyramids at mu = 0.01 and 10 (load on a pyramid edge): inscribed exact, circumscribed mu/cos(pi/m).
  for (const double mu : {0.01, 10.0}) {
    for (const int m : {4, 8}) {
      for (const std::string cone : {"pyramid_inscribed", "pyramid_circumscribed"}) {
        Opt o{"associative", "3d", cone, m};
        o.mu = mu;
        const double bh = 40.0;  // squat enough that sliding governs even at 10 / cos(pi/4)
        const double expected = cone == "pyramid_inscribed" ? mu : mu / std::cos(M_PI / m);
        out.push_back({"friction_" + num(mu) + tag(o), "friction mu = " + num(mu) + ", " + std::to_string(m) +
                                                           "-sided pyramid",
                       model_of(block_blocks(bh, 1), o), Expect::Collapse, expected,
                       cone == "pyramid_inscribed" ? "[pyramid] inscribed, load on an edge: mu"
                                                   : "[pyramid] circumscribed: mu / cos(pi/m)"});
      }
    }
  }

  // ---- Unit-weight contrast 1e6 --------------------------------------------------------------
  for (const Opt& base : {Opt{}, Opt{"associative", "3d"}, Opt{"non_associative", "3d"}}) {
    {
      // Heavy (1e6 x) block on a light one, both 1 x 1: the column rocks about the base toe.
      Opt o = base;
      json blocks = column_blocks(1, {1, 1});
      blocks[2]["unit_weight"] = 18e6;
      const double e = column_alpha(1, {1, 1}, {1, 1e6}, {0.6, 0.6});
      out.push_back({"contrast_1e6_heavy_on_light" + tag(o), "unit weights 18 and 1.8e7 kN/m3 (heavy on top)",
                     model_of(blocks, o), Expect::Collapse, e, "[column] (b/2)/zbar, zbar the weighted centroid"});
    }
    {
      // Light slender block (1 x 4) on a 1e6 x heavier base block: the light block governs.
      Opt o = base;
      json blocks = column_blocks(1, {1, 4});
      blocks[1]["unit_weight"] = 18e6;
      out.push_back({"contrast_1e6_light_on_heavy" + tag(o), "unit weights 1.8e7 and 18 kN/m3 (light on top)",
                     model_of(blocks, o), Expect::Collapse, column_alpha(1, {1, 4}, {1e6, 1}, {0.6, 0.6}),
                     "[column] the light top block rocks: b/h = 0.25"});
    }
    {
      // Light block 1e-6 x lighter between heavy ones: a 3-block column, mu 2 so rocking governs.
      Opt o = base;
      o.mu = 2.0;
      json blocks = column_blocks(1, {1, 1, 1});
      blocks[2]["unit_weight"] = 18e-6;
      out.push_back({"contrast_1e6_light_in_middle" + tag(o), "unit weights 18, 1.8e-5, 18 kN/m3",
                     model_of(blocks, o), Expect::Collapse, column_alpha(1, {1, 1, 1}, {1, 1e-6, 1}, {2, 2, 2}),
                     "[column] weighted centroids"});
    }
  }

  // ---- Unit-weight contrasts 1e9 to 1e20 (issue 19) --------------------------------------------
  // With one force scale for the whole model (the mean free-block weight) a block 1e9 lighter
  // than the one it stands on fell below the solver's tolerance: alpha 0.6 (the heavy block
  // sliding) instead of 0.5. The schema caps a unit weight at 1e12 kN/m3; contrasts beyond 1e12
  // come from small unit weights (1e-8 kN/m3 against 1e12 for 1e20).
  for (const Opt& base : {Opt{}, Opt{"associative", "3d"}, Opt{"non_associative", "3d"}}) {
    for (const int e : {9, 12, 20}) {
      const double heavy = std::min(std::pow(10.0, e), 1e12), light = heavy / std::pow(10.0, e);
      const std::string c = "contrast_1e" + std::to_string(e) + "_";
      const std::string weights = " kN/m3";
      Opt o = base;
      o.unit_weight = 1.0;
      {
        // The case: a light 1 x 2 block on a heavy 1 x 1 one; the light block rocks.
        json blocks = column_blocks(1, {1, 2});
        blocks[1]["unit_weight"] = heavy;
        blocks[2]["unit_weight"] = light;
        out.push_back({c + "light_on_heavy" + tag(o), "unit weights " + num(heavy) + " and " + num(light) + weights,
                       model_of(blocks, o), Expect::Collapse, column_alpha(1, {1, 2}, {heavy, light}, {0.6, 0.6}),
                       "[column] the light top block rocks: b/h = 0.5 (the heavy one alone would slide at 0.6)"});
      }
      {
        json blocks = column_blocks(1, {1, 1});
        blocks[1]["unit_weight"] = light;
        blocks[2]["unit_weight"] = heavy;
        out.push_back({c + "heavy_on_light" + tag(o), "unit weights " + num(light) + " and " + num(heavy) + weights,
                       model_of(blocks, o), Expect::Collapse, column_alpha(1, {1, 1}, {light, heavy}, {0.6, 0.6}),
                       "[column] (b/2)/zbar, zbar the weighted centroid"});
      }
      {
        Opt m = o;
        m.mu = 2.0;
        json blocks = column_blocks(1, {1, 1, 1});
        blocks[1]["unit_weight"] = heavy;
        blocks[2]["unit_weight"] = light;
        blocks[3]["unit_weight"] = heavy;
        out.push_back({c + "light_in_middle" + tag(m), "unit weights " + num(heavy) + ", " + num(light) + ", " + num(heavy) + weights,
                       model_of(blocks, m), Expect::Collapse, column_alpha(1, {1, 1, 1}, {heavy, light, heavy}, {2, 2, 2}),
                       "[column] weighted centroids"});
      }
    }
    // Under the warning limits (analysis/force_scales.hpp): 1e14 associative, 1e10 non-associative.
    const std::vector<int> lateral = base.friction_model == "associative" ? std::vector<int>{9, 12, 14} : std::vector<int>{9};
    for (const int e : lateral) {
      // A light 1 x 1 block beside a heavy one of the same size, both on the base; the light one's
      // bed joint has friction 0.3, the rest 0.6: pushed away from the heavy block it slides at
      // alpha = 0.3, whatever its weight (the heavy one alone would slide at 0.6). Side by side, no
      // load passes from one to the other: the light block's scale lies between the two.
      Opt o = base;
      o.unit_weight = 1.0;
      const double heavy = std::min(std::pow(10.0, e), 1e12), light = heavy / std::pow(10.0, e);
      json blocks = json::array({box_block("base", -0.5, -0.5, -0.5, 2.5, 1.5, 0.0, "fixed"),
                                 box_block("H", 0, 0, 0, 1, 1, 1), box_block("L", 1, 0, 0, 2, 1, 1)});
      blocks[1]["unit_weight"] = heavy;
      blocks[2]["unit_weight"] = light;
      json model = model_of(blocks, o);
      model["interfaces"] = json::array({{{"id", "L_bed"}, {"blocks", {"base", "L"}}, {"friction", 0.3},
                                          {"polygon", {{1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}}}}});
      model["detection"] = {{"mode", "merge"}};
      out.push_back({"contrast_1e" + std::to_string(e) + "_light_beside_heavy" + tag(o),
                     "unit weights " + num(heavy) + " and " + num(light) + " kN/m3, side by side", model,
                     Expect::Collapse, 0.3, "[block] the light block slides on its own bed joint: mu = 0.3"});
    }
  }

  // ---- Aspect ratios to 1:1000 -----------------------------------------------------------------
  for (const Opt& o : {Opt{}, Opt{"associative", "3d"}, Opt{"non_associative"}, Opt{"non_associative", "3d"}}) {
    out.push_back({"slender_block_1_1000" + tag(o), "column 0.01 x 10 m (1:1000), one block",
                   model_of(block_blocks(0.01, 10, 1), o), Expect::Collapse, 1e-3, "[block] b/h = 1e-3"});
    out.push_back({"slender_column_10_blocks_1_1000" + tag(o), "column 0.01 x 10 m (1:1000), 10 blocks",
                   model_of(column_blocks(0.01, std::vector<double>(10, 1.0), 1), o), Expect::Collapse, 1e-3,
                   "[column] b/H = 1e-3"});
    out.push_back({"thin_slab_1000_1" + tag(o), "slab 10 x 0.01 m (1000:1), slides",
                   model_of(block_blocks(10, 0.01, 1), o), Expect::Collapse, 0.6, "[block] min(b/h = 1000, mu = 0.6)"});
    out.push_back({"thin_slab_stack_5" + tag(o), "5 slabs 10 x 0.01 m, slides",
                   model_of(column_blocks(10, std::vector<double>(5, 0.01), 1), o), Expect::Collapse, 0.6,
                   "[column] min(b/H = 200, mu = 0.6)"});
  }
  for (const Opt& base : {Opt{}, Opt{"associative", "3d"}, Opt{"non_associative", "3d"}}) {
    // A wall 1 m long, 1 cm thick, 10 m high, pushed out of its plane (+y): alpha = d/h = 1e-3.
    Opt o = base;
    o.seismic = json::array({0.0, 1.0, 0.0});
    out.push_back({"thin_wall_out_of_plane_1_1000" + tag(o), "wall 0.01 thick x 10 m high, out of plane",
                   model_of(block_blocks(1, 10, 0.01), o), Expect::Collapse, 1e-3, "[block] d/h = 1e-3"});
  }

  // ---- Tiny interfaces and nearly collinear contact points ---------------------------------
  for (const Opt& o : {Opt{}, Opt{"associative", "3d"}, Opt{"non_associative", "3d"},
                       Opt{"associative", "3d", "pyramid_inscribed", 4}}) {
    // A 1 x 1 x 1 block on a fixed post 0.01 x 0.01 (1e-4 of its base), centred: alpha = e/(h/2),
    // e = 0.005.
    json blocks = json::array({box_block("post", 0.495, 0.495, -1.0, 0.505, 0.505, 0.0, "fixed"),
                               box_block("B", 0, 0, 0, 1, 1, 1)});
    out.push_back({"tiny_interface_1e-4" + tag(o), "contact area 1e-4 of the face", model_of(blocks, o),
                   Expect::Collapse, 0.01, "[support] e/(h/2) = 0.005/0.5"});
    // Knife edge: a strip 1e-4 wide (x) and 1 long (y), contact corners nearly collinear. The
    // default detection tolerance (1e-4 of the 3.5 m diagonal) is wider than the strip, so
    // detection would (with an isolated_block warning) find no contact: the CAD states a finer
    // tolerance, or gives the interface itself.
    json knife = json::array({box_block("edge", 0.49995, -0.5, -1.0, 0.50005, 1.5, 0.0, "fixed"),
                              box_block("B", 0, 0, 0, 1, 1, 1)});
    json detected = model_of(knife, o);
    detected["detection"] = {{"distance_tolerance", 1e-6}};
    out.push_back({"knife_edge_1e-4" + tag(o), "contact strip 1e-4 x 1: nearly collinear corners (detected)",
                   detected, Expect::Collapse, 1e-4, "[support] e/(h/2) = 5e-5/0.5"});
    json given = model_of(knife, o);
    given["interfaces"] = {{{"blocks", {"edge", "B"}},
                            {"polygon", {{0.49995, 0, 0}, {0.50005, 0, 0}, {0.50005, 1, 0}, {0.49995, 1, 0}}}}};
    out.push_back({"knife_edge_1e-4_given" + tag(o), "contact strip 1e-4 x 1: nearly collinear corners (given)",
                   given, Expect::Collapse, 1e-4, "[support] e/(h/2) = 5e-5/0.5"});
    // The post off-centre (its near edge 0.295 beyond the centroid): under dead load alone the
    // block falls. (A horizontal push alpha W would move the resultant onto the post for alpha in
    // [0.59, 0.61]; standing only while pushed is not standing, so the verdict is cannot stand.)
    json off = json::array({box_block("post", 0.795, 0.495, -1.0, 0.805, 0.505, 0.0, "fixed"),
                            box_block("B", 0, 0, 0, 1, 1, 1)});
    out.push_back({"tiny_interface_off_centre" + tag(o), "contact 1e-4 of the face, centroid outside it",
                   model_of(off, o), Expect::CannotStand, std::nan(""), "[support] e = -0.295 < 0"});
  }

  // ---- Rank-deficient and redundant contact sets ---------------------------------------------
  for (const Opt& o : {Opt{}, Opt{"associative", "3d"}, Opt{"non_associative", "3d"}}) {
    // The support pasted twice (a CAD duplicate): every contact point appears twice.
    json blocks = block_blocks(1, 2);
    blocks.push_back(blocks[0]);
    blocks[2]["id"] = "base_copy";
    out.push_back({"duplicated_support" + tag(o), "support block pasted twice: duplicate contact columns",
                   model_of(blocks, o), Expect::Collapse, 0.5, "[block] min(0.5, 0.6); duplicates add no capacity"});
    // The same interface given twice with the same polygon.
    json m = model_of(block_blocks(1, 2), o);
    const json poly = json::array({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    m["interfaces"] = {{{"id", "i1"}, {"blocks", {"base", "B"}}, {"polygon", poly}},
                       {{"id", "i2"}, {"blocks", {"base", "B"}}, {"polygon", poly}}};
    out.push_back({"duplicated_interface" + tag(o), "one interface given twice", m, Expect::Collapse, 0.5,
                   "[block] min(0.5, 0.6)"});
    // The base contact split into 20 x 20 given interfaces (1600 contact points, most coincident).
    json r = model_of(block_blocks(1, 2), o);
    r["interfaces"] = json::array();
    const int k = 20;
    for (int i = 0; i < k; ++i) {
      for (int j = 0; j < k; ++j) {
        const double x0 = double(i) / k, x1 = double(i + 1) / k, y0 = double(j) / k, y1 = double(j + 1) / k;
        r["interfaces"].push_back({{"blocks", {"base", "B"}},
                                   {"polygon", {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}}}});
      }
    }
    out.push_back({"redundant_400_interfaces" + tag(o), "base contact split into 400 interfaces", r,
                   Expect::Collapse, 0.5, "[block] min(0.5, 0.6)"});
    // A weightless free block floating beside the structure: zero rows and no load.
    json w = block_blocks(1, 2);
    w.push_back(box_block("ghost", 5, 5, 5, 6, 6, 6));
    w[2]["unit_weight"] = 0.0;
    out.push_back({"weightless_floating_block" + tag(o), "an unloaded block with no contact (zero rows)",
                   model_of(w, o), Expect::Collapse, 0.5, "[block] min(0.5, 0.6); the unloaded block does no work"});
  }

  // ---- Edge of stability, cannot stand, no mechanism -----------------------------------------
  for (const Opt& o : {Opt{}, Opt{"associative", "3d"}, Opt{"non_associative", "3d"}}) {
    // A 1 x 1 x 1 block overhanging a support whose edge is e beyond its centroid: alpha = 2e.
    for (const double e : {1e-2, 1e-4, 1e-6}) {
      json blocks = json::array({box_block("support", -1.0, -0.5, -1.0, 0.5 + e, 1.5, 0.0, "fixed"),
                                 box_block("B", 0, 0, 0, 1, 1, 1)});
      out.push_back({"overhang_e_" + num(e) + tag(o), "edge of stability: support edge " + num(e) + " past the centroid",
                     model_of(blocks, o), Expect::Collapse, 2 * e, "[support] e/(h/2) = 2e"});
    }
    json beyond = json::array({box_block("support", -1.0, -0.5, -1.0, 0.5 - 1e-3, 1.5, 0.0, "fixed"),
                               box_block("B", 0, 0, 0, 1, 1, 1)});
    out.push_back({"overhang_e_-0.001" + tag(o), "support edge 1e-3 short of the centroid", model_of(beyond, o),
                   Expect::CannotStand, std::nan(""), "[support] e = -1e-3 < 0"});
    // [slope]: a squat block (2 x 0.5) on a 1-degree incline, +x downhill.
    const double theta = M_PI / 180.0;
    for (const double mu : {0.02, 0.01}) {
      Opt p = o;
      p.mu = mu;
      json ground = box_block("ground", -3, -0.5, -1, 5, 1.5, 0, "fixed");
      json blk = box_block("B", 0, 0, 0, 2, 1, 0.5);
      for (json* b : {&ground, &blk}) {
        for (auto& v : (*b)["vertices"]) {
          const double x = v[0].get<double>(), z = v[2].get<double>();
          v[0] = std::cos(theta) * x + std::sin(theta) * z;
          v[2] = -std::sin(theta) * x + std::cos(theta) * z;
        }
      }
      const double phi = std::atan(mu);
      const bool stands = phi > theta;
      out.push_back({"slope_1deg_mu_" + num(mu) + tag(p),
                     "1-degree slope, mu = " + num(mu) + (stands ? " (just stands)" : " (slides)"),
                     model_of(json::array({ground, blk}), p), stands ? Expect::Collapse : Expect::CannotStand,
                     stands ? std::tan(phi - theta) : std::nan(""),
                     stands ? "[slope] tan(atan(mu) - 1 deg)" : "[slope] 1 deg > atan(0.01) = 0.573 deg"});
    }
    // A block locked in a pit at 1 mm scale: no mechanism.
    {
      Opt p = o;
      p.length_unit = "mm";
      json pit = json::array({box_block("floor", -1, -1, -0.5, 2, 2, 0, "fixed"),
                              box_block("west", -1, -1, 0, 0, 2, 1, "fixed"), box_block("east", 1, -1, 0, 2, 2, 1, "fixed"),
                              box_block("south", 0, -1, 0, 1, 0, 1, "fixed"),
                              box_block("north", 0, 1, 0, 1, 2, 1, "fixed"), box_block("B", 0, 0, 0, 1, 1, 1)});
      out.push_back({"locked_in_pit_1mm" + tag(p), "1 mm block locked in a pit", model_of(pit, p),
                     Expect::NoMechanism, std::nan(""), "no admissible motion"});
    }
    {
      // A downward live load of 1 MN on a 36 kN block: compression is unlimited, no collapse.
      Opt p = o;
      p.force_unit = "MN";
      p.seismic = nullptr;
      json m = model_of(block_blocks(1, 2), p);
      m["loads"] = {{"live", {{{"block", "B"}, {"force", {0.0, 0.0, -1.0}}}}}};
      out.push_back({"downward_live_load" + tag(p), "a live load that only compresses", m, Expect::NoMechanism,
                     std::nan(""), "infinite compressive strength"});
    }
  }

  // Leaning stacks at the harmonic-stacking limit delta = 1/n: 1% inside (stands, alpha ~ 1e-4)
  // and 1% beyond (cannot stand).
  for (const int n : {100, 1000}) {
    for (const Opt& o : {Opt{}, Opt{"associative", "3d"}, Opt{"non_associative", "3d"}}) {
      if (n == 1000 && o.friction_model == "non_associative") continue;
      const double h = 0.1, inside = 0.99 / n, beyond = 1.01 / n;
      StiffCase stands{"leaning_stack_" + std::to_string(n) + "_at_0.99_limit" + tag(o),
                       std::to_string(n) + "-block leaning stack, offsets 0.99 of the stacking limit",
                       model_of(leaning_stack_blocks(n, inside, h), o), Expect::Collapse,
                       leaning_stack_alpha(n, inside, h, o.mu), "[leaning] min_j (e_j - xbar_j)/(zbar_j - z_j)"};
      StiffCase falls{"leaning_stack_" + std::to_string(n) + "_at_1.01_limit" + tag(o),
                      std::to_string(n) + "-block leaning stack, offsets 1.01 of the stacking limit",
                      model_of(leaning_stack_blocks(n, beyond, h), o), Expect::CannotStand, std::nan(""),
                      "[leaning] delta > 1/n: the part above joint 1 overhangs"};
      stands.slow = falls.slow = n == 1000 && o.formulation == "3d";
      out.push_back(stands);
      out.push_back(falls);
    }
  }

  // ---- Size: tall stacks ------------------------------------------------------------------
  for (const Opt& o : {Opt{}, Opt{"associative", "3d"}}) {
    out.push_back({"stack_200" + tag(o), "200-block stack, b/H = 0.05", model_of(column_blocks(1, std::vector<double>(200, 0.1)), o),
                   Expect::Collapse, 0.05, "[column] min(b/H, mu) = 1/20"});
  }
  // The 1000-block stack: associative in the suite (under a second); non-associative takes
  // seconds, benchmark only.
  for (const Opt& o : {Opt{}, Opt{"associative", "3d"}, Opt{"non_associative"}, Opt{"non_associative", "3d"}}) {
    StiffCase c{"stack_1000" + tag(o), "1000-block stack, b/H = 0.01",
                model_of(column_blocks(1, std::vector<double>(1000, 0.1)), o), Expect::Collapse, 0.01,
                "[column] min(b/H, mu) = 1/100"};
    c.slow = o.friction_model == "non_associative";
    out.push_back(c);
  }
  {
    // 1000 slabs 1000:1 (10 x 0.01 m), with the weight contrast 1e6 between alternate slabs.
    Opt o;
    std::vector<double> h(1000, 0.01), g(1000, 1.0);
    json blocks = column_blocks(10, h);
    for (std::size_t i = 0; i < h.size(); i += 2) {
      blocks[i + 1]["unit_weight"] = 18e6;
      g[i] = 1e6;
    }
    StiffCase c{"slab_stack_1000_contrast_1e6", "1000 slabs 1000:1, unit weights alternating 1e6 apart",
                model_of(blocks, o), Expect::Collapse, column_alpha(10, h, g, std::vector<double>(1000, 0.6)),
                "[column] min(mu, b/2 / zbar) = mu"};
    c.slow = true;
    out.push_back(c);
  }
  {
    Opt o{"associative", "3d"};
    std::vector<double> h(1000, 0.01), g(1000, 1.0);
    json blocks = column_blocks(10, h);
    for (std::size_t i = 0; i < h.size(); i += 2) {
      blocks[i + 1]["unit_weight"] = 18e6;
      g[i] = 1e6;
    }
    StiffCase c{"slab_stack_1000_contrast_1e6" + tag(o), "1000 slabs 1000:1, unit weights alternating 1e6 apart",
                model_of(blocks, o), Expect::Collapse, column_alpha(10, h, g, std::vector<double>(1000, 0.6)),
                "[column] min(mu, b/2 / zbar) = mu"};
    c.slow = true;
    out.push_back(c);
  }

  // The non-associative scheme stops when alpha changes by less than its tolerance (1e-6
  // relative, Opt::na_tolerance) between two solves; a damped fixed point stopped there is
  // within a few times that of its limit: allow 1e-5 relative (plus the 1e-7 absolute above).
  for (auto& c : out) {
    if (c.model["analysis"].value("friction_model", "") == "non_associative") {
      c.rel_tol = 1e-5;
      c.tol_reason = "non-associative: scheme stops at 1e-6 relative change of alpha; allow 1e-5 relative + 1e-7 absolute";
    }
  }
  return out;
}

// running_bond_blocks (tests/support/model_builder.hpp): the wall of the rescaled-twin checks.

/// A model and its well-conditioned twin (the same mechanics at 1 m scale, in kN): the
/// reference is the twin's alpha, so no closed form is needed (STYLE.md allows a twin run by
/// the same solver only for such scale changes, where the non-dimensionalised problem is the same).
struct TwinCase {
  std::string name;
  std::string varies;
  json model;
  json twin;
  std::string source;
  double rel_tol = 1e-6;
  std::string tol_reason = "associative alpha is unique: the twins agree to the solver's accuracy (gap 1e-8), 1e-6";
  bool slow = false;
};

inline void PrintTo(const TwinCase& c, std::ostream* os) { *os << c.name; }

/// Running-bond wall with every other course 1e6 times heavier (unit weight 18e6 kN/m3).
inline json contrast_wall(int bricks, int courses, double s) {
  json blocks = running_bond_blocks(bricks, courses, s);
  for (auto& b : blocks) {
    const std::string id = b["id"];
    if (id[0] == 'W' && std::stoi(id.substr(1)) % 2 == 1) b["unit_weight"] = 18e6;
  }
  return blocks;
}

inline std::vector<TwinCase> twin_cases() {
  std::vector<TwinCase> out;
  for (const std::string friction : {"associative", "non_associative"}) {
    for (const bool out_of_plane : {false, true}) {
      Opt o{friction, out_of_plane ? "3d" : "auto"};
      if (out_of_plane) o.seismic = json::array({std::cos(M_PI / 6), std::sin(M_PI / 6), 0.0});
      const std::string t = tag(o) + (out_of_plane ? "_30deg" : "");
      const json twin = model_of(running_bond_blocks(5, 6), o);
      const std::string nonassoc_reason =
          "non-associative: each twin's scheme stops at 1e-6 relative change of alpha; allow 1e-5";
      const double tol = friction == "associative" ? 1e-6 : 1e-5;
      TwinCase mm{"wall_5x6_at_1mm" + t, "wall 5 x 6 bricks drawn at 1/1000 (bricks 0.4 mm), in m",
                  model_of(running_bond_blocks(5, 6, 1e-3), o), twin, "twin: the same wall at 1 m", tol};
      TwinCase km{"wall_5x6_at_1km" + t, "wall 5 x 6 bricks drawn at 1000 x (bricks 400 m), in m",
                  model_of(running_bond_blocks(5, 6, 1e3), o), twin, "twin: the same wall at 1 m", tol};
      Opt f = o;
      f.length_unit = "mm";
      f.force_unit = "N";
      f.unit_weight_unit = "N/mm3";
      f.unit_weight = 18e-6;
      TwinCase file{"wall_5x6_in_mm_N" + t, "the wall in a mm / N / N/mm3 file", model_of(running_bond_blocks(5, 6, 1e3), f),
                    twin, "twin: the same wall in m / kN", tol};
      Opt heavy = o;
      heavy.unit_weight = 18e6;
      TwinCase w{"wall_5x6_weights_x1e6" + t, "every unit weight x 1e6", model_of(running_bond_blocks(5, 6), heavy), twin,
                 "twin: unit weight 18 kN/m3", tol};
      for (TwinCase* c : {&mm, &km, &file, &w}) {
        if (friction != "associative") c->tol_reason = nonassoc_reason;
        out.push_back(*c);
      }
    }
  }
  // Weight contrasts past 1e12 (issue 19), against the limit of a weightless light part (alpha
  // depends continuously on the weights: 1e-12 of a weight moves it by about that much). These
  // twins are not scale changes: they guard the per-block scaling of the conic problem
  // (analysis/force_scales.hpp) where one light block carries its heavy neighbours' thrust.
  for (const std::string formulation : {"auto", "3d"}) {
    Opt o{"associative", formulation};
    const std::string t = formulation == "3d" ? "_3d" : "";
    // The arch sample's shape (16 voussoirs, R 5 m, t 0.8 m): V7, at the crown, 1e12 lighter.
    ArchSpec spec;
    spec.voussoirs = 16;
    spec.radius = 5.0;
    spec.thickness = 0.8;
    spec.depth = 1.0;
    json arch = arch_blocks(spec);
    json weightless = arch;
    arch[7]["unit_weight"] = 18e-12;
    weightless[7]["unit_weight"] = 0.0;
    out.push_back({"arch_crown_voussoir_1e12_lighter" + t, "voussoir V7 (crown) 1e12 lighter than the others",
                   model_of(arch, o), model_of(weightless, o), "limit: the same arch with V7 weightless"});
    // Running bond, 6 x 8 bricks, odd courses 1e12 lighter (1e-12 against 1 kN/m3).
    Opt w = o;
    w.unit_weight = 1.0;
    if (formulation == "3d") w.seismic = json::array({0.0, 1.0, 0.0});
    json wall = running_bond_blocks(6, 8), bare = wall;
    for (std::size_t i = 0; i < wall.size(); ++i) {
      const std::string id = wall[i]["id"];
      if (id[0] == 'W' && std::stoi(id.substr(1)) % 2 == 1) {
        wall[i]["unit_weight"] = 1e-12;
        bare[i]["unit_weight"] = 0.0;
      }
    }
    out.push_back({"wall_6x8_courses_1e12_lighter" + t + (formulation == "3d" ? "_out_of_plane" : ""),
                   "odd courses 1e12 lighter than even ones", model_of(wall, w), model_of(bare, w),
                   "limit: the same wall with the odd courses weightless"});
  }
  {
    // A 20 x 20 wall with 1e6 contrast between courses, at 1 km, out of plane (3-D): twin at 1 m.
    Opt o{"associative", "3d"};
    o.seismic = json::array({std::cos(M_PI / 6), std::sin(M_PI / 6), 0.0});
    TwinCase c{"wall_20x20_contrast_1e6_at_1km_3d", "410 blocks, courses 1e6 apart in weight, drawn at 1 km",
               model_of(contrast_wall(20, 20, 1e3), o), model_of(contrast_wall(20, 20, 1.0), o),
               "twin: the same wall at 1 m"};
    c.slow = true;
    out.push_back(c);
    Opt p{"associative"};
    TwinCase q{"wall_20x20_contrast_1e6_at_1mm", "410 blocks, courses 1e6 apart in weight, drawn at 1/1000",
               model_of(contrast_wall(20, 20, 1e-3), p), model_of(contrast_wall(20, 20, 1.0), p),
               "twin: the same wall at 1 m"};
    q.slow = true;
    out.push_back(q);
  }
  return out;
}

}  // namespace rbla::stiff
