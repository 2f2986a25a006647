#include "geometry/joints_through_blocks.hpp"

#include "geometry/polygon2d.hpp"
#include "model/angles.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace rbla::geometry {

namespace {

using model::ContactInterface;
using model::Vec3;

/// The contact's normal pointing out of `block` (a contact's normal points from block_a into block_b).
Vec3 normal_out_of(const ContactInterface& c, int block) { return c.block_a == block ? c.normal : Vec3(-c.normal); }

int other_block(const ContactInterface& c, int block) { return c.block_a == block ? c.block_b : c.block_a; }

/// The contact's polygon in the frame (t1, t2) of `frame`, counter-clockwise.
Polygon2 seen_along(const ContactInterface& c, const ContactInterface& frame) {
  Polygon2 p;
  p.reserve(c.polygon.size());
  for (const Vec3& x : c.polygon) p.emplace_back(x.dot(frame.tangent1), x.dot(frame.tangent2));
  if (signed_area(p) < 0.0) std::reverse(p.begin(), p.end());
  return p;
}

/// The mean height of a contact's corners along n.
double height_along(const ContactInterface& c, const Vec3& n) {
  double sum = 0.0;
  for (const Vec3& x : c.polygon) sum += x.dot(n);
  return c.polygon.empty() ? 0.0 : sum / static_cast<double>(c.polygon.size());
}

/// Whether a and b overlap, seen along `frame`'s normal, by more than a hundredth of the smaller
/// of the two (slivers along shared edges of noisy geometry are not an overlap).
bool overlap_along(const ContactInterface& a, const ContactInterface& b, const ContactInterface& frame) {
  const double smaller = std::min(a.area, b.area);
  if (!(smaller > 0.0)) return false;
  const double snap = 1e-6 * std::sqrt(std::max(a.area, b.area));
  double common = 0.0;
  for (const Polygon2& piece : intersect(seen_along(a, frame), seen_along(b, frame), snap)) {
    common += std::abs(signed_area(piece));
  }
  return common > 0.01 * smaller;
}

/// The model's own contacts and the detected ones, by block and by block pair (pointers: the
/// contacts are not copied).
class ContactGraph {
 public:
  ContactGraph(std::size_t blocks, const std::vector<ContactInterface>& given,
               const std::vector<ContactInterface>& detected)
      : of_block_(blocks) {
    for (const auto* list : {&given, &detected}) {
      for (const ContactInterface& c : *list) add(c);
    }
  }
  const ContactInterface& operator[](int k) const { return *all_[k]; }
  const std::vector<int>& of_block(int block) const { return of_block_[block]; }
  const std::vector<int>* of_pair(int a, int b) const {
    const auto found = of_pair_.find(std::minmax(a, b));
    return found == of_pair_.end() ? nullptr : &found->second;
  }

 private:
  void add(const ContactInterface& c) {
    const int k = static_cast<int>(all_.size());
    all_.push_back(&c);
    of_block_[c.block_a].push_back(k);
    of_block_[c.block_b].push_back(k);
    of_pair_[std::minmax(c.block_a, c.block_b)].push_back(k);
  }
  std::vector<const ContactInterface*> all_;
  std::vector<std::vector<int>> of_block_;
  std::map<std::pair<int, int>, std::vector<int>> of_pair_;
};

/// How far from the plane of A-B (as a fraction of its gap) S's joints must lie: a fifth. Two
/// layers of thickness t between A and B put the joint of each across the other (itself a joint
/// through a block) a quarter of the 2t gap from A-B's plane: at a quarter, 7 mm tiles stacked
/// five high were joined to the tile three above (found while testing the clearance limit).
constexpr double kApartFromPlane = 0.2;

/// A block S between A and B under joint ab, seen from A: S touches A with a contact facing as ab
/// does, overlapping it and kApartFromPlane of its gap or more nearer A than its plane, and touches B the
/// same way from the other side (or S and B are both supports). -1 when there is none.
int block_between_from(const model::Model& m, const ContactGraph& graph, int ab, int a, int b, double gap,
                       double cos_angle) {
  const ContactInterface& joint = graph[ab];
  const Vec3 n = normal_out_of(joint, a);
  const double level = height_along(joint, n), apart = kApartFromPlane * gap;
  for (const int as : graph.of_block(a)) {
    const int s = other_block(graph[as], a);
    if (as == ab || s == b || normal_out_of(graph[as], a).dot(n) < cos_angle) continue;
    if (level - height_along(graph[as], n) < apart || !overlap_along(graph[as], joint, joint)) continue;
    if (m.blocks[s].is_support() && m.blocks[b].is_support()) return s;
    const std::vector<int>* sb = graph.of_pair(s, b);
    if (!sb) continue;
    for (const int k : *sb) {
      if (normal_out_of(graph[k], s).dot(n) >= cos_angle && height_along(graph[k], n) - level >= apart &&
          overlap_along(graph[k], joint, joint))
        return s;
    }
  }
  return -1;
}

/// Either way round: A's joints are searched for S (supports form no joints with each other, so the
/// side that is not a support must be A).
int block_between(const model::Model& m, const ContactGraph& graph, int ab, double gap, double cos_angle) {
  const ContactInterface& joint = graph[ab];
  for (const bool reversed : {false, true}) {
    const int a = reversed ? joint.block_b : joint.block_a, b = reversed ? joint.block_a : joint.block_b;
    const int s = block_between_from(m, graph, ab, a, b, gap, cos_angle);
    if (s >= 0) return s;
  }
  return -1;
}

}  // namespace

std::vector<int> blocks_between(const model::Model& m, const std::vector<ContactInterface>& detected,
                                const std::vector<bool>& apart, const std::vector<double>& gaps,
                                double angle_degrees) {
  const ContactGraph graph(m.blocks.size(), m.interfaces, detected);
  const int given = static_cast<int>(m.interfaces.size());
  const double cos_angle = std::cos(model::radians(angle_degrees));
  std::vector<int> between(detected.size(), -1);
  for (std::size_t k = 0; k < detected.size(); ++k) {
    if (apart[k]) between[k] = block_between(m, graph, given + static_cast<int>(k), gaps[k], cos_angle);
  }
  return between;
}

}  // namespace rbla::geometry
