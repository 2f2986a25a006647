#include "io/sensitivities_json.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace rbla::io {
namespace {

using nlohmann::json;

std::vector<std::pair<int, double>> by_magnitude(std::vector<std::pair<int, double>> entries) {
  std::stable_sort(entries.begin(), entries.end(),
                   [](const auto& a, const auto& b) { return std::abs(a.second) > std::abs(b.second); });
  return entries;
}

}  // namespace

json sensitivities_json(const model::Model& model, const analysis::Sensitivities& s) {
  json interfaces = json::array();
  for (const auto& [k, value] : by_magnitude(s.interface_friction)) {
    interfaces.push_back({{"id", model.interfaces[k].id}, {"d_load_multiplier_d_friction", value}});
  }
  // Unit weight: kN/m^3 inside, user force / user length^3 outside.
  const double l = model.units.length_to_m, f = model.units.force_to_kN;
  const double per_user_unit_weight = f / (l * l * l);
  json blocks = json::array();
  for (const auto& [b, value] : by_magnitude(s.block_unit_weight)) {
    blocks.push_back({{"id", model.blocks[b].id}, {"d_load_multiplier_d_unit_weight", value * per_user_unit_weight}});
  }
  return json{{"d_load_multiplier_d_friction_factor", s.friction_factor},
              {"interfaces", interfaces},
              {"blocks", blocks}};
}

}  // namespace rbla::io
