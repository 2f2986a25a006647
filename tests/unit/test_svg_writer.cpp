// The SVG pictures: well-formed XML, the right title, the rigid motion drawn where a hand
// computation puts it, up on the page, auto view axis, escaping, convergence series.
#include "io/svg_writer.hpp"
#include "io/critical_friction_json.hpp"
#include "io/worst_direction_json.hpp"
#include "io/worst_settlement_json.hpp"
#include "io/load_model.hpp"
#include "support/model_builder.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace rbla::testing;
using rbla::analysis::AnalysisResult;
using rbla::analysis::InterfaceState;
using rbla::analysis::Verdict;
using rbla::io::SvgOptions;
using rbla::model::Model;
using rbla::model::Vec3;

namespace {

/// Enough of XML for these pictures: one root element, balanced and properly nested tags, quoted
/// attributes, no raw '<' or bare '&' in text or attribute values. Returns "" when well formed.
std::string xml_problem(const std::string& text) {
  std::vector<std::string> open;
  int roots = 0;
  std::size_t i = 0;
  auto check_entities = [&](std::size_t from, std::size_t to) -> std::string {
    for (std::size_t k = from; k < to; ++k) {
      if (text[k] == '<') return "raw '<' at " + std::to_string(k);
      if (text[k] != '&') continue;
      const std::size_t semi = text.find(';', k);
      if (semi == std::string::npos || semi > to) return "bare '&' at " + std::to_string(k);
      const std::string entity = text.substr(k + 1, semi - k - 1);
      if (entity != "amp" && entity != "lt" && entity != "gt" && entity != "quot" && entity != "apos" &&
          (entity.empty() || entity[0] != '#')) {
        return "unknown entity &" + entity + ";";
      }
    }
    return "";
  };
  while (i < text.size()) {
    const std::size_t lt = text.find('<', i);
    const std::size_t text_end = lt == std::string::npos ? text.size() : lt;
    if (std::string p = check_entities(i, text_end); !p.empty()) return p;
    if (lt == std::string::npos) break;
    if (text.compare(lt, 2, "<?") == 0) {
      const std::size_t end = text.find("?>", lt);
      if (end == std::string::npos) return "unterminated <?";
      i = end + 2;
      continue;
    }
    if (text.compare(lt, 4, "<!--") == 0) {
      const std::size_t end = text.find("-->", lt);
      if (end == std::string::npos) return "unterminated comment";
      i = end + 3;
      continue;
    }
    const bool closing = text.compare(lt, 2, "</") == 0;
    std::size_t k = lt + (closing ? 2 : 1);
    const std::size_t name_start = k;
    while (k < text.size() && (std::isalnum(static_cast<unsigned char>(text[k])) || text[k] == '-' ||
                               text[k] == ':' || text[k] == '_')) {
      ++k;
    }
    const std::string name = text.substr(name_start, k - name_start);
    if (name.empty()) return "empty tag name at " + std::to_string(lt);
    // Attributes: name="value" pairs up to '>' or '/>'.
    bool self_closing = false;
    for (;;) {
      while (k < text.size() && std::isspace(static_cast<unsigned char>(text[k]))) ++k;
      if (k >= text.size()) return "unterminated tag " + name;
      if (text[k] == '>') {
        ++k;
        break;
      }
      if (text.compare(k, 2, "/>") == 0 && !closing) {
        self_closing = true;
        k += 2;
        break;
      }
      if (closing) return "junk in closing tag " + name;
      const std::size_t eq = text.find('=', k);
      if (eq == std::string::npos || eq + 1 >= text.size() || (text[eq + 1] != '"' && text[eq + 1] != '\'')) {
        return "unquoted attribute in " + name;
      }
      const std::size_t end = text.find(text[eq + 1], eq + 2);
      if (end == std::string::npos) return "unterminated attribute in " + name;
      if (std::string p = check_entities(eq + 2, end); !p.empty()) return p;
      k = end + 1;
    }
    if (closing) {
      if (open.empty() || open.back() != name) return "mismatched </" + name + ">";
      open.pop_back();
    } else {
      if (open.empty()) ++roots;
      if (!self_closing) open.push_back(name);
    }
    i = k;
  }
  if (!open.empty()) return "unclosed <" + open.back() + ">";
  if (roots != 1) return "expected one root element, found " + std::to_string(roots);
  return "";
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

// The writer prints page coordinates to 0.1 px without a trailing ".0".
std::string page_number(double value) {
  char buffer[32];
  double r = std::round(value * 10.0) / 10.0;
  if (r == 0.0) r = 0.0;
  int n = std::snprintf(buffer, sizeof buffer, "%.1f", r);
  if (n >= 2 && buffer[n - 1] == '0' && buffer[n - 2] == '.') n -= 2;
  return std::string(buffer, static_cast<std::size_t>(n));
}

/// Whether "x,y" appears for a page point, allowing one unit of the last digit either way so a
/// value at a rounding boundary cannot make the test flaky.
bool contains_point(const std::string& svg, double x, double y) {
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      if (svg.find(page_number(x + 0.1 * dx) + "," + page_number(y + 0.1 * dy)) != std::string::npos) return true;
    }
  }
  return false;
}

const char* kTopId = "top<1>&\"x";

/// A 1 x 1 x 2 pier on a wider fixed base; the pier's id needs escaping.
Model pier_model() {
  json blocks = json::array({box_block("base", -1, 0, -0.5, 2, 1, 0, "fixed"), box_block(kTopId, 0, 0, 0, 1, 1, 2)});
  return rbla::io::load_model_text(model_with(blocks).dump()).model;
}

// Rocking of the pier about its base edge x = 1, z = 0 (a line along y), toward +x, with
// rotation 0.5 about +y: the centroid moves theta x (g - c) = (0.5, 0, 0.25).
const Vec3 kTheta(0.0, 0.5, 0.0);
const Vec3 kTranslation(0.5, 0.0, 0.25);

AnalysisResult rocking_result(const Model& model) {
  AnalysisResult result;
  result.verdict = Verdict::Collapse;
  result.type = rbla::model::AnalysisType::LoadMultiplier;
  result.load_multiplier = 0.25;
  result.planar = true;
  result.planar_axis = 1;
  result.mechanism.blocks.resize(model.blocks.size());
  const int top = model.block_index.at(kTopId);
  result.mechanism.blocks[static_cast<std::size_t>(top)].translation = kTranslation;
  result.mechanism.blocks[static_cast<std::size_t>(top)].rotation = kTheta;
  result.mechanism.blocks[static_cast<std::size_t>(top)].moving = true;
  result.mechanism.interfaces.resize(model.interfaces.size());
  if (!model.interfaces.empty()) {
    result.mechanism.interfaces[0].state = InterfaceState::Hinge;
    result.mechanism.interfaces[0].cracked = true;
    result.mechanism.cracked_interfaces.push_back(0);
  }
  return result;
}

}  // namespace

TEST(SvgMechanism, WellFormedWithTitleAndLegend) {
  const Model model = pier_model();
  ASSERT_EQ(model.interfaces.size(), 1u);
  const std::string svg = rbla::io::mechanism_svg(model, rocking_result(model));
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_EQ(count(svg, "<svg"), 1u);
  EXPECT_EQ(count(svg, "</svg>"), 1u);
  EXPECT_NE(svg.find("xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
  EXPECT_NE(svg.find("viewBox=\"0 0 "), std::string::npos);
  EXPECT_NE(svg.find("Collapse mechanism — α = 0.2500"), std::string::npos);
  EXPECT_NE(svg.find("displacements ×"), std::string::npos);
  // The hinge drawn in its colour, and all four state colours in the legend.
  EXPECT_NE(svg.find("stroke=\"#ff7f0e\" fill=\"#ff7f0e\""), std::string::npos);
  for (const char* colour : {"#d62728", "#1f77b4", "#9467bd", "#ff7f0e"}) {
    EXPECT_NE(svg.find(colour), std::string::npos) << colour;
  }
}

TEST(SvgMechanism, DisplacedCornerIsTheExactRigidMotion) {
  const Model model = pier_model();
  const AnalysisResult result = rocking_result(model);
  SvgOptions options;
  options.amplitude = 0.4;
  const rbla::io::SvgView view = rbla::io::mechanism_view(model, result, options);
  EXPECT_EQ(view.view_axis, 1);
  EXPECT_DOUBLE_EQ(view.amplitude, 0.4);
  EXPECT_NEAR((view.right - Vec3::UnitX()).norm(), 0.0, 1e-12);
  EXPECT_NEAR((view.up - Vec3::UnitZ()).norm(), 0.0, 1e-12);

  // Corner (0, 0, 2), on the front face y = 0: turned by s*|theta| about y around the centroid
  // g = (0.5, 0.5, 1), then shifted by s*u. Rotation about +y: x' = x cos + z sin, z' = -x sin + z cos.
  const double s = 0.4, angle = s * 0.5;
  const double rx = -0.5, rz = 1.0;  // corner - centroid in x and z
  const Vec3 expected(0.5 + rx * std::cos(angle) + rz * std::sin(angle) + s * 0.5, 0.0,
                      1.0 - rx * std::sin(angle) + rz * std::cos(angle) + s * 0.25);
  // Page mapping by hand from the frame: x right, z up (SVG y downwards).
  const double px = view.origin_x + view.scale * expected.x();
  const double py = view.origin_y - view.scale * expected.z();
  const std::string svg = rbla::io::mechanism_svg(model, result, options);
  EXPECT_TRUE(contains_point(svg, px, py)) << "expected " << page_number(px) << "," << page_number(py);
  EXPECT_EQ(xml_problem(svg), "");

  // Everything on the page.
  EXPECT_GT(px, 0.0);
  EXPECT_LT(px, view.width);
  EXPECT_GT(py, 0.0);
  EXPECT_LT(py, view.height);
}

TEST(SvgMechanism, UpIsUpOnThePage) {
  const Model model = pier_model();
  SvgOptions options;
  options.amplitude = 0.4;
  const rbla::io::SvgView view = rbla::io::mechanism_view(model, rocking_result(model), options);
  const std::string svg = rbla::io::mechanism_svg(model, rocking_result(model), options);
  // Undisplaced outline corners of the pier's front face, bottom and top.
  const double x = view.origin_x, y_bottom = view.origin_y, y_top = view.origin_y - 2.0 * view.scale;
  EXPECT_LT(y_top, y_bottom);
  EXPECT_TRUE(contains_point(svg, x, y_bottom));
  EXPECT_TRUE(contains_point(svg, x, y_top));
  // The page y of the base's bottom (z = -0.5) is the largest of the drawing.
  EXPECT_NEAR(view.height - 20.0, view.origin_y + 0.5 * view.scale, 1e-9);
}

TEST(SvgMechanism, AutoAmplitudeIsEightPercentOfTheDiagonal) {
  const Model model = pier_model();
  const rbla::io::SvgView view = rbla::io::mechanism_view(model, rocking_result(model));
  // Fastest vertex: a top corner sqrt(1 + 4) from the pivot line, at speed 0.5 * sqrt(5).
  const double diagonal = std::sqrt(3.0 * 3.0 + 1.0 + 2.5 * 2.5);
  EXPECT_NEAR(view.amplitude * 0.5 * std::sqrt(5.0), 0.08 * diagonal, 1e-12);
}

TEST(SvgMechanism, AutoViewAxis) {
  const Model model = pier_model();
  AnalysisResult result = rocking_result(model);
  result.planar = true;
  result.planar_axis = 0;  // whatever the motion, a planar result is seen along its extrusion
  EXPECT_EQ(rbla::io::mechanism_view(model, result).view_axis, 0);

  result.planar = false;
  result.planar_axis = -1;
  EXPECT_EQ(rbla::io::mechanism_view(model, result).view_axis, 1);  // motion in x-z: look along y

  const int top = model.block_index.at(kTopId);
  result.mechanism.blocks[static_cast<std::size_t>(top)].translation = Vec3(0.0, 0.5, 0.25);
  result.mechanism.blocks[static_cast<std::size_t>(top)].rotation = Vec3(-0.5, 0.0, 0.0);
  const rbla::io::SvgView view = rbla::io::mechanism_view(model, result);
  EXPECT_EQ(view.view_axis, 0);  // motion in y-z: look along x
  EXPECT_NEAR((view.up - Vec3::UnitZ()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(view.right.cross(view.up).dot(view.toward), 1.0, 1e-12);

  SvgOptions options;
  options.view_axis = 2;  // a plan, looked at from above
  const rbla::io::SvgView plan = rbla::io::mechanism_view(model, result, options);
  EXPECT_EQ(plan.view_axis, 2);
  EXPECT_NEAR((plan.toward - Vec3::UnitZ()).norm(), 0.0, 1e-12);
}

TEST(SvgMechanism, EscapesBlockIds) {
  const Model model = pier_model();
  const std::string svg = rbla::io::mechanism_svg(model, rocking_result(model));
  EXPECT_EQ(svg.find(kTopId), std::string::npos);
  EXPECT_NE(svg.find("top&lt;1&gt;&amp;&quot;x"), std::string::npos);
  EXPECT_EQ(xml_problem(svg), "");
}

TEST(SvgMechanism, OtherVerdictTitles) {
  Model model = pier_model();
  AnalysisResult result = rocking_result(model);

  result.verdict = Verdict::NoMechanism;
  result.load_multiplier.reset();
  result.mechanism = {};
  std::string svg = rbla::io::mechanism_svg(model, result);
  EXPECT_NE(svg.find("No mechanism: α unbounded"), std::string::npos);
  EXPECT_EQ(rbla::io::mechanism_view(model, result).amplitude, 0.0);
  EXPECT_EQ(svg.find("stroke=\"#b4b4b4\""), std::string::npos);  // no undisplaced outlines
  EXPECT_EQ(xml_problem(svg), "");

  result = rocking_result(model);
  result.verdict = Verdict::CannotStand;
  result.load_multiplier.reset();
  svg = rbla::io::mechanism_svg(model, result);
  EXPECT_NE(svg.find("Cannot stand under dead load — falling blocks highlighted"), std::string::npos);

  model.units.force_name = "MN";
  model.units.force_to_kN = 1000.0;
  result = rocking_result(model);
  result.type = rbla::model::AnalysisType::Settlement;
  result.load_multiplier.reset();
  result.base_reaction = 881750.0;  // kN
  svg = rbla::io::mechanism_svg(model, result);
  EXPECT_NE(svg.find("Collapse under settlement — base reaction R = 881.75 MN"), std::string::npos);
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_EQ(svg.find("not certified"), std::string::npos);

  // A non-associative state that did not pass the fixed-point test is not titled a collapse state.
  result.friction_model = rbla::model::FrictionModel::NonAssociative;
  result.non_associative_converged = false;
  svg = rbla::io::mechanism_svg(model, result);
  EXPECT_NE(svg.find("R = 881.75 MN — non-associative, not certified"), std::string::npos);
  result.non_associative_converged = true;
  EXPECT_EQ(rbla::io::mechanism_svg(model, result).find("not certified"), std::string::npos);
}

TEST(SvgMechanism, MarksAndListsTheMostInfluentialJoints) {
  const Model model = pier_model();
  AnalysisResult result = rocking_result(model);
  const rbla::io::SvgView plain = rbla::io::mechanism_view(model, result);
  EXPECT_EQ(rbla::io::mechanism_svg(model, result).find("Most influential joints"), std::string::npos);

  rbla::analysis::Sensitivities sensitivities;
  sensitivities.interface_friction = {{0, 0.375}};
  result.sensitivities = sensitivities;
  const std::string svg = rbla::io::mechanism_svg(model, result);
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_NE(svg.find("Most influential joints"), std::string::npos);
  EXPECT_NE(svg.find("1  " + model.interfaces[0].id + ": dα/dμ = 0.375"), std::string::npos);
  EXPECT_EQ(count(svg, "<circle"), 1u);
  // The list sits under the drawing: the page grows by a heading and one line.
  EXPECT_GT(rbla::io::mechanism_view(model, result).height, plain.height + 30.0);

  // Under settlement the derivative is a force, in the model's units.
  result.type = rbla::model::AnalysisType::Settlement;
  result.load_multiplier.reset();
  result.base_reaction = 12.0;
  result.sensitivities->quantity = rbla::analysis::SensitivityOf::BaseReaction;
  result.sensitivities->interface_friction = {{0, -2.5}};
  EXPECT_NE(rbla::io::mechanism_svg(model, result).find("dR/dμ = -2.5 kN"), std::string::npos);
}

TEST(SvgMechanism, LargeWallStaysCompact) {
  // 50 x 40 bricks 0.4 x 0.3 x 0.2 m, every one moving: the size a facade sample gives.
  Model model;
  const std::vector<std::vector<int>> faces = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                               {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  AnalysisResult result;
  result.verdict = Verdict::Collapse;
  result.load_multiplier = 0.1;
  for (int row = 0; row < 40; ++row) {
    for (int column = 0; column < 50; ++column) {
      rbla::model::Block block;
      block.id = "B" + std::to_string(row) + "_" + std::to_string(column);
      const double x0 = 0.4 * column + (row % 2) * 0.2, z0 = 0.2 * row;
      const double x1 = x0 + 0.4, y1 = 0.3, z1 = z0 + 0.2;
      block.vertices = {{x0, 0, z0}, {x1, 0, z0}, {x1, y1, z0}, {x0, y1, z0},
                        {x0, 0, z1}, {x1, 0, z1}, {x1, y1, z1}, {x0, y1, z1}};
      block.faces = faces;
      block.centroid = Vec3(0.5 * (x0 + x1), 0.5 * y1, 0.5 * (z0 + z1));
      block.volume = 0.4 * 0.3 * 0.2;
      model.blocks.push_back(block);
      rbla::analysis::BlockMotion motion;
      motion.translation = Vec3(0.01 * row, 0.001 * column, 0.002 * column);
      motion.rotation = Vec3(0.001 * row, 0.05, 0.002 * column);
      motion.moving = true;
      result.mechanism.blocks.push_back(motion);
    }
  }
  const std::string svg = rbla::io::mechanism_svg(model, result);
  EXPECT_LT(svg.size(), 3u * 1000u * 1000u);
  EXPECT_EQ(count(svg, "<svg"), 1u);
  EXPECT_EQ(count(svg, "</svg>"), 1u);
}

namespace {

AnalysisResult result_with_histories(int non_associative_steps, int interior_point_rows) {
  AnalysisResult result;
  result.verdict = Verdict::Collapse;
  result.load_multiplier = 0.21;
  result.friction_model = non_associative_steps > 0 ? rbla::model::FrictionModel::NonAssociative
                                                    : rbla::model::FrictionModel::Associative;
  for (int i = 0; i < non_associative_steps; ++i) {
    rbla::analysis::NonAssociativeStep step;
    step.iteration = i + 1;
    step.value = 0.3 - 0.09 * (1.0 - std::pow(0.5, i));
    result.non_associative.push_back(step);
  }
  result.non_associative_converged = non_associative_steps > 0;
  for (int i = 0; i < interior_point_rows; ++i) {
    rbla::conic::IterationRow row;
    row.iteration = i;
    row.gap_rel = std::pow(10.0, -i);
    row.res_primal = i == interior_point_rows - 1 ? 0.0 : std::pow(10.0, -1.5 * i);  // 0 is clamped
    row.res_dual = 0.5 * std::pow(10.0, -0.8 * i);
    result.interior_point_history.push_back(row);
  }
  return result;
}

}  // namespace

TEST(SvgConvergence, OnePolylinePerSeries) {
  const std::string svg = rbla::io::convergence_svg(result_with_histories(4, 12));
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_EQ(count(svg, "<polyline"), 4u);  // alpha, gap, primal, dual
  EXPECT_EQ(count(svg, "<circle"), 4u);    // one marker per non-associative iteration
  for (const char* label : {"relative gap", "primal residual", "dual residual", "load multiplier α"}) {
    EXPECT_NE(svg.find(label), std::string::npos) << label;
  }
  // Ticks at powers of ten, down to the clamp at 1e-16.
  EXPECT_NE(svg.find(">10⁰<"), std::string::npos);
  EXPECT_NE(svg.find(">10⁻¹⁶<"), std::string::npos);
}

TEST(SvgConvergence, EmptyHistoriesGiveNotes) {
  const std::string svg = rbla::io::convergence_svg(result_with_histories(0, 0));
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_EQ(count(svg, "<polyline"), 0u);
  EXPECT_NE(svg.find("associative: one conic solve"), std::string::npos);
  EXPECT_NE(svg.find("no interior-point iterations recorded"), std::string::npos);

  const std::string ip_only = rbla::io::convergence_svg(result_with_histories(0, 1));
  EXPECT_EQ(xml_problem(ip_only), "");
  EXPECT_EQ(count(ip_only, "<polyline"), 3u);
}

TEST(SvgConvergence, SettlementValuesAreReactions) {
  AnalysisResult result = result_with_histories(3, 5);
  result.type = rbla::model::AnalysisType::Settlement;
  result.load_multiplier.reset();
  result.base_reaction = 800.0;
  const std::string svg = rbla::io::convergence_svg(result);
  EXPECT_NE(svg.find("base reaction R (kN)"), std::string::npos);
  EXPECT_EQ(xml_problem(svg), "");
}

// Found by fuzzing the analysis (tests/fuzz/regressions_analysis/settlement_flat_history.json): a
// non-associative history that settles on one value but for an ulp (36 kN, then 36 kN plus
// 7e-15) made the tick step smaller than the values' spacing, and the tick loop never ended
// (2 GB and counting). Such a history is a flat line with a few ticks.
TEST(SvgConvergence, HistoryFlatButForAnUlpHasFewTicks) {
  AnalysisResult result = result_with_histories(2, 3);
  result.type = rbla::model::AnalysisType::Settlement;
  result.load_multiplier.reset();
  result.base_reaction = 36.0;
  result.non_associative[0].value = 36.0;
  result.non_associative[1].value = std::nextafter(36.0, 37.0);
  const std::string svg = rbla::io::convergence_svg(result);
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_LT(svg.size(), 100000u);
  EXPECT_LE(count(svg, "stroke=\"#e4e4e4\""), 40u);  // grid lines of both panels
}

// The search commands' pictures are well-formed XML with their captions, whatever the values
// (a bound printed with a comparison sign once broke the XML).
TEST(SvgSearches, WellFormedWithTheirCaptions) {
  rbla::analysis::WorstSettlement settlement;
  settlement.cone_angle = 0.5;
  for (int k = 0; k < 4; ++k) {
    rbla::analysis::SettlementEvaluation e;
    e.tilt = k == 0 ? 0.0 : 0.5;
    e.azimuth = 2.0 * k;
    e.verdict = Verdict::Collapse;
    e.base_reaction = 10.0 + k;
    e.initial_reaction = 30.0;
    e.ratio = (10.0 + k) / 30.0;
    settlement.evaluations.push_back(e);
  }
  settlement.worst = 3;
  settlement.ratio = 13.0 / 30.0;
  settlement.upper_bound = 0.44;
  std::string svg = rbla::io::worst_settlement_svg(settlement);
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_NE(svg.find("most harmful: R/R0 = 0.433333"), std::string::npos) << svg;
  settlement.worst.reset();
  settlement.upper_bound.reset();
  EXPECT_EQ(xml_problem(rbla::io::worst_settlement_svg(settlement)), "");

  rbla::analysis::WorstDirection direction;
  direction.evaluations.push_back({0.0, Vec3::UnitX(), Verdict::Collapse, 0.3, 10, 0.1});
  direction.evaluations.push_back({1.0, Vec3::UnitY(), Verdict::Collapse, 0.25, 10, 0.1});
  direction.alpha_min = 0.25;
  direction.angle = 1.0;
  direction.lower_bound = 0.2499;
  svg = rbla::io::worst_direction_svg(direction);
  EXPECT_EQ(xml_problem(svg), "");

  rbla::analysis::CriticalFriction friction;
  friction.target_alpha = 0.3;
  friction.evaluations.push_back({1.0, Verdict::Collapse, 0.45, true, 0.1});
  friction.evaluations.push_back({0.5, Verdict::CannotStand, std::nullopt, false, 0.1});
  friction.factor_upper = 1.0;
  friction.uniform_friction = 0.6;
  EXPECT_EQ(xml_problem(rbla::io::critical_friction_svg(friction)), "");
}
