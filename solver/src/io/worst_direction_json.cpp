#include "io/worst_direction_json.hpp"

#include "io/json_values.hpp"
#include "io/number_text.hpp"
#include "model/angles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace rbla::io {
namespace {

using nlohmann::json;
using rbla::model::kPi;

json evaluation_json(const analysis::DirectionEvaluation& e) {
  json out{{"angle_deg", degrees(e.angle)},
           {"direction", vec3_json(e.direction)},
           {"status", analysis::to_string(e.verdict)},
           {"interior_point_iterations", e.interior_point_iterations},
           {"seconds", e.seconds}};
  if (e.load_multiplier) out["load_multiplier"] = *e.load_multiplier;
  return out;
}

}  // namespace

json worst_direction_json(const analysis::WorstDirection& w, double tolerance) {
  json evaluations = json::array();
  for (const auto& e : w.evaluations) evaluations.push_back(evaluation_json(e));
  json out{{"status", analysis::to_string(w.verdict)},
           {"verdict", w.verdict_text},
           {"certified", w.certified},
           {"tolerance", tolerance},
           {"stop", w.stop},
           {"angle_zero", vec3_json(w.axis_x)},
           {"angle_ninety", vec3_json(w.axis_y)},
           {"num_evaluations", static_cast<int>(w.evaluations.size())},
           {"seconds", w.seconds},
           {"evaluations", evaluations}};
  if (w.alpha_min) out["load_multiplier"] = *w.alpha_min;
  if (w.angle) {
    out["angle_deg"] = degrees(*w.angle);
    out["direction"] = vec3_json(std::cos(*w.angle) * w.axis_x + std::sin(*w.angle) * w.axis_y);
  }
  if (w.lower_bound) out["lower_bound"] = *w.lower_bound;
  return out;
}

namespace {

struct Page {
  double x = 0.0, y = 0.0;
};

struct Polar {
  double centre = 0.0, scale = 1.0;  // px, px per unit of alpha
  /// Seen from above: angle 0 to the right, 90 degrees up the page.
  Page at(double angle, double alpha) const {
    return {centre + scale * alpha * std::cos(angle), centre - scale * alpha * std::sin(angle)};
  }
};

std::string circle(Page c, double r, const std::string& style) {
  return "<circle cx=\"" + number_text(c.x) + "\" cy=\"" + number_text(c.y) + "\" r=\"" + number_text(r) + "\" " + style + "/>\n";
}

std::string line(Page a, Page b, const std::string& style) {
  return "<line x1=\"" + number_text(a.x) + "\" y1=\"" + number_text(a.y) + "\" x2=\"" + number_text(b.x) + "\" y2=\"" +
         number_text(b.y) + "\" " + style + "/>\n";
}

std::vector<analysis::DirectionEvaluation> by_angle(const analysis::WorstDirection& w) {
  std::vector<analysis::DirectionEvaluation> sorted;
  for (const auto& e : w.evaluations) {
    if (e.load_multiplier) sorted.push_back(e);
  }
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.angle < b.angle; });
  return sorted;
}

void append_grid(std::string& out, const Polar& p, double largest) {
  const Page centre{p.centre, p.centre};
  for (int ring = 1; ring <= 4; ++ring) {
    const double alpha = largest * ring / 4.0;
    out += circle(centre, p.scale * alpha, "fill=\"none\" stroke=\"#ddd\"");
    out += "<text x=\"" + number_text(p.centre + 4) + "\" y=\"" + number_text(p.centre - p.scale * alpha - 3) +
           "\" font-size=\"11\" fill=\"#888\">" + number_text(alpha, "%.3g") + "</text>\n";
  }
  for (int k = 0; k < 12; ++k) out += line(centre, p.at(k * kPi / 6.0, largest), "stroke=\"#eee\"");
  for (int k = 0; k < 4; ++k) {
    const Page label = p.at(k * kPi / 2.0, largest * 1.08);
    out += "<text x=\"" + number_text(label.x - 10) + "\" y=\"" + number_text(label.y + 4) + "\" font-size=\"12\">" +
           std::to_string(90 * k) + "&#176;</text>\n";
  }
}

}  // namespace

std::string worst_direction_svg(const analysis::WorstDirection& w) {
  const std::vector<analysis::DirectionEvaluation> points = by_angle(w);
  double largest = 0.0;
  for (const auto& e : points) largest = std::max(largest, *e.load_multiplier);
  if (!(largest > 0.0)) largest = 1.0;
  const double size = 640.0;
  const Polar p{size / 2.0, (size / 2.0 - 40.0) / largest};
  std::string out = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + number_text(size, "%.0f") + "\" height=\"" +
                    number_text(size + 40, "%.0f") + "\" font-family=\"sans-serif\">\n<title>alpha(theta)</title>\n";
  out += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  append_grid(out, p, largest);
  if (!points.empty()) {
    std::string polygon;
    for (const auto& e : points) {
      const Page q = p.at(e.angle, *e.load_multiplier);
      polygon += number_text(q.x) + "," + number_text(q.y) + " ";
    }
    out += "<polygon points=\"" + polygon + "\" fill=\"#4a90d9\" fill-opacity=\"0.15\" stroke=\"#4a90d9\"/>\n";
    for (const auto& e : points) out += circle(p.at(e.angle, *e.load_multiplier), 3.0, "fill=\"#1f5fa8\"");
  }
  if (w.alpha_min && w.angle) {
    out += circle({p.centre, p.centre}, p.scale * *w.alpha_min, "fill=\"none\" stroke=\"#c0392b\" stroke-dasharray=\"4 3\"");
    out += line({p.centre, p.centre}, p.at(*w.angle, *w.alpha_min), "stroke=\"#c0392b\" stroke-width=\"2\"");
  }
  std::string caption = "alpha(theta), seen from above, theta from the first horizontal axis; " +
                        std::to_string(w.evaluations.size()) + " directions evaluated";
  if (w.alpha_min && w.angle) {
    caption = "weakest at " + number_text(degrees(*w.angle)) + " deg: alpha = " + number_text(*w.alpha_min, "%.6g") +
              (w.lower_bound ? " (certified >= " + number_text(*w.lower_bound, "%.6g") + ")" : " (not certified)") + "; " +
              std::to_string(w.evaluations.size()) + " directions evaluated";
  }
  out += "<text x=\"10\" y=\"" + number_text(size + 25) + "\" font-size=\"13\">" + caption + "</text>\n</svg>\n";
  return out;
}

}  // namespace rbla::io
