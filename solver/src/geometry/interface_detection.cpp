#include "geometry/interface_detection.hpp"

#include "geometry/polygon2d.hpp"
#include "geometry/polyhedron.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

namespace rbla::geometry {

using model::Vec3;

void local_frame(const Vec3& normal, Vec3& tangent1, Vec3& tangent2) {
  const Vec3 a = normal.cwiseAbs();
  Vec3 axis = Vec3::UnitX();
  if (a.y() < a.x() && a.y() <= a.z()) axis = Vec3::UnitY();
  else if (a.z() < a.x() && a.z() < a.y()) axis = Vec3::UnitZ();
  tangent1 = (axis - axis.dot(normal) * normal).normalized();
  tangent2 = normal.cross(tangent1);
}

namespace {

struct Box {
  Vec3 min, max;
};

struct FaceRecord {
  FaceGeometry geometry;
  Box box;
};

bool overlaps(const Box& a, const Box& b, double pad) {
  return (a.min.array() <= b.max.array() + pad).all() && (b.min.array() <= a.max.array() + pad).all();
}

Box box_of(const std::vector<Vec3>& points, const std::vector<int>& indices) {
  Box box{points[indices[0]], points[indices[0]]};
  for (int i : indices) {
    box.min = box.min.cwiseMin(points[i]);
    box.max = box.max.cwiseMax(points[i]);
  }
  return box;
}

}  // namespace

std::vector<model::ContactInterface> detect_interfaces(const model::Model& model, double tolerance,
                                                        const model::DetectionSettings& settings,
                                                        const std::vector<std::pair<int, int>>& skip_pairs,
                                                        DetectionStats* stats) {
  const int num_blocks = static_cast<int>(model.blocks.size());
  std::vector<Box> block_boxes(num_blocks);
  std::vector<std::vector<FaceRecord>> faces(num_blocks);
  for (int b = 0; b < num_blocks; ++b) {
    const model::Block& block = model.blocks[b];
    std::vector<int> all(block.vertices.size());
    std::iota(all.begin(), all.end(), 0);
    block_boxes[b] = box_of(block.vertices, all);
    faces[b].reserve(block.faces.size());
    for (const auto& face : block.faces) {
      faces[b].push_back({face_geometry(block.vertices, face), box_of(block.vertices, face)});
    }
  }

  // Broad phase: sweep along the axis with the largest extent.
  const model::BoundingBox extent = model.bounding_box();
  int axis = 0;
  (extent.max - extent.min).maxCoeff(&axis);
  std::vector<int> order(num_blocks);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return block_boxes[a].min[axis] < block_boxes[b].min[axis] ||
           (block_boxes[a].min[axis] == block_boxes[b].min[axis] && a < b);
  });
  std::vector<std::pair<int, int>> candidates;
  for (int i = 0; i < num_blocks; ++i) {
    const int a = order[i];
    for (int j = i + 1; j < num_blocks; ++j) {
      const int b = order[j];
      if (block_boxes[b].min[axis] > block_boxes[a].max[axis] + tolerance) break;
      if (model.blocks[a].is_support() && model.blocks[b].is_support()) continue;
      if (!overlaps(block_boxes[a], block_boxes[b], tolerance)) continue;
      candidates.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(candidates.begin(), candidates.end());  // deterministic output order
  const std::set<std::pair<int, int>> skip(skip_pairs.begin(), skip_pairs.end());

  const double cos_limit = std::cos(settings.angle_tolerance_degrees * M_PI / 180.0);
  std::vector<model::ContactInterface> found;
  std::size_t face_pairs_tested = 0;
  for (const auto& [a, b] : candidates) {
    if (skip.count({a, b})) continue;
    for (const FaceRecord& fa : faces[a]) {
      if (fa.geometry.area <= 0.0) continue;
      for (const FaceRecord& fb : faces[b]) {
        if (fb.geometry.area <= 0.0) continue;
        if (fa.geometry.normal.dot(fb.geometry.normal) > -cos_limit) continue;
        if (!overlaps(fa.box, fb.box, tolerance)) continue;
        const Vec3 gap = fb.geometry.centroid - fa.geometry.centroid;
        if (std::abs(fa.geometry.normal.dot(gap)) > tolerance ||
            std::abs(fb.geometry.normal.dot(gap)) > tolerance) {
          continue;
        }
        ++face_pairs_tested;
        // Mid-plane of the two faces; the normal points out of block a into block b.
        const Vec3 normal = (fa.geometry.normal - fb.geometry.normal).normalized();
        Vec3 t1, t2;
        local_frame(normal, t1, t2);
        const double offset = normal.dot(0.5 * (fa.geometry.centroid + fb.geometry.centroid));
        auto project = [&](const model::Block& block, const std::vector<int>& face_indices) {
          Polygon2 polygon;
          polygon.reserve(face_indices.size());
          for (int i : face_indices) polygon.emplace_back(block.vertices[i].dot(t1), block.vertices[i].dot(t2));
          return polygon;
        };
        const std::size_t ia = &fa - faces[a].data();
        const std::size_t ib = &fb - faces[b].data();
        const Polygon2 pa = project(model.blocks[a], model.blocks[a].faces[ia]);
        const Polygon2 pb = project(model.blocks[b], model.blocks[b].faces[ib]);
        const double min_area = settings.min_area_fraction * std::min(fa.geometry.area, fb.geometry.area);
        for (const Polygon2& piece : intersect(pa, pb, tolerance, min_area)) {
          model::ContactInterface contact;
          contact.block_a = a;
          contact.block_b = b;
          contact.normal = normal;
          contact.tangent1 = t1;
          contact.tangent2 = t2;
          contact.detected = true;
          contact.friction = model.default_friction;
          contact.polygon.reserve(piece.size());
          for (const Point2& p : piece) contact.polygon.push_back(offset * normal + p.x() * t1 + p.y() * t2);
          const double area = std::abs(signed_area(piece));
          contact.area = area;
          Vec3 weighted = Vec3::Zero();
          double total = 0.0;
          for (std::size_t k = 1; k + 1 < piece.size(); ++k) {
            const double tri = 0.5 * ((piece[k] - piece[0]).x() * (piece[k + 1] - piece[0]).y() -
                                      (piece[k] - piece[0]).y() * (piece[k + 1] - piece[0]).x());
            weighted += tri * (contact.polygon[0] + contact.polygon[k] + contact.polygon[k + 1]) / 3.0;
            total += tri;
          }
          contact.centroid = total != 0.0 ? Vec3(weighted / total) : contact.polygon[0];
          found.push_back(std::move(contact));
        }
      }
    }
  }
  if (stats) {
    stats->candidate_block_pairs = candidates.size();
    stats->face_pairs_tested = face_pairs_tested;
    stats->interfaces_found = found.size();
  }
  return found;
}

}  // namespace rbla::geometry
