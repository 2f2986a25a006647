#include "io/sweep_io.hpp"

#include "io/number_text.hpp"

#include "model/errors.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace rbla::io {
namespace {

using nlohmann::json;

/// Point result files are ours and small; one larger than this is not read back.
constexpr std::streamsize kMaxPointFileBytes = 1 << 28;

double parse_number(const std::string& text, const std::string& option) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || !std::isfinite(value)) {
    throw model::ModelError(option, "'" + text + "' is not a finite number");
  }
  return value;
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.push_back("");
  return parts;
}

std::string quoted(const std::string& word) {
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

void append_panel(std::string& out, const analysis::SweepAxis& axis, std::size_t a, const std::vector<SweepRow>& rows,
                  double top, const std::string& value_name) {
  const double left = 70, width = 560, height = 200;
  double lo = std::min(axis.low, axis.high), hi = std::max(axis.low, axis.high), v_max = 0.0;
  for (const SweepRow& r : rows) v_max = std::max(v_max, r.value.value_or(0.0));
  if (hi <= lo) hi = lo + 1.0;
  if (!(v_max > 0.0)) v_max = 1.0;
  out += "<rect x=\"70\" y=\"" + number_text(top) + "\" width=\"560\" height=\"200\" fill=\"none\" stroke=\"#999\"/>\n";
  out += "<text x=\"" + number_text(left) + "\" y=\"" + number_text(top + height + 30) + "\" font-size=\"13\">" +
         analysis::to_string(axis.parameter) + " from " + number_text(lo, "%.4g") + " to " + number_text(hi, "%.4g") + "; " +
         value_name + " up to " + number_text(v_max, "%.4g") + "</text>\n";
  for (const SweepRow& r : rows) {
    if (!r.value || a >= r.point.values.size()) continue;
    const double x = left + width * (r.point.values[a] - lo) / (hi - lo);
    const double y = top + height * (1.0 - *r.value / (1.1 * v_max));
    out += "<circle cx=\"" + number_text(x) + "\" cy=\"" + number_text(y) + "\" r=\"3\" fill=\"#1f5fa8\"/>\n";
  }
}

}  // namespace

analysis::SweepAxis parse_sweep_axis(const std::string& text, bool grid, const std::string& option) {
  const auto equals = text.find('=');
  const std::string name = text.substr(0, equals);
  const auto parameter = analysis::parse_sweep_parameter(name);
  if (equals == std::string::npos || !parameter) {
    throw model::ModelError(option, "'" + text + "': expected NAME=" + (grid ? "LOW:HIGH:COUNT" : "LOW:HIGH") +
                                        " with NAME one of friction, friction_factor, unit_weight_factor, "
                                        "seismic_angle, settlement_tilt, settlement_azimuth");
  }
  const std::vector<std::string> parts = split(text.substr(equals + 1), ':');
  if (parts.size() != (grid ? 3u : 2u)) {
    throw model::ModelError(option, "'" + text + "': expected " + (grid ? "LOW:HIGH:COUNT" : "LOW:HIGH") + " after '='");
  }
  analysis::SweepAxis axis{*parameter, parse_number(parts[0], option), parse_number(parts[1], option), 1};
  if (grid) {
    const double count = parse_number(parts[2], option);
    if (count < 1 || count > 100000 || count != std::floor(count)) {
      throw model::ModelError(option, "'" + text + "': COUNT must be a whole number from 1 to 100000");
    }
    axis.count = static_cast<int>(count);
  }
  return axis;
}

std::string point_file_name(int index) {
  char name[32];
  std::snprintf(name, sizeof name, "point_%06d.json", index);
  return name;
}

json sweep_point_json(const std::vector<analysis::SweepAxis>& axes, const analysis::SweepPoint& point) {
  json parameters = json::object();
  for (std::size_t a = 0; a < axes.size(); ++a) parameters[analysis::to_string(axes[a].parameter)] = point.values[a];
  return json{{"index", point.index}, {"parameters", parameters}};
}

/// Whether a point file's sweep_point section is this point's: the same index and the same
/// parameter values (written with 17 digits, so read back exactly). A file left by an earlier
/// sweep in the same folder would otherwise lend its value to another point.
bool is_this_point(const json& result, const std::vector<analysis::SweepAxis>& axes, const analysis::SweepPoint& point) {
  const auto section = result.find("sweep_point");
  if (section == result.end() || !section->is_object() || section->value("index", -1) != point.index) return false;
  const auto parameters = section->find("parameters");
  if (parameters == section->end() || !parameters->is_object() || parameters->size() != axes.size()) return false;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const auto value = parameters->find(analysis::to_string(axes[a].parameter));
    if (value == parameters->end() || !value->is_number() || value->get<double>() != point.values[a]) return false;
  }
  return true;
}

SweepRow read_sweep_row(const std::string& path, const std::vector<analysis::SweepAxis>& axes,
                        const analysis::SweepPoint& point) {
  SweepRow row;
  row.point = point;
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return row;
  row.status = "unreadable";
  if (in.tellg() > kMaxPointFileBytes) return row;
  in.seekg(0);
  const json result = json::parse(in, nullptr, false);
  if (result.is_discarded() || !result.is_object() || !result.contains("status")) return row;
  if (!is_this_point(result, axes, point)) {
    row.status = "mismatched";
    return row;
  }
  row.status = result.value("status", std::string("unreadable"));
  if (result.contains("load_multiplier") && result["load_multiplier"].is_number()) {
    row.value = result["load_multiplier"].get<double>();
  } else if (result.contains("base_reaction") && result["base_reaction"].contains("at_collapse")) {
    row.value = result["base_reaction"]["at_collapse"].get<double>();
  }
  if (result.contains("timings")) row.seconds = result["timings"].value("total_seconds", 0.0);
  return row;
}

std::string sweep_csv(const std::vector<analysis::SweepAxis>& axes, const std::vector<SweepRow>& rows,
                      const std::string& value_name) {
  std::ostringstream out;
  out.precision(17);
  out << "index";
  for (const auto& axis : axes) out << "," << analysis::to_string(axis.parameter);
  out << ",status," << value_name << ",seconds\n";
  for (const SweepRow& r : rows) {
    out << r.point.index;
    for (double v : r.point.values) out << "," << v;
    out << "," << r.status << ",";
    if (r.value) out << *r.value;
    out << "," << r.seconds << "\n";
  }
  return out.str();
}

std::string sweep_svg(const std::vector<analysis::SweepAxis>& axes, const std::vector<SweepRow>& rows,
                      const std::string& value_name) {
  const double panel = 250.0;
  std::string out = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"660\" height=\"" +
                    number_text(40 + panel * std::max<std::size_t>(axes.size(), 1), "%.0f") +
                    "\" font-family=\"sans-serif\">\n<title>sweep</title>\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  for (std::size_t a = 0; a < axes.size(); ++a) append_panel(out, axes[a], a, rows, 20 + panel * a, value_name);
  return out + "</svg>\n";
}

std::string slurm_script(const std::vector<std::string>& command, int tasks) {
  std::string line;
  for (const std::string& word : command) line += quoted(word) + " ";
  return "#!/bin/bash\n"
         "# Written by rbla sweep: one task of the job array per slice of the points. Submit with\n"
         "#   sbatch THIS_FILE\n"
         "# and, once every task has finished, write the summary with the same sweep command and --collect.\n"
         "#SBATCH --job-name=rbla-sweep\n"
         "#SBATCH --array=0-" + std::to_string(tasks - 1) + "\n"
         "#SBATCH --cpus-per-task=1\n"
         "set -eu\n"
         "exec " + line + "--threads 1 --task \"${SLURM_ARRAY_TASK_ID}\" --tasks " + std::to_string(tasks) + "\n";
}

}  // namespace rbla::io
