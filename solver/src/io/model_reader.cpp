#include "io/model_reader.hpp"

#include "io/input_file.hpp"
#include "io/json_reader.hpp"
#include "io/printable.hpp"
#include "io/schema_validation.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <numeric>
#include <algorithm>
#include <sstream>
#include <optional>
#include <unordered_set>

namespace rbla::io {

using model::InputIssue;
using model::ModelError;
using model::Vec3;
using nlohmann::json;

namespace {

// Unit factors to metres, kilonewtons and kN/m^3.
double length_factor(const std::string& unit) {
  if (unit == "mm") return 1e-3;
  if (unit == "cm") return 1e-2;
  return 1.0;  // "m"; the schema admits nothing else
}

double force_factor(const std::string& unit) {
  if (unit == "N") return 1e-3;
  if (unit == "MN") return 1e3;
  return 1.0;  // "kN"
}

double unit_weight_factor(const std::string& unit) {
  // 1 N/m^3 = 1e-3 kN/m^3; 1 N/mm^3 = 1e-3 kN / 1e-9 m^3 = 1e6 kN/m^3; 1 N/cm^3 = 1e3 kN/m^3.
  if (unit == "N/m3") return 1e-3;
  if (unit == "N/mm3") return 1e6;
  if (unit == "kN/mm3") return 1e9;
  if (unit == "N/cm3") return 1e3;
  if (unit == "kN/cm3") return 1e6;
  return 1.0;  // "kN/m3"
}

Vec3 gravity_vector(const std::string& axis) {
  const double sign = axis[0] == '-' ? -1.0 : 1.0;
  switch (axis[1]) {
    case 'x': return sign * Vec3::UnitX();
    case 'y': return sign * Vec3::UnitY();
    default: return sign * Vec3::UnitZ();
  }
}

Vec3 to_vec3(const json& value) { return Vec3(value[0].get<double>(), value[1].get<double>(), value[2].get<double>()); }

std::string at(const std::string& base, std::size_t index) { return base + "/" + std::to_string(index); }

/// Collects semantic issues so the user sees all of them at once, not one per run.
class IssueList {
 public:
  void add(std::string pointer, std::string message) { issues_.push_back({std::move(pointer), std::move(message)}); }
  void throw_if_any() const {
    if (!issues_.empty()) throw ModelError(issues_);
  }

 private:
  std::vector<InputIssue> issues_;
};

std::string format_number(double value) {
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

/// A user string (id, label) as messages quote it: escaped and cut (io/printable.hpp).
std::string quote_user(const std::string& text) { return "'" + printable(text) + "'"; }

/// The unit vector along `d`; empty for the zero vector. Scaled by its largest component first:
/// [1e-170, 0, 0] is the direction +x, though its squared length underflows to zero.
std::optional<Vec3> direction_of(const Vec3& d) {
  const double largest = d.cwiseAbs().maxCoeff();
  if (!(largest > 0.0)) return std::nullopt;
  return Vec3(d / largest).normalized();
}

model::PointLoad read_load(const json& entry, const std::string& pointer, const model::Model& m,
                           IssueList& issues) {
  model::PointLoad load;
  const std::string id = entry.at("block").get<std::string>();
  const auto found = m.block_index.find(id);
  if (found == m.block_index.end()) {
    issues.add(pointer + "/block", "no block has id " + quote_user(id));
    return load;
  }
  load.block = found->second;
  const double lf = m.units.length_to_m;
  const double ff = m.units.force_to_kN;
  if (entry.contains("force")) load.force = to_vec3(entry["force"]) * ff;
  if (entry.contains("moment")) load.moment = to_vec3(entry["moment"]) * (ff * lf);
  // The point defaults to the centroid, known only after geometry: NaN marks "not given".
  load.point = entry.contains("point") ? Vec3(to_vec3(entry["point"]) * lf)
                                       : Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  if (m.blocks[load.block].is_support()) {
    issues.add(pointer + "/block", "block " + quote_user(id) + " is a support (role " +
                                       model::to_string(m.blocks[load.block].role) +
                                       "); loads act on free blocks only");
  }
  return load;
}

/// Schema (/analysis): when it does not say what to compute, a load-multiplier analysis with the
/// live loads, or, when there are none, seismic along +x (+y when gravity is along x).
std::optional<Vec3> default_seismic_direction(const model::Model& m) {
  if (!m.live_loads.empty()) return std::nullopt;
  return std::abs(m.gravity.x()) > 0.5 ? Vec3::UnitY() : Vec3::UnitX();
}

void read_analysis(const json& doc, model::Model& m, IssueList& issues) {
  model::AnalysisRequest& a = m.analysis;
  a.settlement_direction = m.gravity;
  const bool has_live = !m.live_loads.empty();
  if (!doc.contains("analysis")) {
    a.seismic_direction = default_seismic_direction(m);
    return;
  }
  m.analysis_given = true;
  const json& s = doc["analysis"];
  // Only settings (friction model, cone, tolerances...): the default analysis with them.
  if (!s.contains("type") && !s.contains("seismic")) a.seismic_direction = default_seismic_direction(m);
  if (s.contains("type")) {
    a.type = s["type"].get<std::string>() == "settlement" ? model::AnalysisType::Settlement
                                                          : model::AnalysisType::LoadMultiplier;
  }
  bool seismic_refused = false;
  if (s.contains("seismic")) {
    const std::optional<Vec3> d = direction_of(to_vec3(s["seismic"]["direction"]));
    seismic_refused = !d || std::abs(d->dot(m.gravity)) > 1e-6;
    if (!d) {
      issues.add("/analysis/seismic/direction", "must be a non-zero vector (all three components are 0)");
    } else if (seismic_refused) {
      issues.add("/analysis/seismic/direction",
                 "must be horizontal: perpendicular to gravity (" + m.gravity_axis + ")");
    } else {
      a.seismic_direction = *d;
    }
  }
  if (s.contains("settlement") && s["settlement"].contains("direction")) {
    const std::optional<Vec3> d = direction_of(to_vec3(s["settlement"]["direction"]));
    if (!d) issues.add("/analysis/settlement/direction", "must be a non-zero vector (all three components are 0)");
    else a.settlement_direction = *d;
  }
  if (s.contains("friction_model")) {
    a.friction_model = s["friction_model"].get<std::string>() == "non_associative"
                           ? model::FrictionModel::NonAssociative
                           : model::FrictionModel::Associative;
  }
  a.pyramid_bracket = s.value("pyramid_bracket", a.pyramid_bracket);
  a.check_dead_load = s.value("check_dead_load", a.check_dead_load);
  if (s.contains("cone")) {
    const std::string cone = s["cone"].get<std::string>();
    a.cone = cone == "pyramid_inscribed"       ? model::ConeKind::PyramidInscribed
             : cone == "pyramid_circumscribed" ? model::ConeKind::PyramidCircumscribed
                                               : model::ConeKind::Exact;
  }
  a.pyramid_faces = s.value("pyramid_faces", a.pyramid_faces);
  if (s.contains("formulation")) {
    const std::string formulation = s["formulation"].get<std::string>();
    a.formulation = formulation == "3d"       ? model::Formulation::ThreeD
                    : formulation == "planar" ? model::Formulation::Planar
                                              : model::Formulation::Auto;
  }
  if (s.contains("tolerances")) {
    a.tol_relative_gap = s["tolerances"].value("relative_gap", a.tol_relative_gap);
    a.tol_feasibility = s["tolerances"].value("feasibility", a.tol_feasibility);
  }
  if (s.contains("non_associative")) {
    const json& na = s["non_associative"];
    a.non_associative_max_iterations = na.value("max_iterations", a.non_associative_max_iterations);
    a.non_associative_tolerance = na.value("tolerance", a.non_associative_tolerance);
    a.non_associative_damping = na.value("damping", a.non_associative_damping);
    a.non_associative_warm_start = na.value("warm_start", a.non_associative_warm_start);
    a.non_associative_pointwise_retry = na.value("pointwise_retry", a.non_associative_pointwise_retry);
    a.non_associative_trajectories = na.value("trajectories", a.non_associative_trajectories);
  }
  a.time_limit_seconds = s.value("time_limit", a.time_limit_seconds);

  // A seismic direction that was given but refused has its own message; this one would mislead.
  if (a.type == model::AnalysisType::LoadMultiplier && !has_live && !a.seismic_direction && !seismic_refused) {
    issues.add("/analysis", "a load-multiplier analysis needs live loads (/loads/live) or a seismic direction "
                            "(/analysis/seismic/direction)");
  }
  if (a.type == model::AnalysisType::Settlement) {
    bool any_moving = false;
    for (const auto& block : m.blocks) any_moving |= block.role == model::BlockRole::MovingSupport;
    if (!any_moving) {
      issues.add("/analysis/type", "a settlement analysis needs at least one block with role 'moving_support'");
    }
    if (has_live || a.seismic_direction) {
      issues.add("/analysis/type", "a settlement analysis takes no live loads or seismic direction; "
                                   "run those as a separate load-multiplier analysis");
    }
  }
}


/// Units, gravity, title and defaults; returns the default unit weight (file units). What the
/// file leaves out keeps the value model::Model starts with (the schema's defaults; a test,
/// tests/unit/test_schema_defaults.cpp, keeps the two equal).
double read_units_and_defaults(const json& doc, model::Model& m) {
  m.title = doc.value("title", m.title);
  const json& units = doc["units"];
  m.units.length_name = units["length"].get<std::string>();
  m.units.force_name = units.value("force", m.units.force_name);
  m.units.unit_weight_name = units.value("unit_weight", m.units.unit_weight_name);
  m.units.length_to_m = length_factor(m.units.length_name);
  m.units.force_to_kN = force_factor(m.units.force_name);
  m.units.unit_weight_to_kN_m3 = unit_weight_factor(m.units.unit_weight_name);
  m.gravity_axis = doc.value("gravity", m.gravity_axis);
  m.gravity = gravity_vector(m.gravity_axis);
  if (doc.contains("defaults")) {
    m.default_unit_weight = doc["defaults"].value("unit_weight", m.default_unit_weight);
    m.default_friction = doc["defaults"].value("friction", m.default_friction);
  }
  return m.default_unit_weight;
}

std::vector<std::vector<int>> read_faces(const json& faces, std::size_t num_vertices, const std::string& pointer,
                                         const std::string& block_id, IssueList& issues) {
  std::vector<std::vector<int>> out;
  out.reserve(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    std::vector<int> face;
    face.reserve(faces[f].size());
    for (std::size_t k = 0; k < faces[f].size(); ++k) {
      // The schema has checked for integers >= 0 (int64: json_reader turns larger ones into doubles).
      const auto index = faces[f][k].get<std::int64_t>();
      if (index >= static_cast<std::int64_t>(num_vertices)) {
        issues.add(at(at(pointer + "/faces", f), k),
                   "vertex index " + std::to_string(index) + " is out of range: block " + quote_user(block_id) + " has " +
                       std::to_string(num_vertices) + " vertices (indices 0 to " + std::to_string(num_vertices - 1) +
                       ")");
        continue;
      }
      face.push_back(static_cast<int>(index));
    }
    out.push_back(std::move(face));
  }
  return out;
}

void read_blocks(const json& blocks, double default_unit_weight, model::Model& m, IssueList& issues) {
  const double lf = m.units.length_to_m;
  m.blocks.reserve(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const json& b = blocks[i];
    const std::string pointer = at("/blocks", i);
    model::Block block;
    block.id = b["id"].get<std::string>();
    block.label = b.value("label", block.label);
    if (b.contains("role")) {
      const std::string role = b["role"].get<std::string>();
      block.role = role == "fixed"            ? model::BlockRole::Fixed
                   : role == "moving_support" ? model::BlockRole::MovingSupport
                                              : model::BlockRole::Free;
    }
    const json& vertices = b["vertices"];
    block.vertices.reserve(vertices.size());
    for (const json& v : vertices) block.vertices.push_back(to_vec3(v) * lf);
    block.faces = read_faces(b["faces"], vertices.size(), pointer, block.id, issues);
    block.unit_weight = b.value("unit_weight", default_unit_weight) * m.units.unit_weight_to_kN_m3;
    if (b.contains("volume")) block.cad_volume = b["volume"].get<double>() * lf * lf * lf;
    if (b.contains("centroid")) block.cad_centroid = to_vec3(b["centroid"]) * lf;

    const auto [existing, inserted] = m.block_index.emplace(block.id, static_cast<int>(i));
    if (!inserted) {
      issues.add(pointer + "/id", "duplicate block id " + quote_user(block.id) + " (first used at " +
                                      at("/blocks", existing->second) + ")");
    }
    m.blocks.push_back(std::move(block));
  }
  bool any_free = false;
  for (const auto& block : m.blocks) any_free |= !block.is_support();
  if (!any_free) issues.add("/blocks", "no block has role 'free': there is nothing to analyse");
}

/// Position in `polygon` of its k-th corner read from corner `start` in direction `step` (+1, -1).
inline std::size_t corner(std::size_t n, std::size_t start, int step, std::size_t k) {
  return step > 0 ? (start + k) % n : (start + n - k % n) % n;
}

/// The reading of a polygon that every copy of it shares, whatever corner and direction it
/// starts from: the lexicographically smallest sequence of corners.
struct CanonicalPolygon {
  std::size_t start = 0;
  int step = 1;
};

bool corner_less(const Vec3& a, const Vec3& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

/// -1, 0, 1 as the polygon p read as `cp` sorts before, equal to or after q read as `cq`.
int compare_polygons(const std::vector<Vec3>& p, CanonicalPolygon cp, const std::vector<Vec3>& q, CanonicalPolygon cq) {
  if (p.size() != q.size()) return p.size() < q.size() ? -1 : 1;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const Vec3& a = p[corner(p.size(), cp.start, cp.step, k)];
    const Vec3& b = q[corner(q.size(), cq.start, cq.step, k)];
    if (corner_less(a, b)) return -1;
    if (corner_less(b, a)) return 1;
  }
  return 0;
}

CanonicalPolygon canonical(const std::vector<Vec3>& polygon) {
  CanonicalPolygon best;
  if (polygon.empty()) return best;
  std::size_t lowest = 0;
  for (std::size_t k = 1; k < polygon.size(); ++k) {
    if (corner_less(polygon[k], polygon[lowest])) lowest = k;
  }
  // Readings from every copy of the lowest corner, both ways; a polygon with many equal corners
  // has zero area and is refused later, so a few candidates are enough.
  std::size_t tried = 0;
  for (std::size_t k = 0; k < polygon.size() && tried < 8; ++k) {
    if (corner_less(polygon[lowest], polygon[k])) continue;
    ++tried;
    for (int step : {1, -1}) {
      const CanonicalPolygon candidate{k, step};
      if (compare_polygons(polygon, candidate, polygon, best) < 0) best = candidate;
    }
  }
  return best;
}

/// Interfaces given more than once: the same two blocks (either order) and the same polygon (the
/// same corners in the same cyclic order, from any corner, either way round). A repeat adds
/// contact points where there already are some; the friction cones of coincident points add up
/// to the same cone, so the forces the joint admits do not change, only the unknowns multiply
/// (10^5 copies of a square joint: 4 * 10^5 contact points). Each joint is kept once and one
/// warning says how many repeats were dropped; repeats that disagree on friction are ambiguous
/// and refused. Sorting by a canonical reading, O(n log n) in the interfaces. A polygon with more
/// than 8 copies of its lowest corner may keep its repeats (harmless: as before).
void drop_repeated_interfaces(model::Model& m, IssueList& issues) {
  const auto& list = m.interfaces;
  std::vector<CanonicalPolygon> forms(list.size());
  for (std::size_t i = 0; i < list.size(); ++i) forms[i] = canonical(list[i].polygon);
  auto pair_of = [&](std::size_t i) {
    return std::make_pair(std::min(list[i].block_a, list[i].block_b), std::max(list[i].block_a, list[i].block_b));
  };
  auto compare = [&](std::size_t i, std::size_t j) {
    if (pair_of(i) != pair_of(j)) return pair_of(i) < pair_of(j) ? -1 : 1;
    return compare_polygons(list[i].polygon, forms[i], list[j].polygon, forms[j]);
  };
  std::vector<std::size_t> order(list.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    const int c = compare(i, j);
    return c < 0 || (c == 0 && i < j);
  });
  std::vector<char> repeat(list.size(), 0);
  std::size_t repeats = 0, conflicts = 0;
  std::size_t first_repeat = list.size(), its_original = 0, first_conflict = list.size(), conflict_original = 0;
  for (std::size_t run = 0, k = 1; k < order.size(); ++k) {
    if (compare(order[run], order[k]) != 0) {
      run = k;
      continue;
    }
    const std::size_t i = order[k], original = order[run];  // original: the run's first in the file
    if (list[i].friction != list[original].friction) {
      if (conflicts++ == 0 || i < first_conflict) first_conflict = i, conflict_original = original;
      continue;
    }
    repeat[i] = 1;
    if (repeats++ == 0 || i < first_repeat) first_repeat = i, its_original = original;
  }
  if (conflicts > 0) {
    issues.add(at("/interfaces", first_conflict),
               "repeats " + at("/interfaces", conflict_original) + " (the same two blocks and the same polygon) with " +
                   "another friction (" + format_number(list[first_conflict].friction) + " against " +
                   format_number(list[conflict_original].friction) + "): which is meant is ambiguous" +
                   (conflicts > 1 ? " (" + std::to_string(conflicts) + " interfaces in all are such repeats)" : ""));
    return;
  }
  if (repeats == 0) return;
  m.warnings.push_back(
      {"repeated_interfaces",
       std::to_string(repeats) + (repeats == 1 ? " interface repeats" : " interfaces repeat") +
           " an earlier one (the same two blocks and the same polygon; first " + at("/interfaces", first_repeat) +
           ", a repeat of " + at("/interfaces", its_original) + "): each joint is kept once",
       at("/interfaces", first_repeat)});
  std::size_t kept = 0;
  for (std::size_t i = 0; i < m.interfaces.size(); ++i) {
    if (repeat[i]) continue;
    if (kept != i) m.interfaces[kept] = std::move(m.interfaces[i]);
    ++kept;
  }
  m.interfaces.resize(kept);
}

void read_interfaces(const json& list, model::Model& m, IssueList& issues) {
  std::unordered_map<std::string, std::size_t> seen;
  bool references_sound = true;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const json& entry = list[i];
    const std::string pointer = at("/interfaces", i);
    model::ContactInterface contact;
    contact.id = entry.value("id", "I" + std::to_string(i));
    contact.label = entry.value("label", contact.label);
    contact.friction = entry.value("friction", m.default_friction);
    contact.source_index = static_cast<int>(i);
    const auto [existing, inserted] = seen.emplace(contact.id, i);
    if (!inserted) {
      issues.add(pointer + "/id", "duplicate interface id " + quote_user(contact.id) + " (first used at " +
                                      at("/interfaces", existing->second) + ")");
    }
    int ends[2] = {-1, -1};
    for (int k = 0; k < 2; ++k) {
      const std::string id = entry["blocks"][k].get<std::string>();
      const auto found = m.block_index.find(id);
      if (found == m.block_index.end()) {
        issues.add(at(pointer + "/blocks", k), "no block has id " + quote_user(id));
        references_sound = false;
      } else {
        ends[k] = found->second;
      }
    }
    if (ends[0] >= 0 && ends[0] == ends[1]) {
      issues.add(pointer + "/blocks", "an interface joins two different blocks; both are " +
                                          quote_user(entry["blocks"][0].get<std::string>()));
      references_sound = false;
    }
    contact.block_a = ends[0];
    contact.block_b = ends[1];
    for (const json& p : entry["polygon"]) contact.polygon.push_back(to_vec3(p) * m.units.length_to_m);
    m.interfaces.push_back(std::move(contact));
  }
  if (references_sound) drop_repeated_interfaces(m, issues);
}

void read_detection(const json& d, model::Model& m) {
  if (d.contains("mode")) {
    const std::string mode = d["mode"].get<std::string>();
    m.detection.mode = mode == "off"     ? model::DetectionMode::Off
                       : mode == "merge" ? model::DetectionMode::Merge
                                         : model::DetectionMode::Auto;
  }
  m.detection.joint_tolerance = d.value("joint_tolerance", m.detection.joint_tolerance);
  if (d.contains("relative_tolerance")) m.detection.relative_tolerance = d["relative_tolerance"].get<double>();
  if (d.contains("distance_tolerance")) {
    m.detection.distance_tolerance = d["distance_tolerance"].get<double>() * m.units.length_to_m;
  }
  m.detection.angle_tolerance_degrees = d.value("angle_tolerance", m.detection.angle_tolerance_degrees);
  m.detection.min_area_fraction = d.value("min_area_fraction", m.detection.min_area_fraction);
  m.detection.max_near_misses = d.value("max_near_misses", m.detection.max_near_misses);
}

void read_loads(const json& loads, model::Model& m, IssueList& issues) {
  for (const char* kind : {"dead", "live"}) {
    if (!loads.contains(kind)) continue;
    auto& target = std::string(kind) == "dead" ? m.dead_loads : m.live_loads;
    for (std::size_t i = 0; i < loads[kind].size(); ++i) {
      target.push_back(read_load(loads[kind][i], at(std::string("/loads/") + kind, i), m, issues));
    }
  }
}

}  // namespace

std::string read_text(const std::string& path, const InputLimits& limits) {
  InputFile input(path, limits.max_bytes);
  std::ostringstream buffer;
  buffer << input.stream().rdbuf();
  return buffer.str();
}

model::Model parse_model(const std::string& text, const InputLimits& limits) {
  return model_from_json(read_json(std::string_view(text), limits));
}

model::Model parse_model(std::istream& in, const InputLimits& limits) { return model_from_json(read_json(in, limits)); }

model::Model model_from_json(const json& doc) {
  if (const auto issues = validate_against_schema(doc, SchemaKind::Model); !issues.empty()) {
    throw ModelError(issues);
  }
  model::Model m;
  IssueList issues;
  const double default_unit_weight = read_units_and_defaults(doc, m);
  read_blocks(doc["blocks"], default_unit_weight, m, issues);
  if (doc.contains("interfaces")) read_interfaces(doc["interfaces"], m, issues);
  if (doc.contains("detection")) read_detection(doc["detection"], m);
  issues.throw_if_any();  // loads refer to blocks by id: the index must be sound first

  if (doc.contains("loads")) read_loads(doc["loads"], m, issues);
  read_analysis(doc, m, issues);
  if (m.analysis.type == model::AnalysisType::LoadMultiplier) {
    for (std::size_t i = 0; i < m.blocks.size(); ++i) {
      if (m.blocks[i].role == model::BlockRole::MovingSupport) {
        m.warnings.push_back({"moving_support_held",
                              "block " + quote_user(m.blocks[i].id) +
                                  " is a moving support but the analysis is not a settlement analysis: "
                                  "it is held fixed",
                              at("/blocks", i) + "/role"});
      }
    }
  }
  issues.throw_if_any();
  return m;
}

std::vector<InputIssue> validate_result_text(const std::string& text) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    return {{"", std::string("malformed JSON: ") + e.what()}};
  }
  return validate_against_schema(doc, SchemaKind::Result);
}

}  // namespace rbla::io
