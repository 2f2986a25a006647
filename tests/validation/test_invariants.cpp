// Invariants every correct limit analysis must satisfy, whatever the model: static = kinematic
// (work balance), global equilibrium, the non-associative value below the associative one,
// planar = 3-D on extruded scenes, unit invariance, pyramid bracketing and the axis-aligned
// pyramid oracle, and the verdicts for locked and unsupported blocks.
#include "support/arch_builder.hpp"
#include "support/vault_builder.hpp"
#include "validation_helpers.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iomanip>
#include <iostream>
#include <numeric>
#include <random>
#include <string>
#include <vector>

namespace rbla::validation {
namespace {


double total_free_weight(const json& model) {
  const auto loaded = rbla::io::load_model_text(model.dump());
  double w = 0.0;
  for (const auto& b : loaded.model.blocks) {
    if (!b.is_support()) w += b.weight();
  }
  return w;
}

/// Every model the invariants run on, with a name.
struct Named {
  std::string name;
  json model;
};

std::vector<Named> invariant_models() {
  std::vector<Named> out;
  Case s;
  out.push_back({"block rocking", single_block(1.0, 2.0, s)});
  out.push_back({"block sliding", single_block(2.0, 1.0, s)});
  {
    Case s3 = s;
    s3.formulation = "3d";
    out.push_back({"block rocking 3d", single_block(1.0, 2.0, s3)});
    out.push_back({"block sliding 3d", single_block(2.0, 1.0, s3)});
    out.push_back({"column 3d", column(4, 1.0, 4.0, s3)});
  }
  out.push_back({"column", column(4, 1.0, 4.0, s)});
  out.push_back({"running-bond wall", finish(running_bond_blocks(5, 6), s)});
  {
    Case sd = s;
    sd.seismic_direction = json::array({std::cos(M_PI / 6), std::sin(M_PI / 6), 0.0});
    out.push_back({"running-bond wall 30 deg", finish(running_bond_blocks(5, 6), sd)});
  }
  {
    Case sl = s;
    sl.mu = 0.3;
    out.push_back({"squat running-bond wall mu 0.3", finish(running_bond_blocks(6, 3), sl)});
  }
  {
    ArchSpec spec;
    spec.voussoirs = 20;
    spec.thickness = 0.15;
    json arch = arch_model(spec, 5.0);
    arch["analysis"] = analysis_of(Case{});
    arch["defaults"]["friction"] = 5.0;
    out.push_back({"arch", arch});
  }
  {
    json blocks = json::array({box_block("fixed", -0.5, -0.5, -0.5, 1.0, 1.5, 0.0, "fixed"),
                               box_block("moving", 1.001, -0.5, -0.5, 4.5, 1.5, 0.0, "moving_support"),
                               box_block("B", 0.0, 0.0, 0.0, 4.0, 1.0, 1.0)});
    json model = model_with(blocks);
    model["defaults"] = {{"unit_weight", 18.0}, {"friction", 0.6}};
    model["analysis"] = {{"type", "settlement"}, {"non_associative", {{"max_iterations", 200}, {"tolerance", 1e-6}}}};
    out.push_back({"settlement", model});
  }
  out.push_back({"drawer", drawer("associative", 0.6)});
  return out;
}

json with_friction_model(json model, const std::string& friction) {
  model["analysis"]["friction_model"] = friction;
  return model;
}

double value_of(const AnalysisResult& r) {
  if (r.base_reaction) return *r.base_reaction;
  return r.load_multiplier.value_or(std::nan(""));
}

// Static multiplier = kinematic work balance (alpha live + dead = dissipation) and every free
// block in equilibrium, for both friction models, on every model above.
TEST(Invariants, WorkBalanceAndEquilibrium) {
  for (const auto& [name, model] : invariant_models()) {
    const double weight = total_free_weight(model);
    for (const std::string friction : {"associative", "non_associative"}) {
      SCOPED_TRACE(name + " " + friction);
      const auto r = run(with_friction_model(model, friction));
      ASSERT_EQ(r.verdict, Verdict::Collapse) << r.verdict_text;
      EXPECT_LT(r.work.relative_error, 1e-6) << "static " << value_of(r) << " kinematic " << r.work.kinematic_value;
      EXPECT_LT(r.accuracy.equilibrium_residual, 1e-7 * weight) << "total free weight " << weight << " kN";
      if (friction == "non_associative") {
        EXPECT_TRUE(r.non_associative_converged) << r.non_associative.size() << " steps";
      }
    }
  }
}

// The associative value is the largest load any Coulomb-admissible stress state carries; the
// non-associative scheme ends on one such state, so alpha_na <= alpha_assoc. (For settlement
// the roles swap: the base reaction is minimised, so R_na >= R_assoc.) Where friction does not
// govern the two are equal in theory; each is solved to a relative gap of 1e-8, but the scheme's
// last radii come from looser steps, so equality is only checked to 1e-6 (the closed-form tolerance).
TEST(Invariants, NonAssociativeBelowAssociative) {
  for (const auto& [name, model] : invariant_models()) {
    SCOPED_TRACE(name);
    const auto a = run(with_friction_model(model, "associative"));
    const auto n = run(with_friction_model(model, "non_associative"));
    ASSERT_EQ(a.verdict, Verdict::Collapse);
    ASSERT_EQ(n.verdict, Verdict::Collapse);
    if (a.base_reaction) {
      EXPECT_GE(value_of(n), value_of(a) * (1.0 - 1e-6));
    } else {
      EXPECT_LE(value_of(n), value_of(a) * (1.0 + 1e-6));
    }
    std::cout << std::setprecision(12) << "[ na/assoc ] " << name << ": " << value_of(n) << " / " << value_of(a) << "\n";
  }
}

// Where dilatancy matters: the drawer (see `drawer`). M slides along +x under T; T cannot go +x
// (the stop). Associative: M's top joint must open by mu times its slip, so T rises, and rising
// along the stop it must open from it by mu times that rise, which it does by moving -x, which
// increases the slip under it. Virtual work (M: u = s, w = mu s; T: u_T <= 0, w_T):
//   w_T >= mu s + mu (s - u_T),  -u_T >= mu w_T   =>   w_T >= 2 mu s / (1 - mu^2)  (mu < 1),
//   P s = W_M mu s + W_T w_T   =>   P_assoc <= mu W_M + 2 mu W_T / (1 - mu^2).
// A static state reaches it: the stop's friction pushes T down by mu H, H = mu N_MT, so
// N_MT = W_T / (1 - mu^2), and P = mu N_base + mu N_MT = mu W_M + 2 mu N_MT (moments of T
// check for a stop resultant anywhere on T's side and the base resultant inside T's base).
// So P_assoc = mu W_M + 2 mu W_T / (1 - mu^2) exactly.
// Non-associative: M slides with no dilatancy, T does not move; T's vertical balance
// N_MT + V = W_T with |V| <= mu H = mu^2 N_MT, so N_MT in [W_T/(1+mu^2), W_T/(1-mu^2)] and
// P_na = mu W_M + 2 mu N_MT is in [mu W_M + 2 mu W_T/(1+mu^2), P_assoc]. Without dilatancy
// nothing pushes T up the stop: the natural state is V = 0, P = mu (W_M + 2 W_T), well below.
TEST(Invariants, NonAssociativeStrictlyBelowWhenDilatancyMatters) {
  const double mu = 0.6, gamma = 18.0;
  const double WM = gamma * 2.0 * 1.0 * 0.5, WT = gamma * 1.0;
  const double p_assoc = mu * WM + 2.0 * mu * WT / (1.0 - mu * mu);
  const double p_na_low = mu * WM + 2.0 * mu * WT / (1.0 + mu * mu);
  const auto a = run(drawer("associative", mu));
  const auto n = run(drawer("non_associative", mu));
  const double pa = alpha_of(a), pn = alpha_of(n);
  std::cout << "[ drawer   ] associative " << pa << " (closed form " << p_assoc << "), non-associative " << pn
            << " (range " << p_na_low << " .. " << p_assoc << ", natural " << mu * (WM + 2 * WT) << ")\n";
  EXPECT_LT(relative_error(pa, p_assoc), 1e-6);
  EXPECT_GE(pn, p_na_low * (1.0 - 1e-6));
  EXPECT_LT(pn, 0.95 * pa) << "no dilatancy should lower the drawer's pull-out force";
  EXPECT_TRUE(n.non_associative_converged);
}

// Planar (3 rows per block, an LP) and 3-D (6 rows, cones) agree on extruded scenes: exactly
// (1e-6) for associative friction, where alpha is unique. The non-associative value is not unique
// (the normal forces that set the cylinder radii are not): the planar scheme carries one radius
// per pair of coincident corners, the 3-D one a radius per corner, so the two iterations may end
// on different admissible states; there only 1e-3 agreement is required.
TEST(Invariants, PlanarEquals3d) {
  std::vector<Named> models;
  models.push_back({"running-bond wall", finish(running_bond_blocks(5, 6), Case{})});
  models.push_back({"column", column(3, 1.0, 2.0, Case{})});
  {
    ArchSpec spec;
    spec.voussoirs = 20;
    spec.thickness = 0.15;
    models.push_back({"arch", arch_model(spec, 5.0)});
    spec.thickness = 0.12;
    json low = arch_model(spec, 0.4);
    models.push_back({"arch mu 0.4", low});
  }
  {
    json blocks = json::array({box_block("fixed", -0.5, -0.5, -0.5, 1.0, 1.5, 0.0, "fixed"),
                               box_block("moving", 1.001, -0.5, -0.5, 4.5, 1.5, 0.0, "moving_support"),
                               box_block("B", 0.0, 0.0, 0.0, 4.0, 1.0, 1.0)});
    json model = model_with(blocks);
    model["analysis"] = {{"type", "settlement"}};
    models.push_back({"settlement", model});
  }
  for (const auto& [name, model] : models) {
    for (const std::string friction : {"associative", "non_associative"}) {
      SCOPED_TRACE(name + " " + friction);
      json planar = with_friction_model(model, friction), three = planar;
      planar["analysis"]["formulation"] = "planar";
      three["analysis"]["formulation"] = "3d";
      planar["analysis"]["non_associative"] = three["analysis"]["non_associative"] =
          json{{"max_iterations", 200}, {"tolerance", 1e-6}};
      const auto p = run(planar), t = run(three);
      ASSERT_EQ(p.verdict, Verdict::Collapse) << p.verdict_text;
      ASSERT_EQ(t.verdict, Verdict::Collapse) << t.verdict_text;
      EXPECT_TRUE(p.planar);
      EXPECT_FALSE(t.planar);
      EXPECT_LT(relative_error(value_of(p), value_of(t)), friction == "associative" ? 1e-6 : 1e-3)
          << value_of(p) << " vs " << value_of(t);
    }
  }
}

// The same wall in m / kN / kN/m3 and in mm / N / N/mm3 (18 kN/m3 = 1.8e-5 N/mm3): same alpha.
// And a settlement in mm / N gives the same base reaction (reported in kN internally).
TEST(Invariants, UnitInvariance) {
  for (const std::string friction : {"associative", "non_associative"}) {
    for (const bool out_of_plane : {false, true}) {
      SCOPED_TRACE(friction + (out_of_plane ? " 3-D" : " planar"));
      Case s;
      s.friction_model = friction;
      if (out_of_plane) s.seismic_direction = json::array({std::cos(M_PI / 6), std::sin(M_PI / 6), 0.0});
      json m = finish(running_bond_blocks(4, 4), s);
      // The non-associative scheme stops once its state no longer dilates (to its tolerance); two
      // runs that differ only by rounding take the same steps and report the same state.
      if (friction == "non_associative")
        m["analysis"]["non_associative"] = json{{"max_iterations", 200}, {"tolerance", 1e-6}};
      json mm = scaled(m, 1000.0);
      mm["units"] = {{"length", "mm"}, {"force", "N"}, {"unit_weight", "N/mm3"}};
      mm["defaults"]["unit_weight"] = 18.0e3 / 1.0e9;
      const auto a = run(m), b = run(mm);
      EXPECT_LT(relative_error(alpha_of(b), alpha_of(a)), 1e-7) << alpha_of(a) << " vs " << alpha_of(b);
    }
  }
  json blocks = json::array({box_block("fixed", -0.5, -0.5, -0.5, 1.0, 1.5, 0.0, "fixed"),
                             box_block("moving", 1.001, -0.5, -0.5, 4.5, 1.5, 0.0, "moving_support"),
                             box_block("B", 0.0, 0.0, 0.0, 4.0, 1.0, 1.0)});
  json m = model_with(blocks);
  m["analysis"] = {{"type", "settlement"}};
  json mm = scaled(m, 1000.0);
  mm["units"] = {{"length", "mm"}, {"force", "N"}, {"unit_weight", "N/mm3"}};
  mm["defaults"] = {{"unit_weight", 18.0e3 / 1.0e9}};
  const auto a = run(m), b = run(mm);
  ASSERT_TRUE(a.base_reaction && b.base_reaction);
  EXPECT_LT(relative_error(*b.base_reaction, *a.base_reaction), 1e-7) << *a.base_reaction << " vs " << *b.base_reaction;
  ASSERT_TRUE(a.initial_base_reaction && b.initial_base_reaction);
  EXPECT_LT(relative_error(*b.initial_base_reaction, *a.initial_base_reaction), 1e-9)
      << *a.initial_base_reaction << " vs " << *b.initial_base_reaction;
}

// Pyramids: an inscribed pyramid is a subset of the cone (safe), a circumscribed one a superset,
// so alpha_in <= alpha_exact <= alpha_out, for m = 4, 8, 16 with a 3-D load (30 deg to the wall).
// And the exact check of docs/method.md ("An exact check for in-plane loads"): for an in-plane
// load on a wall symmetric about its mid-plane an optimum has no out-of-plane friction, and the
// axis-aligned 4-sided inscribed pyramid (|T1| + |T2| <= mu N, whose edges lie on the in-plane
// axis) keeps the full in-plane capacity mu N: it gives the exact cone's alpha.
TEST(Invariants, PyramidsBracketTheCone) {
  Case s;
  s.formulation = "3d";
  s.seismic_direction = json::array({std::cos(M_PI / 6), std::sin(M_PI / 6), 0.0});
  const json wall = finish(running_bond_blocks(4, 4), s);
  const double exact = alpha_of(run(wall));
  for (const int m : {4, 8, 16}) {
    SCOPED_TRACE("m=" + std::to_string(m));
    json in = wall, out = wall;
    in["analysis"]["cone"] = "pyramid_inscribed";
    out["analysis"]["cone"] = "pyramid_circumscribed";
    in["analysis"]["pyramid_faces"] = out["analysis"]["pyramid_faces"] = m;
    const double a_in = alpha_of(run(in)), a_out = alpha_of(run(out));
    std::cout << "[ pyramid  ] m = " << m << ": " << a_in << " <= " << exact << " <= " << a_out << "\n";
    // analysis.pyramid_bracket reports both from one run, whichever pyramid was asked for.
    for (json asked : {in, out}) {
      asked["analysis"]["pyramid_bracket"] = true;
      const AnalysisResult r = run(asked);
      ASSERT_TRUE(r.accuracy.pyramid_bracket.has_value());
      EXPECT_LT(relative_error(r.accuracy.pyramid_bracket->first, a_in), 1e-7);
      EXPECT_LT(relative_error(r.accuracy.pyramid_bracket->second, a_out), 1e-7);
    }
    EXPECT_LE(a_in, exact * (1.0 + 1e-7));
    EXPECT_GE(a_out, exact * (1.0 - 1e-7));
    // The cone lies between the pyramid and its 1/cos(pi/m) enlargement, so alpha for a
    // friction-governed case is within that factor; a loose sanity bracket.
    EXPECT_GE(a_in, exact * std::cos(M_PI / m) * (1.0 - 1e-7));
  }

  // The m = 4 inscribed pyramid on this wall: the 30-degree load overturns the wall out of its
  // plane at alpha sin 30 = d / H = 0.25 unless the base slides first; the diamond
  // |T1| + |T2| <= mu N carries alpha W (cos 30 + sin 30) <= mu W: alpha = mu / (cos 30 + sin 30).
  {
    json in = wall;
    in["analysis"]["cone"] = "pyramid_inscribed";
    in["analysis"]["pyramid_faces"] = 4;
    const double expected = 0.6 / (std::cos(M_PI / 6) + std::sin(M_PI / 6));
    EXPECT_LT(relative_error(alpha_of(run(in)), expected), 1e-6);
  }

  for (const auto& [name, blocks] : std::vector<std::pair<std::string, json>>{
           {"running-bond wall", running_bond_blocks(5, 6)}, {"squat wall", running_bond_blocks(6, 3)}}) {
    SCOPED_TRACE(name);
    Case in_plane;
    in_plane.formulation = "3d";
    in_plane.mu = 0.3;  // friction matters in the squat wall
    json exact_model = finish(blocks, in_plane), pyramid = exact_model;
    pyramid["analysis"]["cone"] = "pyramid_inscribed";
    pyramid["analysis"]["pyramid_faces"] = 4;
    const double a_exact = alpha_of(run(exact_model)), a_pyr = alpha_of(run(pyramid));
    EXPECT_LT(relative_error(a_pyr, a_exact), 1e-6) << a_pyr << " vs " << a_exact;
  }
}

// Closed forms for the pyramids: a squat block (2 x 2 x 1, so it slides before it rocks) on a
// base, seismic at phi = 30 deg to x. The bed joint's frame has t1 = x, so the pyramid's edges are
// at 2 pi j / m and its faces' mid-directions at (2 j + 1) pi / m; let delta be the angle from phi
// to the nearest face mid-direction. The inscribed polygon (vertices on the circle of radius mu N)
// reaches mu N cos(pi/m) / cos(delta) along phi; the circumscribed one (faces tangent to it)
// mu N / cos(delta). Exact cone: mu. m = 4: delta 15 deg; m = 8: 7.5 deg; m = 16: 3.75 deg.
TEST(Invariants, PyramidClosedFormsSlidingBlock) {
  const double mu = 0.6, phi = M_PI / 6;
  Case s;
  s.mu = mu;
  s.formulation = "3d";
  s.seismic_direction = json::array({std::cos(phi), std::sin(phi), 0.0});
  json blocks = json::array({box_block("base", -1.0, -1.0, -0.5, 3.0, 3.0, 0.0, "fixed"),
                             box_block("B", 0.0, 0.0, 0.0, 2.0, 2.0, 1.0)});
  const json model = finish(blocks, s);
  EXPECT_LT(relative_error(alpha_of(run(model)), mu), 1e-6);
  for (const int m : {4, 8, 16}) {
    SCOPED_TRACE("m=" + std::to_string(m));
    double delta = M_PI;
    for (int j = 0; j < m; ++j) delta = std::min(delta, std::abs(phi - (2 * j + 1) * M_PI / m));
    json in = model, out = model;
    in["analysis"]["cone"] = "pyramid_inscribed";
    out["analysis"]["cone"] = "pyramid_circumscribed";
    in["analysis"]["pyramid_faces"] = out["analysis"]["pyramid_faces"] = m;
    const double a_in = alpha_of(run(in)), a_out = alpha_of(run(out));
    EXPECT_LT(relative_error(a_in, mu * std::cos(M_PI / m) / std::cos(delta)), 1e-6) << a_in;
    EXPECT_LT(relative_error(a_out, mu / std::cos(delta)), 1e-6) << a_out;
  }
}

// A block sitting in a pit whose fixed walls touch all four sides: no admissible motion (it
// cannot slide up the walls without opening from them, and cannot rotate without penetrating
// one), so the seismic load can grow without bound.
TEST(Invariants, LockedBlockHasNoMechanism) {
  for (const std::string formulation : {"auto", "3d"}) {
    SCOPED_TRACE(formulation);
    json blocks = json::array({box_block("floor", -1.0, -1.0, -0.5, 2.0, 2.0, 0.0, "fixed"),
                               box_block("west", -1.0, -1.0, 0.0, 0.0, 2.0, 1.0, "fixed"),
                               box_block("east", 1.0, -1.0, 0.0, 2.0, 2.0, 1.0, "fixed"),
                               box_block("south", 0.0, -1.0, 0.0, 1.0, 0.0, 1.0, "fixed"),
                               box_block("north", 0.0, 1.0, 0.0, 1.0, 2.0, 1.0, "fixed"),
                               box_block("B", 0.0, 0.0, 0.0, 1.0, 1.0, 1.0)});
    Case s;
    s.formulation = formulation;
    const auto r = run(finish(blocks, s));
    EXPECT_EQ(r.verdict, Verdict::NoMechanism) << r.verdict_text;
    EXPECT_FALSE(r.load_multiplier.has_value());
  }
}

// A block floating 0.1 m above its neighbours (no contact) cannot stand: it falls, and the
// certificate marks it as moving. A block resting on the base next to it does not change that.
TEST(Invariants, FloatingBlockCannotStand) {
  for (const std::string formulation : {"auto", "3d"}) {
    SCOPED_TRACE(formulation);
    json blocks = json::array({box_block("base", -0.5, -0.5, -0.5, 3.5, 1.5, 0.0, "fixed"),
                               box_block("resting", 0.0, 0.0, 0.0, 1.0, 1.0, 1.0),
                               box_block("floating", 2.0, 0.0, 0.1, 3.0, 1.0, 1.1)});
    Case s;
    s.formulation = formulation;
    const auto r = run(finish(blocks, s));
    EXPECT_EQ(r.verdict, Verdict::CannotStand) << r.verdict_text;
    ASSERT_EQ(r.mechanism.blocks.size(), 3u);
    EXPECT_TRUE(r.mechanism.blocks[2].moving);
    EXPECT_FALSE(r.mechanism.blocks[0].moving);
    // It falls along gravity.
    EXPECT_LT(r.mechanism.blocks[2].translation.z(), 0.0);
  }
}

// Listing the blocks the other way round changes nothing, also on imperfect geometry: a vault
// whose vertices moved by up to 3 mm gets the same contact points and alpha. Interface detection
// snapped the two faces' outlines in the order the blocks were listed, and its contact points
// moved by up to 1.4 mm and alpha by 5e-5 (the search review); the larger face now goes first.
TEST(Invariants, BlockOrderDoesNotMatterOnImperfectGeometry) {
  rbla::testing::VaultSpec spec;
  spec.units = 3;
  spec.noise = 3e-3;
  const json forward = rbla::testing::vault_model(spec);
  json backward = forward;
  std::reverse(backward["blocks"].begin(), backward["blocks"].end());
  const AnalysisResult a = run(forward), b = run(backward);
  ASSERT_EQ(a.verdict, Verdict::Collapse) << a.verdict_text;
  ASSERT_EQ(b.verdict, Verdict::Collapse) << b.verdict_text;
  EXPECT_LT(relative_error(*b.load_multiplier, *a.load_multiplier), 1e-7)
      << *a.load_multiplier << " listed forwards, " << *b.load_multiplier << " backwards";
}

// How a CAD tool numbers a block's vertices, orders its faces and picks each face's first corner
// is arbitrary, and so is whether it splits a planar quad into two triangles: none of it may
// change the answer. (Splitting a warped quad does change the surface: two triangles are one of
// the two ways to read four corners that are not coplanar. On this vault α moves by about 0.07
// times the corners' noise in metres: 8e-6 at 0.1 mm, 2e-4 at 3 mm.)
json renumbered(json block, unsigned seed, bool split) {
  std::mt19937 random(seed);
  const std::size_t n = block["vertices"].size();
  std::vector<std::size_t> to(n);
  std::iota(to.begin(), to.end(), std::size_t{0});
  std::shuffle(to.begin(), to.end(), random);
  json vertices = json::array();
  for (std::size_t i = 0; i < n; ++i) vertices.push_back(nullptr);
  for (std::size_t i = 0; i < n; ++i) vertices[to[i]] = block["vertices"][i];
  json faces = json::array();
  for (const json& face : block["faces"]) {
    std::vector<std::size_t> f;
    for (const json& v : face) f.push_back(to[v.get<std::size_t>()]);
    std::rotate(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(random() % f.size()), f.end());
    if (!split || random() % 2 == 0) {
      faces.push_back(f);
      continue;
    }
    for (std::size_t k = 1; k + 1 < f.size(); ++k) faces.push_back({f[0], f[k], f[k + 1]});
  }
  std::reverse(faces.begin(), faces.end());
  block["vertices"] = vertices;
  block["faces"] = faces;
  return block;
}

void expect_same_answer_renumbered(double noise, bool split) {
  rbla::testing::VaultSpec spec;
  spec.units = 3;
  spec.noise = noise;
  const json original = rbla::testing::vault_model(spec);
  json changed = original;
  unsigned seed = 1;
  for (json& block : changed["blocks"]) block = renumbered(block, seed++, split);
  const auto loaded_a = rbla::io::load_model_text(original.dump());
  const auto loaded_b = rbla::io::load_model_text(changed.dump());
  EXPECT_EQ(loaded_a.model.interfaces.size(), loaded_b.model.interfaces.size());
  EXPECT_EQ(loaded_a.model.num_contact_points(), loaded_b.model.num_contact_points());
  const AnalysisResult a = rbla::analysis::analyse(loaded_a.model);
  const AnalysisResult b = rbla::analysis::analyse(loaded_b.model);
  ASSERT_EQ(a.verdict, Verdict::Collapse) << a.verdict_text;
  ASSERT_EQ(b.verdict, Verdict::Collapse) << b.verdict_text;
  EXPECT_LT(relative_error(*b.load_multiplier, *a.load_multiplier), 1e-7)
      << *a.load_multiplier << " as built, " << *b.load_multiplier << " renumbered";
}

TEST(Invariants, VertexNumberingAndFaceOrderDoNotMatterOnImperfectGeometry) {
  expect_same_answer_renumbered(3e-3, false);
}

TEST(Invariants, PlanarFacesSplitIntoTrianglesDoNotMatter) {
  expect_same_answer_renumbered(0.0, true);
}

}  // namespace
}  // namespace rbla::validation
