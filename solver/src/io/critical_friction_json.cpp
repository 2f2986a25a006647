#include "io/critical_friction_json.hpp"

#include "io/number_text.hpp"

#include <algorithm>

namespace rbla::io {
namespace {

using nlohmann::json;

const char* outcome_name(analysis::ThresholdOutcome outcome) {
  switch (outcome) {
    case analysis::ThresholdOutcome::Bracketed: return "bracketed";
    case analysis::ThresholdOutcome::PassesAtMinimum: return "passes_at_smallest_factor";
    case analysis::ThresholdOutcome::FailsAtMaximum: return "fails_at_largest_factor";
    case analysis::ThresholdOutcome::Failed: return "failed";
  }
  return "failed";
}

json evaluation_json(const analysis::FrictionEvaluation& e) {
  json out{{"factor", e.factor}, {"status", analysis::to_string(e.verdict)}, {"passes", e.passes}, {"seconds", e.seconds}};
  if (e.load_multiplier) out["load_multiplier"] = *e.load_multiplier;
  return out;
}

/// Plot area of the alpha(mu) picture: x (friction or factor) from 0 to x_max, alpha from 0 to y_max.
struct Axes {
  double left = 70, top = 30, width = 560, height = 360, x_max = 0, y_max = 0;
  double px(double x) const { return left + width * x / x_max; }
  double py(double y) const { return top + height * (1.0 - y / y_max); }
};

void append_axes(std::string& out, const Axes& a, const std::string& x_label) {
  out += "<rect x=\"" + number_text(a.left) + "\" y=\"" + number_text(a.top) + "\" width=\"" + number_text(a.width) + "\" height=\"" +
         number_text(a.height) + "\" fill=\"none\" stroke=\"#999\"/>\n";
  for (int k = 0; k <= 4; ++k) {
    out += "<text x=\"" + number_text(a.px(a.x_max * k / 4) - 10) + "\" y=\"" + number_text(a.top + a.height + 16) +
           "\" font-size=\"11\">" + number_text(a.x_max * k / 4, "%.3g") + "</text>\n";
    out += "<text x=\"" + number_text(a.left - 40) + "\" y=\"" + number_text(a.py(a.y_max * k / 4) + 4) + "\" font-size=\"11\">" +
           number_text(a.y_max * k / 4, "%.3g") + "</text>\n";
  }
  out += "<text x=\"" + number_text(a.left + a.width / 2 - 20) + "\" y=\"" + number_text(a.top + a.height + 34) +
         "\" font-size=\"13\">" + x_label + "</text>\n";
  out += "<text x=\"" + number_text(a.left) + "\" y=\"" + number_text(a.top - 10) + "\" font-size=\"13\">alpha</text>\n";
}

}  // namespace

json critical_friction_json(const model::Model& model, const analysis::CriticalFriction& c, double tolerance) {
  json evaluations = json::array();
  for (const auto& e : c.evaluations) evaluations.push_back(evaluation_json(e));
  json out{{"outcome", outcome_name(c.outcome)}, {"verdict", c.verdict_text},   {"certified", c.certified},
           {"tolerance", tolerance},             {"stop", c.stop},              {"num_evaluations", static_cast<int>(c.evaluations.size())},
           {"seconds", c.seconds},               {"evaluations", evaluations}};
  if (c.target_alpha) out["target_load_multiplier"] = *c.target_alpha;
  if (!c.scaled_interfaces.empty()) {
    json ids = json::array();
    for (int k : c.scaled_interfaces) ids.push_back(model.interfaces[static_cast<std::size_t>(k)].id);
    out["scaled_interfaces"] = ids;
  }
  if (c.factor_lower) out["factor_lower"] = *c.factor_lower;
  if (c.factor_upper) out["factor"] = *c.factor_upper;
  if (c.uniform_friction) {
    out["given_friction"] = *c.uniform_friction;
    if (c.factor_upper) out["friction"] = *c.uniform_friction * *c.factor_upper;
  }
  return out;
}

std::string critical_friction_svg(const analysis::CriticalFriction& c) {
  const double unit = c.uniform_friction.value_or(1.0);
  Axes a;
  for (const auto& e : c.evaluations) {
    a.x_max = std::max(a.x_max, e.factor * unit);
    if (e.load_multiplier) a.y_max = std::max(a.y_max, *e.load_multiplier);
  }
  if (c.target_alpha) a.y_max = std::max(a.y_max, *c.target_alpha);
  a.x_max = a.x_max > 0.0 ? 1.05 * a.x_max : 1.0;
  a.y_max = a.y_max > 0.0 ? 1.1 * a.y_max : 1.0;
  std::string out = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"660\" height=\"460\" font-family=\"sans-serif\">\n"
                    "<title>alpha(mu)</title>\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  append_axes(out, a, c.uniform_friction ? "friction coefficient mu" : "friction factor");
  if (c.target_alpha) {
    out += "<line x1=\"" + number_text(a.px(0)) + "\" x2=\"" + number_text(a.px(a.x_max)) + "\" y1=\"" + number_text(a.py(*c.target_alpha)) +
           "\" y2=\"" + number_text(a.py(*c.target_alpha)) + "\" stroke=\"#888\" stroke-dasharray=\"4 3\"/>\n";
  }
  if (c.factor_upper) {
    const double x = a.px(*c.factor_upper * unit);
    out += "<line x1=\"" + number_text(x) + "\" x2=\"" + number_text(x) + "\" y1=\"" + number_text(a.py(0)) + "\" y2=\"" +
           number_text(a.py(a.y_max)) + "\" stroke=\"#c0392b\" stroke-width=\"2\"/>\n";
  }
  for (const auto& e : c.evaluations) {
    const double y = e.load_multiplier ? std::max(0.0, *e.load_multiplier) : 0.0;
    out += "<circle cx=\"" + number_text(a.px(e.factor * unit)) + "\" cy=\"" + number_text(a.py(y)) + "\" r=\"4\" " +
           (e.passes ? "fill=\"#1f5fa8\"" : "fill=\"white\" stroke=\"#c0392b\"") + "/>\n";
  }
  const std::string caption = c.factor_upper ? "critical: " + (c.uniform_friction ? "mu = " + number_text(*c.factor_upper * unit, "%.6g")
                                                                                  : "factor " + number_text(*c.factor_upper, "%.6g"))
                                             : std::string("no critical value in the range tried");
  out += "<text x=\"70\" y=\"450\" font-size=\"13\">" + caption + "; hollow: does not " +
         (c.target_alpha ? "carry the target" : "stand") + "</text>\n</svg>\n";
  return out;
}

}  // namespace rbla::io
