#include "io/detection_json.hpp"

namespace rbla::io {

using nlohmann::json;

namespace {

json spread_json(const model::Spread& s, double scale) {
  return json{{"count", s.count}, {"min", s.min / scale}, {"median", s.median / scale}, {"max", s.max / scale}};
}

json near_miss_json(const model::NearMiss& miss, const model::Model& m) {
  const double l = m.units.length_to_m;
  return json{{"blocks", {m.blocks[miss.block_a].id, m.blocks[miss.block_b].id}},
              {"faces", {miss.face_a, miss.face_b}},
              {"distance", miss.distance / l},
              {"distance_tolerance", miss.distance_tolerance / l},
              {"angle", miss.angle_degrees},
              {"overlap_area", miss.overlap_area / (l * l)}};
}

}  // namespace

json detection_json(const model::Model& m) {
  const model::DetectionSummary& s = m.detection_summary;
  if (!s.ran) return nullptr;
  const double l = m.units.length_to_m;
  json tolerances{{"rule", s.per_joint ? "per_joint" : "fixed"}, {"angle", s.angle_tolerance_degrees}};
  if (s.per_joint) {
    tolerances["joint_tolerance"] = s.joint_tolerance;
    tolerances["clearance_limit"] = s.clearance_limit / l;
  } else {
    tolerances["distance"] = s.fixed_distance / l;
  }
  tolerances["distance_used"] = spread_json(s.distance_tolerances, l);
  json near = json::array();
  for (const model::NearMiss& miss : m.near_misses) near.push_back(near_miss_json(miss, m));
  return json{{"tolerances", tolerances},
              {"num_interfaces", s.interfaces_found},
              {"num_merged_faces", s.merged_faces},
              {"gaps", spread_json(s.gaps, l)},
              {"largest_gap_fraction", s.largest_gap_fraction},
              {"angles", spread_json(s.angles, 1.0)},
              {"num_near_misses", s.near_misses_total},
              {"near_misses", near}};
}

}  // namespace rbla::io
