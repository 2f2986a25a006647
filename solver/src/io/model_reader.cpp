#include "io/model_reader.hpp"

#include "io/schema_validation.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <sstream>
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

model::PointLoad read_load(const json& entry, const std::string& pointer, const model::Model& m,
                           IssueList& issues) {
  model::PointLoad load;
  const std::string id = entry.at("block").get<std::string>();
  const auto found = m.block_index.find(id);
  if (found == m.block_index.end()) {
    issues.add(pointer + "/block", "no block has id '" + id + "'");
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
    issues.add(pointer + "/block", "block '" + id + "' is a support (role " +
                                       model::to_string(m.blocks[load.block].role) +
                                       "); loads act on free blocks only");
  }
  return load;
}

void read_analysis(const json& doc, model::Model& m, IssueList& issues) {
  model::AnalysisRequest& a = m.analysis;
  a.settlement_direction = m.gravity;
  const bool has_live = !m.live_loads.empty();
  if (!doc.contains("analysis")) {
    // Schema: with no analysis section, the live loads, or else seismic along a horizontal axis.
    if (!has_live) a.seismic_direction = std::abs(m.gravity.x()) > 0.5 ? Vec3::UnitY() : Vec3::UnitX();
    return;
  }
  m.analysis_given = true;
  const json& s = doc["analysis"];
  a.type = s.value("type", "load_multiplier") == "settlement" ? model::AnalysisType::Settlement
                                                                : model::AnalysisType::LoadMultiplier;
  if (s.contains("seismic")) {
    const Vec3 d = to_vec3(s["seismic"]["direction"]);
    if (d.norm() == 0.0) {
      issues.add("/analysis/seismic/direction", "must be a non-zero vector");
    } else if (std::abs(d.normalized().dot(m.gravity)) > 1e-6) {
      issues.add("/analysis/seismic/direction",
                 "must be horizontal: perpendicular to gravity (" + m.gravity_axis + ")");
    } else {
      a.seismic_direction = d.normalized();
    }
  }
  if (s.contains("settlement") && s["settlement"].contains("direction")) {
    const Vec3 d = to_vec3(s["settlement"]["direction"]);
    if (d.norm() == 0.0) issues.add("/analysis/settlement/direction", "must be a non-zero vector");
    else a.settlement_direction = d.normalized();
  }
  a.friction_model = s.value("friction_model", "associative") == "non_associative"
                         ? model::FrictionModel::NonAssociative
                         : model::FrictionModel::Associative;
  const std::string cone = s.value("cone", "exact");
  a.pyramid_bracket = s.value("pyramid_bracket", false);
  a.check_dead_load = s.value("check_dead_load", true);
  a.cone = cone == "pyramid_inscribed"       ? model::ConeKind::PyramidInscribed
           : cone == "pyramid_circumscribed" ? model::ConeKind::PyramidCircumscribed
                                             : model::ConeKind::Exact;
  a.pyramid_faces = s.value("pyramid_faces", 8);
  const std::string formulation = s.value("formulation", "auto");
  a.formulation = formulation == "3d"       ? model::Formulation::ThreeD
                  : formulation == "planar" ? model::Formulation::Planar
                                            : model::Formulation::Auto;
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
  }
  a.time_limit_seconds = s.value("time_limit", 0.0);

  if (a.type == model::AnalysisType::LoadMultiplier && !has_live && !a.seismic_direction) {
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

/// Parser callback that finds the first repeated name in a JSON object. nlohmann keeps the last
/// value of a repeated name silently, so `"unit_weight": 18, ..., "unit_weight": 1.8e7` would
/// pick one without a word; a model must not be ambiguous. Tracks the JSON pointer on the way.
class DuplicateKeyCheck {
 public:
  bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start: frames_.push_back({false, 0, {}, {}}); break;
      case json::parse_event_t::array_start: frames_.push_back({true, 0, {}, {}}); break;
      case json::parse_event_t::key:
        if (!frames_.empty() && parsed.is_string()) {
          Frame& top = frames_.back();
          top.key = parsed.get<std::string>();
          if (!top.keys.insert(top.key).second && pointer_.empty()) {
            key_ = top.key;
            for (const Frame& f : frames_) {
              pointer_ += "/" + (f.array ? std::to_string(f.index) : model::pointer_token(f.key));
            }
          }
        }
        break;
      case json::parse_event_t::value: next_element(); break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        if (!frames_.empty()) frames_.pop_back();
        next_element();
        break;
    }
    return true;
  }
  /// "" when no name repeats; else the JSON pointer of the second occurrence.
  const std::string& pointer() const { return pointer_; }
  const std::string& key() const { return key_; }

 private:
  struct Frame {
    bool array = false;
    std::size_t index = 0;  // array: index of the element being read
    std::string key;        // object: name of the member being read
    std::unordered_set<std::string> keys;
  };
  void next_element() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
  }
  std::vector<Frame> frames_;
  std::string pointer_, key_;
};

}  // namespace

std::string read_text(const std::string& path) {
  if (path == "-") {
    std::ostringstream buffer;
    buffer << std::cin.rdbuf();
    return buffer.str();
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ModelError("", "cannot open '" + path + "' for reading");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw ModelError("", "error while reading '" + path + "'");
  return text;
}

model::Model parse_model(const std::string& text) {
  json doc;
  DuplicateKeyCheck duplicates;
  try {
    doc = json::parse(text, std::ref(duplicates));
  } catch (const json::parse_error& e) {
    std::string what = e.what();
    const auto colon = what.find("parse error");
    throw ModelError("", "malformed JSON: " + (colon == std::string::npos ? what : what.substr(colon)));
  } catch (const json::out_of_range& e) {
    // A number literal beyond double range (e.g. 1e999) is out_of_range.406, not a parse_error.
    std::string what = e.what();
    const auto bracket = what.find("] ");
    throw ModelError("", "malformed JSON: " + (bracket == std::string::npos ? what : what.substr(bracket + 2)));
  }
  if (!duplicates.pointer().empty()) {
    throw ModelError(duplicates.pointer(), "the name '" + duplicates.key() +
                                               "' appears twice in the same object: which value is meant is ambiguous");
  }
  if (const auto issues = validate_against_schema(doc, SchemaKind::Model); !issues.empty()) {
    throw ModelError(issues);
  }

  model::Model m;
  IssueList issues;
  m.title = doc.value("title", "");
  const json& units = doc["units"];
  m.units.length_name = units["length"].get<std::string>();
  m.units.force_name = units.value("force", "kN");
  m.units.unit_weight_name = units.value("unit_weight", "kN/m3");
  m.units.length_to_m = length_factor(m.units.length_name);
  m.units.force_to_kN = force_factor(m.units.force_name);
  m.units.unit_weight_to_kN_m3 = unit_weight_factor(m.units.unit_weight_name);
  m.gravity_axis = doc.value("gravity", "-z");
  m.gravity = gravity_vector(m.gravity_axis);

  double default_unit_weight = 18.0;
  if (doc.contains("defaults")) {
    default_unit_weight = doc["defaults"].value("unit_weight", default_unit_weight);
    m.default_friction = doc["defaults"].value("friction", m.default_friction);
  }

  const double lf = m.units.length_to_m;
  const json& blocks = doc["blocks"];
  m.blocks.reserve(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const json& b = blocks[i];
    const std::string pointer = at("/blocks", i);
    model::Block block;
    block.id = b["id"].get<std::string>();
    block.label = b.value("label", "");
    const std::string role = b.value("role", "free");
    block.role = role == "fixed"            ? model::BlockRole::Fixed
                 : role == "moving_support" ? model::BlockRole::MovingSupport
                                            : model::BlockRole::Free;
    const json& vertices = b["vertices"];
    block.vertices.reserve(vertices.size());
    for (const json& v : vertices) block.vertices.push_back(to_vec3(v) * lf);
    const json& faces = b["faces"];
    block.faces.reserve(faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f) {
      std::vector<int> face;
      face.reserve(faces[f].size());
      for (std::size_t k = 0; k < faces[f].size(); ++k) {
        const auto index = faces[f][k].get<std::int64_t>();
        if (index >= static_cast<std::int64_t>(vertices.size())) {
          issues.add(at(at(pointer + "/faces", f), k),
                     "vertex index " + std::to_string(index) + " is out of range: block '" + block.id +
                         "' has " + std::to_string(vertices.size()) + " vertices");
          continue;
        }
        face.push_back(static_cast<int>(index));
      }
      block.faces.push_back(std::move(face));
    }
    block.unit_weight = b.value("unit_weight", default_unit_weight) * m.units.unit_weight_to_kN_m3;
    if (b.contains("volume")) block.cad_volume = b["volume"].get<double>() * lf * lf * lf;
    if (b.contains("centroid")) block.cad_centroid = to_vec3(b["centroid"]) * lf;

    const auto [existing, inserted] = m.block_index.emplace(block.id, static_cast<int>(i));
    if (!inserted) {
      issues.add(pointer + "/id", "duplicate block id '" + block.id + "' (first used at " +
                                      at("/blocks", existing->second) + ")");
    }
    m.blocks.push_back(std::move(block));
  }

  bool any_free = false;
  for (const auto& block : m.blocks) any_free |= !block.is_support();
  if (!any_free) issues.add("/blocks", "no block has role 'free': there is nothing to analyse");

  if (doc.contains("interfaces")) {
    const json& list = doc["interfaces"];
    std::unordered_map<std::string, std::size_t> seen;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const json& entry = list[i];
      const std::string pointer = at("/interfaces", i);
      model::ContactInterface contact;
      contact.id = entry.value("id", "I" + std::to_string(i));
      contact.label = entry.value("label", "");
      contact.friction = entry.value("friction", m.default_friction);
      const auto [existing, inserted] = seen.emplace(contact.id, i);
      if (!inserted) {
        issues.add(pointer + "/id", "duplicate interface id '" + contact.id + "' (first used at " +
                                        at("/interfaces", existing->second) + ")");
      }
      int ends[2] = {-1, -1};
      for (int k = 0; k < 2; ++k) {
        const std::string id = entry["blocks"][k].get<std::string>();
        const auto found = m.block_index.find(id);
        if (found == m.block_index.end()) {
          issues.add(at(pointer + "/blocks", k), "no block has id '" + id + "'");
        } else {
          ends[k] = found->second;
        }
      }
      if (ends[0] >= 0 && ends[0] == ends[1]) {
        issues.add(pointer + "/blocks", "an interface joins two different blocks; both are '" +
                                            entry["blocks"][0].get<std::string>() + "'");
      }
      contact.block_a = ends[0];
      contact.block_b = ends[1];
      for (const json& p : entry["polygon"]) contact.polygon.push_back(to_vec3(p) * lf);
      m.interfaces.push_back(std::move(contact));
    }
  }

  if (doc.contains("detection")) {
    const json& d = doc["detection"];
    const std::string mode = d.value("mode", "auto");
    m.detection.mode = mode == "off"     ? model::DetectionMode::Off
                       : mode == "merge" ? model::DetectionMode::Merge
                                         : model::DetectionMode::Auto;
    m.detection.joint_tolerance = d.value("joint_tolerance", m.detection.joint_tolerance);
    if (d.contains("relative_tolerance")) m.detection.relative_tolerance = d["relative_tolerance"].get<double>();
    if (d.contains("distance_tolerance")) m.detection.distance_tolerance = d["distance_tolerance"].get<double>() * lf;
    m.detection.angle_tolerance_degrees = d.value("angle_tolerance", m.detection.angle_tolerance_degrees);
    m.detection.min_area_fraction = d.value("min_area_fraction", m.detection.min_area_fraction);
    m.detection.max_near_misses = d.value("max_near_misses", m.detection.max_near_misses);
  }

  issues.throw_if_any();  // loads refer to blocks by id: the index must be sound first

  if (doc.contains("loads")) {
    const json& loads = doc["loads"];
    for (const char* kind : {"dead", "live"}) {
      if (!loads.contains(kind)) continue;
      auto& target = std::string(kind) == "dead" ? m.dead_loads : m.live_loads;
      for (std::size_t i = 0; i < loads[kind].size(); ++i) {
        target.push_back(read_load(loads[kind][i], at(std::string("/loads/") + kind, i), m, issues));
      }
    }
  }
  read_analysis(doc, m, issues);
  if (m.analysis.type == model::AnalysisType::LoadMultiplier) {
    for (std::size_t i = 0; i < m.blocks.size(); ++i) {
      if (m.blocks[i].role == model::BlockRole::MovingSupport) {
        m.warnings.push_back({"moving_support_held",
                              "block '" + m.blocks[i].id +
                                  "' is a moving support but the analysis is not a settlement analysis: "
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
