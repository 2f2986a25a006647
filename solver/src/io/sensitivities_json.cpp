#include "io/sensitivities_json.hpp"

#include <algorithm>
#include <cmath>
#include <string>
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
  // The value differentiated: alpha (dimensionless), or the base reaction (kN inside, the
  // model's force unit outside).
  const bool reaction = s.quantity == analysis::SensitivityOf::BaseReaction;
  const std::string name = reaction ? "base_reaction" : "load_multiplier";
  const double f = model.units.force_to_kN;
  const double value_unit = reaction ? 1.0 / f : 1.0;
  json interfaces = json::array();
  for (const auto& [k, value] : by_magnitude(s.interface_friction)) {
    interfaces.push_back({{"id", model.interfaces[k].id}, {"d_" + name + "_d_friction", value * value_unit}});
  }
  // Unit weight: kN/m^3 inside, the model's units.unit_weight outside, the unit its unit weights
  // are given in (kN/m3 in a model drawn in mm is common: per kN/mm^3 was 1e9 times off).
  const double per_user_unit_weight = value_unit * model.units.unit_weight_to_kN_m3;
  json blocks = json::array();
  for (const auto& [b, value] : by_magnitude(s.block_unit_weight)) {
    blocks.push_back({{"id", model.blocks[b].id}, {"d_" + name + "_d_unit_weight", value * per_user_unit_weight}});
  }
  return json{{"d_" + name + "_d_friction_factor", s.friction_factor * value_unit},
              {"interfaces", interfaces},
              {"blocks", blocks}};
}

}  // namespace rbla::io
