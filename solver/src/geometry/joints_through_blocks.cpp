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

/// A block S between A and B under joint ab: S touches A and B with contacts facing as ab does,
/// both overlapping ab. -1 when there is none.
int block_between(const std::vector<ContactInterface>& all, const std::vector<std::vector<int>>& of_block,
                  const std::map<std::pair<int, int>, std::vector<int>>& of_pair, int ab, double cos_angle) {
  const ContactInterface& joint = all[ab];
  const int a = joint.block_a, b = joint.block_b;
  const Vec3 n = joint.normal;  // out of a, into b
  for (const int as : of_block[a]) {
    const int s = other_block(all[as], a);
    if (as == ab || s == b || normal_out_of(all[as], a).dot(n) < cos_angle) continue;
    if (!overlap_along(all[as], joint, joint)) continue;
    const auto sb = of_pair.find(std::minmax(s, b));
    if (sb == of_pair.end()) continue;
    for (const int k : sb->second) {
      if (normal_out_of(all[k], s).dot(n) >= cos_angle && overlap_along(all[k], joint, joint)) return s;
    }
  }
  return -1;
}

}  // namespace

std::vector<int> blocks_between(const std::vector<ContactInterface>& given,
                                const std::vector<ContactInterface>& detected, double angle_degrees) {
  std::vector<ContactInterface> all = given;
  all.insert(all.end(), detected.begin(), detected.end());
  int blocks = 0;
  for (const ContactInterface& c : all) blocks = std::max({blocks, c.block_a + 1, c.block_b + 1});
  std::vector<std::vector<int>> of_block(static_cast<std::size_t>(blocks));
  std::map<std::pair<int, int>, std::vector<int>> of_pair;
  for (int k = 0; k < static_cast<int>(all.size()); ++k) {
    of_block[all[k].block_a].push_back(k);
    of_block[all[k].block_b].push_back(k);
    of_pair[std::minmax(all[k].block_a, all[k].block_b)].push_back(k);
  }
  const double cos_angle = std::cos(model::radians(angle_degrees));
  std::vector<int> between(detected.size(), -1);
  for (std::size_t k = 0; k < detected.size(); ++k) {
    between[k] = block_between(all, of_block, of_pair, static_cast<int>(given.size() + k), cos_angle);
  }
  return between;
}

}  // namespace rbla::geometry
