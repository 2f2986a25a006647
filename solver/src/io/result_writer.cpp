#include "io/result_writer.hpp"

namespace rbla::io {

using nlohmann::json;

namespace {

json vec3_json(const model::Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

}  // namespace

json model_summary_json(const model::Model& model) {
  std::size_t free_blocks = 0, fixed_blocks = 0, moving_blocks = 0, detected = 0;
  double total_weight = 0.0;
  for (const auto& block : model.blocks) {
    switch (block.role) {
      case model::BlockRole::Free:
        ++free_blocks;
        total_weight += block.weight();
        break;
      case model::BlockRole::Fixed: ++fixed_blocks; break;
      case model::BlockRole::MovingSupport: ++moving_blocks; break;
    }
  }
  for (const auto& contact : model.interfaces) detected += contact.detected ? 1 : 0;
  const model::BoundingBox box = model.bounding_box();
  const double l = model.units.length_to_m;
  return json{{"num_blocks", model.blocks.size()},
              {"num_free_blocks", free_blocks},
              {"num_fixed_blocks", fixed_blocks},
              {"num_moving_blocks", moving_blocks},
              {"num_interfaces", model.interfaces.size()},
              {"num_contact_points", model.num_contact_points()},
              {"num_detected_interfaces", detected},
              {"bounding_box", {{"min", vec3_json(box.min / l)}, {"max", vec3_json(box.max / l)}}},
              {"total_weight", total_weight / model.units.force_to_kN}};
}

json warnings_json(const model::Model& model) {
  json list = json::array();
  for (const auto& warning : model.warnings) {
    json entry{{"code", warning.code}, {"message", warning.message}};
    if (!warning.pointer.empty()) entry["pointer"] = warning.pointer;
    list.push_back(std::move(entry));
  }
  return list;
}

json model_only_result(const model::Model& model, const StageTimings& timings, const std::string& source) {
  json result{{"schema_version", "1.0.0"},
              {"rbla_version", RBLA_VERSION},
              {"status", "model_only"},
              {"verdict", "Model read and checked; no analysis was run."},
              {"units", {{"length", model.units.length_name}, {"force", model.units.force_name}}},
              {"model_summary", model_summary_json(model)},
              {"warnings", warnings_json(model)},
              {"timings",
               {{"read_seconds", timings.read_seconds},
                {"validate_seconds", timings.validate_seconds},
                {"geometry_seconds", timings.geometry_seconds},
                {"detect_seconds", timings.detect_seconds},
                {"total_seconds", timings.total_seconds}}}};
  json source_info = json::object();
  if (!source.empty() && source != "-") source_info["source"] = source;
  if (!model.title.empty()) source_info["title"] = model.title;
  if (!source_info.empty()) result["model"] = source_info;
  return result;
}

}  // namespace rbla::io
