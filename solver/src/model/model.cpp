#include "model/model.hpp"

#include <cmath>

#include <algorithm>
#include <limits>
#include <sstream>

namespace rbla::model {

std::string length_text(double metres, const Units& units, int digits) {
  std::ostringstream out;
  out.precision(digits);
  out << metres / units.length_to_m << " " << units.length_name;
  return out.str();
}

const char* to_string(BlockRole role) {
  switch (role) {
    case BlockRole::Free: return "free";
    case BlockRole::Fixed: return "fixed";
    case BlockRole::MovingSupport: return "moving_support";
  }
  return "?";
}

const char* to_string(AnalysisType value) {
  switch (value) {
    case AnalysisType::LoadMultiplier: return "load_multiplier";
    case AnalysisType::Settlement: return "settlement";
  }
  return "?";
}

const char* to_string(FrictionModel value) {
  switch (value) {
    case FrictionModel::Associative: return "associative";
    case FrictionModel::NonAssociative: return "non_associative";
  }
  return "?";
}

const char* to_string(ConeKind value) {
  switch (value) {
    case ConeKind::Exact: return "exact";
    case ConeKind::PyramidInscribed: return "pyramid_inscribed";
    case ConeKind::PyramidCircumscribed: return "pyramid_circumscribed";
  }
  return "?";
}

const char* to_string(Formulation value) {
  switch (value) {
    case Formulation::Auto: return "auto";
    case Formulation::ThreeD: return "3d";
    case Formulation::Planar: return "planar";
  }
  return "?";
}

BoundingBox bounding_box_of(const std::vector<Vec3>& points) {
  BoundingBox box;
  if (points.empty()) return box;
  box.min = box.max = points[0];
  for (const Vec3& v : points) {
    box.min = box.min.cwiseMin(v);
    box.max = box.max.cwiseMax(v);
  }
  return box;
}

BoundingBox Model::bounding_box() const {
  BoundingBox box;
  const double inf = std::numeric_limits<double>::infinity();
  box.min = Vec3::Constant(inf);
  box.max = Vec3::Constant(-inf);
  for (const Block& block : blocks) {
    for (const Vec3& v : block.vertices) {
      box.min = box.min.cwiseMin(v);
      box.max = box.max.cwiseMax(v);
    }
  }
  if (blocks.empty()) box.min = box.max = Vec3::Zero();
  return box;
}

std::size_t Model::num_contact_points() const {
  std::size_t count = 0;
  for (const ContactInterface& contact : interfaces) count += contact.polygon.size();
  return count;
}

double Model::distance_tolerance() const {
  if (detection.distance_tolerance) return *detection.distance_tolerance;
  return detection.relative_tolerance.value_or(kModelRelativeTolerance) * std::max(bounding_box().diagonal(), 1e-300);
}

std::pair<Vec3, Vec3> Model::horizontal_axes() const {
  const Vec3 up = -gravity.normalized();
  const Vec3 seed = std::abs(up.x()) > 0.9 ? Vec3::UnitY() : Vec3::UnitX();
  const Vec3 x = (seed - seed.dot(up) * up).normalized();
  return {x, up.cross(x)};
}

std::vector<std::vector<int>> Model::neighbours(bool through_supports) const {
  std::vector<std::vector<int>> out(blocks.size());
  for (const ContactInterface& contact : interfaces) {
    if (!through_supports && (blocks[contact.block_a].is_support() || blocks[contact.block_b].is_support())) continue;
    out[contact.block_a].push_back(contact.block_b);
    out[contact.block_b].push_back(contact.block_a);
  }
  return out;
}

namespace {

bool named(const std::string& id, const std::string& label, const std::string& name) {
  return id == name || (!label.empty() && label == name);
}

std::vector<int> picked_indices(const std::vector<bool>& picked) {
  std::vector<int> indices;
  for (std::size_t k = 0; k < picked.size(); ++k) {
    if (picked[k]) indices.push_back(static_cast<int>(k));
  }
  return indices;
}

/// Marks in `picked` the items (blocks or interfaces) whose id or label is one of `names`.
template <typename Items>
void pick_named(const Items& items, const std::vector<std::string>& names, std::vector<bool>& picked,
                std::vector<std::string>& unmatched) {
  for (const std::string& name : names) {
    bool found = false;
    for (std::size_t k = 0; k < items.size(); ++k) {
      if (!named(items[k].id, items[k].label, name)) continue;
      picked[k] = found = true;
    }
    if (!found) unmatched.push_back(name);
  }
}

}  // namespace

std::vector<int> Model::blocks_named(const std::vector<std::string>& names, std::vector<std::string>& unmatched) const {
  std::vector<bool> picked(blocks.size(), false);
  pick_named(blocks, names, picked, unmatched);
  return picked_indices(picked);
}

std::vector<int> Model::interfaces_named(const std::vector<std::string>& interface_names,
                                         const std::vector<std::string>& block_names,
                                         std::vector<std::string>& unmatched) const {
  std::vector<bool> picked(interfaces.size(), false);
  pick_named(interfaces, interface_names, picked, unmatched);
  for (int b : blocks_named(block_names, unmatched)) {
    for (std::size_t k = 0; k < interfaces.size(); ++k) {
      if (interfaces[k].block_a == b || interfaces[k].block_b == b) picked[k] = true;
    }
  }
  return picked_indices(picked);
}

}  // namespace rbla::model
