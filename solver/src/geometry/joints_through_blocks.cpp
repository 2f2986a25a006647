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

/// A block S between A and B under joint ab, seen from A: S touches A with a contact facing as ab
/// does and overlapping it, and touches B the same way (or S and B are both supports). -1 when
/// there is none.
int block_between_from(const model::Model& m, const std::vector<ContactInterface>& all,
                       const std::vector<std::vector<int>>& of_block,
                       const std::map<std::pair<int, int>, std::vector<int>>& of_pair, int ab, int a, int b,
                       double gap, double cos_angle) {
  const ContactInterface& joint = all[ab];
  const Vec3 n = normal_out_of(joint, a);
  const double level = height_along(joint, n), apart = 0.25 * gap;
  for (const int as : of_block[a]) {
    const int s = other_block(all[as], a);
    if (as == ab || s == b || normal_out_of(all[as], a).dot(n) < cos_angle) continue;
    if (level - height_along(all[as], n) < apart || !overlap_along(all[as], joint, joint)) continue;
    if (m.blocks[s].is_support() && m.blocks[b].is_support()) return s;
    const auto sb = of_pair.find(std::minmax(s, b));
    if (sb == of_pair.end()) continue;
    for (const int k : sb->second) {
      if (normal_out_of(all[k], s).dot(n) >= cos_angle && height_along(all[k], n) - level >= apart &&
          overlap_along(all[k], joint, joint))
        return s;
    }
  }
  return -1;
}

/// Either way round: A's joints are searched for S (supports form no joints with each other, so the
/// side that is not a support must be A).
int block_between(const model::Model& m, const std::vector<ContactInterface>& all,
                  const std::vector<std::vector<int>>& of_block,
                  const std::map<std::pair<int, int>, std::vector<int>>& of_pair, int ab, double gap,
                  double cos_angle) {
  const ContactInterface& joint = all[ab];
  for (const bool reversed : {false, true}) {
    const int a = reversed ? joint.block_b : joint.block_a, b = reversed ? joint.block_a : joint.block_b;
    const int s = block_between_from(m, all, of_block, of_pair, ab, a, b, gap, cos_angle);
    if (s >= 0) return s;
  }
  return -1;
}

}  // namespace

std::vector<int> blocks_between(const model::Model& m, const std::vector<ContactInterface>& detected,
                                const std::vector<bool>& apart, const std::vector<double>& gaps,
                                double angle_degrees) {
  std::vector<ContactInterface> all = m.interfaces;
  const std::size_t given = all.size();
  all.insert(all.end(), detected.begin(), detected.end());
  std::vector<std::vector<int>> of_block(m.blocks.size());
  std::map<std::pair<int, int>, std::vector<int>> of_pair;
  for (int k = 0; k < static_cast<int>(all.size()); ++k) {
    of_block[all[k].block_a].push_back(k);
    of_block[all[k].block_b].push_back(k);
    of_pair[std::minmax(all[k].block_a, all[k].block_b)].push_back(k);
  }
  const double cos_angle = std::cos(model::radians(angle_degrees));
  std::vector<int> between(detected.size(), -1);
  for (std::size_t k = 0; k < detected.size(); ++k) {
    if (apart[k]) between[k] = block_between(m, all, of_block, of_pair, static_cast<int>(given + k), gaps[k], cos_angle);
  }
  return between;
}

}  // namespace rbla::geometry
