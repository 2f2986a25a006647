#include "model/model.hpp"

#include <cmath>

#include <algorithm>
#include <limits>
#include <sstream>
#include <tuple>
#include <utility>
#include <vector>

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

namespace {

/// The range along one axis of the largest group of blocks: the blocks' intervals [lo, hi],
/// sorted by lo, form one group while each begins within `gap` of the furthest end so far; the
/// group with the most blocks wins (the first of equals).
std::pair<double, double> main_group_range(std::vector<std::pair<double, double>>& intervals, double gap) {
  std::sort(intervals.begin(), intervals.end());
  std::pair<double, double> best = intervals.front(), group = intervals.front();
  std::size_t best_count = 0, count = 0;
  for (const auto& [lo, hi] : intervals) {
    if (count > 0 && lo > group.second + gap) {
      if (count > best_count) std::tie(best, best_count) = std::make_pair(group, count);
      group = {lo, hi};
      count = 0;
    }
    group.second = std::max(group.second, hi);
    ++count;
  }
  if (count > best_count) best = group;
  return best;
}

}  // namespace

/// Per axis, the range of the largest group of blocks whose intervals along the axis are
/// separated by no gap wider than kStructureGapBlocks median block sizes. A connected structure
/// has no such gap along any axis, so its box is its bounding box; a block kilometres away (a
/// survey marker of a georeferenced export) falls outside, and no longer makes every default
/// tolerance, derived from the diagonal, a thousand times that of the structure.
BoundingBox Model::structure_box() const {
  if (blocks.size() < 2) return bounding_box();
  std::vector<BoundingBox> boxes;
  boxes.reserve(blocks.size());
  for (const Block& block : blocks) boxes.push_back(bounding_box_of(block.vertices));
  const double gap = kStructureGapBlocks * median_block_size();
  BoundingBox box;
  std::vector<std::pair<double, double>> intervals(boxes.size());
  for (int axis = 0; axis < 3; ++axis) {
    for (std::size_t i = 0; i < boxes.size(); ++i) intervals[i] = {boxes[i].min[axis], boxes[i].max[axis]};
    std::tie(box.min[axis], box.max[axis]) = main_group_range(intervals, gap);
  }
  return box;
}

double Model::median_block_size() const {
  if (blocks.empty()) return 0.0;
  std::vector<double> sizes;
  sizes.reserve(blocks.size());
  for (const Block& block : blocks) sizes.push_back(bounding_box_of(block.vertices).diagonal());
  const auto middle = sizes.begin() + static_cast<std::ptrdiff_t>(sizes.size() / 2);
  std::nth_element(sizes.begin(), middle, sizes.end());
  return *middle;
}

double Model::distance_tolerance() const {
  if (detection.distance_tolerance) return *detection.distance_tolerance;
  return detection.relative_tolerance.value_or(kModelRelativeTolerance) * std::max(structure_box().diagonal(), 1e-300);
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
