// One source of truth for defaults: every "default" in schema/model.schema.json equals the
// initialiser of the C++ struct it lands in (solver/src/model/model.hpp), and the reader, given a
// model that leaves the property out, falls back on that initialiser. A default added to the
// schema, or a field mapped here whose schema default went away, fails the test until both sides
// agree.
#include "io/load_model.hpp"
#include "model/model.hpp"
#include "rbla/embedded_schemas.hpp"
#include "support/model_builder.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <string>

namespace {

using nlohmann::json;
using rbla::model::Model;
using rbla::testing::box_block;

/// JSON pointer of every schema node with a "default" -> that default.
void collect_defaults(const json& node, const std::string& pointer, std::map<std::string, json>& out) {
  if (node.is_object()) {
    if (node.contains("default")) out[pointer] = node["default"];
    for (const auto& [key, child] : node.items()) collect_defaults(child, pointer + "/" + key, out);
  } else if (node.is_array()) {
    for (std::size_t i = 0; i < node.size(); ++i) collect_defaults(node[i], pointer + "/" + std::to_string(i), out);
  }
}

json vec(const rbla::model::Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

const char* mode_name(rbla::model::DetectionMode mode) {
  switch (mode) {
    case rbla::model::DetectionMode::Auto: return "auto";
    case rbla::model::DetectionMode::Off: return "off";
    case rbla::model::DetectionMode::Merge: return "merge";
  }
  return "?";
}

/// A block on a fixed base that leaves out every optional property the schema gives a default,
/// with empty `defaults`, `detection`, `tolerances` and `non_associative` objects. A dead load with
/// only a moment and a live load with only a force leave out the other.
json model_leaving_out_defaults() {
  json block = box_block("B", 0, 0, 0, 1, 1, 2);
  block.erase("role");
  return json{{"schema_version", "1.0.0"},
              {"units", {{"length", "m"}}},
              {"defaults", json::object()},
              {"detection", json::object()},
              {"blocks", {box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"), block}},
              {"loads",
               {{"dead", {{{"block", "B"}, {"moment", {0, 0, 1}}}}},
                {"live", {{{"block", "B"}, {"force", {1, 0, 0}}}}}}},
              {"analysis", {{"tolerances", json::object()}, {"non_associative", json::object()}}}};
}

/// A model with an empty `loads` and a seismic load, for the loads' own defaults.
json model_with_empty_loads() {
  return json{{"schema_version", "1.0.0"},
              {"units", {{"length", "m"}}},
              {"blocks", {box_block("base", -1, -1, -0.5, 2, 2, 0, "fixed"), box_block("B", 0, 0, 0, 1, 1, 2)}},
              {"loads", json::object()},
              {"analysis", {{"seismic", {{"direction", {1, 0, 0}}}}}}};
}

/// For each schema pointer with a default: its value in a model (read from a file that left the
/// property out, or default-constructed), in the schema's terms (names for enums, file units).
using Field = std::function<json(const Model&)>;

std::map<std::string, Field> fields() {
  const std::string analysis = "/definitions/analysis/properties/";
  const std::string detection = "/properties/detection/properties/";
  return {
      {"/properties/title", [](const Model& m) { return json(m.title); }},
      {"/properties/units/properties/force", [](const Model& m) { return json(m.units.force_name); }},
      {"/properties/units/properties/unit_weight", [](const Model& m) { return json(m.units.unit_weight_name); }},
      {"/properties/gravity", [](const Model& m) { return json(m.gravity_axis); }},
      {"/properties/defaults/properties/unit_weight", [](const Model& m) { return json(m.default_unit_weight); }},
      {"/properties/defaults/properties/friction", [](const Model& m) { return json(m.default_friction); }},
      {detection + "mode", [](const Model& m) { return json(mode_name(m.detection.mode)); }},
      {detection + "joint_tolerance", [](const Model& m) { return json(m.detection.joint_tolerance); }},
      {detection + "angle_tolerance", [](const Model& m) { return json(m.detection.angle_tolerance_degrees); }},
      {detection + "min_area_fraction", [](const Model& m) { return json(m.detection.min_area_fraction); }},
      {detection + "max_near_misses", [](const Model& m) { return json(m.detection.max_near_misses); }},
      {analysis + "type", [](const Model& m) { return json(to_string(m.analysis.type)); }},
      {analysis + "friction_model", [](const Model& m) { return json(to_string(m.analysis.friction_model)); }},
      {analysis + "cone", [](const Model& m) { return json(to_string(m.analysis.cone)); }},
      {analysis + "check_dead_load", [](const Model& m) { return json(m.analysis.check_dead_load); }},
      {analysis + "pyramid_bracket", [](const Model& m) { return json(m.analysis.pyramid_bracket); }},
      {analysis + "pyramid_faces", [](const Model& m) { return json(m.analysis.pyramid_faces); }},
      {analysis + "formulation", [](const Model& m) { return json(to_string(m.analysis.formulation)); }},
      {analysis + "tolerances/properties/relative_gap", [](const Model& m) { return json(m.analysis.tol_relative_gap); }},
      {analysis + "tolerances/properties/feasibility", [](const Model& m) { return json(m.analysis.tol_feasibility); }},
      {analysis + "non_associative/properties/max_iterations",
       [](const Model& m) { return json(m.analysis.non_associative_max_iterations); }},
      {analysis + "non_associative/properties/tolerance",
       [](const Model& m) { return json(m.analysis.non_associative_tolerance); }},
      {analysis + "non_associative/properties/damping",
       [](const Model& m) { return json(m.analysis.non_associative_damping); }},
      {analysis + "non_associative/properties/warm_start",
       [](const Model& m) { return json(m.analysis.non_associative_warm_start); }},
      {analysis + "non_associative/properties/pointwise_retry",
       [](const Model& m) { return json(m.analysis.non_associative_pointwise_retry); }},
      {analysis + "non_associative/properties/trajectories",
       [](const Model& m) { return json(m.analysis.non_associative_trajectories); }},
      {analysis + "time_limit", [](const Model& m) { return json(m.analysis.time_limit_seconds); }},
  };
}

/// Numbers compare by value (the schema's 0 and 10.0 against a double or an int field).
void expect_same(const json& schema_default, const json& actual, const std::string& what) {
  if (schema_default.is_number() && actual.is_number()) {
    EXPECT_EQ(schema_default.get<double>(), actual.get<double>()) << what;
  } else if (schema_default.is_array() && actual.is_array() && schema_default.size() == actual.size()) {
    for (std::size_t i = 0; i < actual.size(); ++i) expect_same(schema_default[i], actual[i], what + "/" + std::to_string(i));
  } else {
    EXPECT_EQ(schema_default, actual) << what;
  }
}

}  // namespace

TEST(SchemaDefaults, EveryDefaultIsTheStructInitialiserAndTheReadersFallback) {
  std::map<std::string, json> defaults;
  collect_defaults(json::parse(rbla::io::embedded::model_schema), "", defaults);
  const Model constructed;
  const Model read = rbla::io::load_model_text(model_leaving_out_defaults().dump()).model;
  const Model read_empty_loads = rbla::io::load_model_text(model_with_empty_loads().dump()).model;
  const auto& blocks = read.blocks;
  ASSERT_EQ(blocks.size(), 2u);
  ASSERT_EQ(read.dead_loads.size(), 1u);
  ASSERT_EQ(read.live_loads.size(), 1u);

  const auto table = fields();
  std::size_t checked = 0;
  for (const auto& [pointer, value] : defaults) {
    SCOPED_TRACE(pointer);
    if (pointer == "/definitions/block/properties/role") {
      expect_same(value, json(to_string(rbla::model::Block{}.role)), "Block{}");
      expect_same(value, json(to_string(blocks[1].role)), "read");
    } else if (pointer == "/definitions/point_load/properties/force") {
      expect_same(value, vec(rbla::model::PointLoad{}.force), "PointLoad{}");
      expect_same(value, vec(read.dead_loads[0].force), "read");
    } else if (pointer == "/definitions/point_load/properties/moment") {
      expect_same(value, vec(rbla::model::PointLoad{}.moment), "PointLoad{}");
      expect_same(value, vec(read.live_loads[0].moment), "read");
    } else if (pointer == "/properties/loads/properties/dead") {
      EXPECT_EQ(value, json::array());
      EXPECT_TRUE(constructed.dead_loads.empty());
      EXPECT_TRUE(read_empty_loads.dead_loads.empty());
    } else if (pointer == "/properties/loads/properties/live") {
      EXPECT_EQ(value, json::array());
      EXPECT_TRUE(constructed.live_loads.empty());
      EXPECT_TRUE(read_empty_loads.live_loads.empty());
    } else {
      const auto field = table.find(pointer);
      if (field == table.end()) {
        ADD_FAILURE() << "the schema gives a default that no C++ field is checked against: map it in fields()";
        continue;
      }
      expect_same(value, field->second(constructed), "default-constructed Model");
      expect_same(value, field->second(read), "read from a model that leaves it out");
    }
    ++checked;
  }
  // The free block without a unit weight gets the default one (kN/m3, the default unit).
  EXPECT_EQ(blocks[1].unit_weight, defaults.at("/properties/defaults/properties/unit_weight").get<double>());
  for (const auto& [pointer, field] : table) {
    EXPECT_TRUE(defaults.count(pointer)) << pointer << " is mapped here but has no default in the schema";
  }
  EXPECT_EQ(checked, defaults.size());
  EXPECT_GE(checked, 30u);  // the schema's defaults when this test was written
}

TEST(SchemaDefaults, OptionalToleranceOverridesHaveNoDefault) {
  // Absent relative and distance tolerances mean per-joint tolerances: no default on either side.
  const json schema = json::parse(rbla::io::embedded::model_schema);
  const json& p = schema["properties"]["detection"]["properties"];
  EXPECT_FALSE(p["relative_tolerance"].contains("default"));
  EXPECT_FALSE(p["distance_tolerance"].contains("default"));
  const rbla::model::DetectionSettings d;
  EXPECT_FALSE(d.relative_tolerance.has_value());
  EXPECT_FALSE(d.distance_tolerance.has_value());
}
