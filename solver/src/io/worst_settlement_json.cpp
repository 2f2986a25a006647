#include "io/worst_settlement_json.hpp"

#include "io/json_values.hpp"
#include "io/number_text.hpp"

#include <algorithm>
#include <cmath>

namespace rbla::io {
namespace {

using nlohmann::json;

json evaluation_json(const analysis::SettlementEvaluation& e, double force_unit) {
  json out{{"tilt_deg", degrees(e.tilt)},
           {"azimuth_deg", degrees(e.azimuth)},
           {"direction", vec3_json(e.direction)},
           {"status", analysis::to_string(e.verdict)},
           {"initial_base_reaction", e.initial_reaction / force_unit},
           {"interior_point_iterations", e.interior_point_iterations},
           {"seconds", e.seconds}};
  if (e.base_reaction) out["base_reaction"] = *e.base_reaction / force_unit;
  if (e.ratio) out["ratio"] = *e.ratio;
  return out;
}

}  // namespace

json worst_settlement_json(const model::Model& model, const analysis::WorstSettlement& w, double tolerance) {
  const double force_unit = model.units.force_to_kN;
  json evaluations = json::array();
  for (const auto& e : w.evaluations) evaluations.push_back(evaluation_json(e, force_unit));
  json out{{"status", analysis::to_string(w.verdict)},
           {"verdict", w.verdict_text},
           {"certified", w.certified},
           {"tolerance", tolerance},
           {"stop", w.stop},
           {"cone_angle_deg", degrees(w.cone_angle)},
           {"azimuth_zero", vec3_json(w.axis_x)},
           {"azimuth_ninety", vec3_json(w.axis_y)},
           {"initial_reaction_vector", vec3_json(w.initial_reaction_vector / force_unit)},
           {"num_evaluations", static_cast<int>(w.evaluations.size())},
           {"seconds", w.seconds},
           {"evaluations", evaluations}};
  if (w.worst) {
    const analysis::SettlementEvaluation& e = w.evaluations[static_cast<std::size_t>(*w.worst)];
    out["ratio"] = *e.ratio;
    out["direction"] = vec3_json(e.direction);
    out["tilt_deg"] = degrees(e.tilt);
    out["azimuth_deg"] = degrees(e.azimuth);
    out["base_reaction"] = *e.base_reaction / force_unit;
    out["initial_base_reaction"] = e.initial_reaction / force_unit;
  }
  if (w.upper_bound) out["upper_bound"] = *w.upper_bound;
  return out;
}

json candidate_groups_json(const model::Model& model, const analysis::SupportGroupRanking& r) {
  const double force_unit = model.units.force_to_kN;
  json groups = json::array();
  for (std::size_t g = 0; g < r.groups.size(); ++g) {
    const analysis::WorstSettlement& w = r.groups[g].search;
    json ids = json::array();
    for (int b : r.groups[g].blocks) ids.push_back(model.blocks[b].id);
    json group{{"supports", ids},
               {"status", analysis::to_string(w.verdict)},
               {"most_harmful", r.most_harmful && *r.most_harmful == static_cast<int>(g)},
               {"certified", w.certified},
               {"num_evaluations", static_cast<int>(w.evaluations.size())},
               {"seconds", w.seconds}};
    if (w.worst) {
      const analysis::SettlementEvaluation& e = w.evaluations[static_cast<std::size_t>(*w.worst)];
      group["ratio"] = *e.ratio;
      group["tilt_deg"] = degrees(e.tilt);
      group["azimuth_deg"] = degrees(e.azimuth);
      group["base_reaction"] = *e.base_reaction / force_unit;
      group["initial_base_reaction"] = e.initial_reaction / force_unit;
    }
    if (w.upper_bound) group["upper_bound"] = *w.upper_bound;
    groups.push_back(group);
  }
  return json{{"certain", r.certain}, {"verdict", r.verdict_text}, {"seconds", r.seconds}, {"groups", groups}};
}

namespace {

/// Blue (0) to red (1).
std::string ramp(double t) {
  t = std::clamp(t, 0.0, 1.0);
  const int r = static_cast<int>(std::lround(40 + 190 * t)), g = 70, b = static_cast<int>(std::lround(200 - 160 * t));
  return "rgb(" + std::to_string(r) + "," + std::to_string(g) + "," + std::to_string(b) + ")";
}

}  // namespace

std::string worst_settlement_svg(const analysis::WorstSettlement& w) {
  const double size = 600.0, centre = size / 2.0, radius = size / 2.0 - 60.0;
  const double scale = w.cone_angle > 0.0 ? radius / w.cone_angle : 1.0;
  double lo = 1e300, hi = -1e300;
  for (const auto& e : w.evaluations) {
    if (!e.ratio) continue;
    lo = std::min(lo, *e.ratio);
    hi = std::max(hi, *e.ratio);
  }
  auto at = [&](const analysis::SettlementEvaluation& e, double& x, double& y) {
    x = centre + scale * e.tilt * std::cos(e.azimuth);
    y = centre - scale * e.tilt * std::sin(e.azimuth);
  };
  std::string out = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + number_text(size, "%.0f") + "\" height=\"" +
                    number_text(size + 50, "%.0f") + "\" font-family=\"sans-serif\">\n<title>R / R0 over the settlement "
                    "directions</title>\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  out += "<circle cx=\"" + number_text(centre) + "\" cy=\"" + number_text(centre) + "\" r=\"" + number_text(radius) +
         "\" fill=\"none\" stroke=\"#999\"/>\n";
  out += "<text x=\"" + number_text(centre + radius + 12) + "\" y=\"" + number_text(centre + 4) +
         "\" font-size=\"12\">0&#176;</text>\n";
  out += "<text x=\"" + number_text(centre - 10) + "\" y=\"" + number_text(centre - radius - 14) +
         "\" font-size=\"12\">90&#176;</text>\n";
  for (const auto& e : w.evaluations) {
    double x = 0.0, y = 0.0;
    at(e, x, y);
    const std::string fill = e.ratio ? ramp(hi > lo ? (*e.ratio - lo) / (hi - lo) : 1.0) : std::string("white");
    out += "<circle cx=\"" + number_text(x) + "\" cy=\"" + number_text(y) + "\" r=\"5\" fill=\"" + fill + "\" stroke=\"#333\">" +
           "<title>tilt " + number_text(degrees(e.tilt)) + " deg, azimuth " + number_text(degrees(e.azimuth)) + " deg" +
           (e.ratio ? ": R/R0 = " + number_text(*e.ratio, "%.6g") : std::string(": ") + analysis::to_string(e.verdict)) +
           "</title></circle>\n";
    if (e.ratio) {
      out += "<text x=\"" + number_text(x + 8) + "\" y=\"" + number_text(y - 6) + "\" font-size=\"10\" fill=\"#555\">" +
             number_text(*e.ratio, "%.3g") + "</text>\n";
    }
  }
  std::string first = std::to_string(w.evaluations.size()) + " directions within " + number_text(degrees(w.cone_angle)) +
                      "&#176; of gravity, seen from above (distance: tilt, angle: azimuth)";
  std::string second = "no direction collapsed";
  if (w.worst) {
    const analysis::SettlementEvaluation& e = w.evaluations[static_cast<std::size_t>(*w.worst)];
    double x = 0.0, y = 0.0;
    at(e, x, y);
    out += "<circle cx=\"" + number_text(x) + "\" cy=\"" + number_text(y) + "\" r=\"10\" fill=\"none\" stroke=\"#c0392b\" "
           "stroke-width=\"2\"/>\n";
    second = "most harmful: R/R0 = " + number_text(*e.ratio, "%.6g") + ", tilt " + number_text(degrees(e.tilt)) +
             "&#176;, azimuth " + number_text(degrees(e.azimuth)) + "&#176;" +
             (w.upper_bound ? ", certified &#8804; " + number_text(*w.upper_bound, "%.6g") : ", not certified");
  }
  out += "<text x=\"10\" y=\"" + number_text(size + 18) + "\" font-size=\"13\">" + first + "</text>\n";
  out += "<text x=\"10\" y=\"" + number_text(size + 38) + "\" font-size=\"13\">" + second + "</text>\n</svg>\n";
  return out;
}

}  // namespace rbla::io
