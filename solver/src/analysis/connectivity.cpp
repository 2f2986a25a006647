#include "analysis/connectivity.hpp"

#include "analysis/mechanism.hpp"
#include "analysis/solve_steps.hpp"

#include <algorithm>
#include <numeric>

namespace rbla::analysis {

namespace {

/// Union-find over block indices, with path halving.
struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(int a, int b) { parent[find(a)] = find(b); }
};

/// Whether the dead loads of `blocks` (self-weight and dead point loads) have a resultant: a
/// force, or a moment about the first block's centroid, above round-off of the loads' sizes.
bool carries_dead_load(const model::Model& m, const std::vector<int>& blocks) {
  std::vector<bool> in_group(m.blocks.size(), false);
  for (int b : blocks) in_group[b] = true;
  const Vec3 origin = m.blocks[blocks.front()].centroid;
  Vec3 force = Vec3::Zero(), moment = Vec3::Zero();
  double force_size = 0.0, moment_size = 0.0;
  auto add = [&](const Vec3& f, const Vec3& point, const Vec3& couple) {
    force += f;
    moment += (point - origin).cross(f) + couple;
    force_size += f.norm();
    moment_size += (point - origin).norm() * f.norm() + couple.norm();
  };
  for (int b : blocks) add(m.blocks[b].weight() * m.gravity, m.blocks[b].centroid, Vec3::Zero());
  for (const model::PointLoad& load : m.dead_loads) {
    if (in_group[load.block]) add(load.force, load.point, load.moment);
  }
  constexpr double kRoundOff = 1e-9;
  return force.norm() > kRoundOff * force_size || moment.norm() > kRoundOff * moment_size;
}

/// The near misses of interface detection, when there were any: joints a looser tolerance would
/// have found, which is what a user whose blocks hang in the air looks for first.
/// The near misses of interface detection. At the unsupported blocks they point to joints the
/// geometry misses (faces that cross or gape beyond the tolerances) rather than to a structure that
/// falls, and the sentence says so.
std::string near_miss_text(const Connectivity& connectivity) {
  if (connectivity.num_near_misses == 0) return "";
  const std::size_t n = connectivity.num_near_misses, at = connectivity.near_misses_at_groups.size();
  const std::string where = at > 0 ? ": probably joints the geometry misses, not a collapse; see " : ": see ";
  return " Interface detection rejected " + std::to_string(n) + (n == 1 ? " face pair" : " face pairs") +
         " that came close (near misses), " + std::to_string(at) + " of them at these blocks" + where +
         "connectivity.near_misses in the result and the tolerances under /detection.";
}

}  // namespace

Connectivity check_connectivity(const model::Model& m) {
  Connectivity result;
  result.checked = true;
  result.num_near_misses = m.near_misses.size();
  const std::size_t n = m.blocks.size();
  DisjointSets sets(n);
  for (const auto& contact : m.interfaces) {
    if (!m.blocks[contact.block_a].is_support() && !m.blocks[contact.block_b].is_support()) {
      sets.join(contact.block_a, contact.block_b);
    }
  }
  std::vector<bool> supported(n, false);
  for (const auto& contact : m.interfaces) {
    const bool a_support = m.blocks[contact.block_a].is_support();
    const bool b_support = m.blocks[contact.block_b].is_support();
    if (a_support != b_support) supported[sets.find(a_support ? contact.block_b : contact.block_a)] = true;
  }
  std::vector<int> group_of_root(n, -1);
  for (std::size_t b = 0; b < n; ++b) {
    if (m.blocks[b].is_support()) continue;
    const int root = sets.find(static_cast<int>(b));
    if (supported[root]) continue;
    if (group_of_root[root] < 0) {
      group_of_root[root] = static_cast<int>(result.groups.size());
      result.groups.emplace_back();
    }
    result.groups[group_of_root[root]].blocks.push_back(static_cast<int>(b));
  }
  for (UnsupportedGroup& group : result.groups) {
    group.touches_nothing = group.blocks.size() == 1;
    group.carries_dead_load = carries_dead_load(m, group.blocks);
  }
  std::stable_sort(result.groups.begin(), result.groups.end(),
                   [](const UnsupportedGroup& a, const UnsupportedGroup& b) { return a.blocks.size() > b.blocks.size(); });
  std::vector<bool> in_group(n, false);
  for (const UnsupportedGroup& group : result.groups) {
    for (int b : group.blocks) in_group[b] = true;
  }
  for (std::size_t k = 0; k < m.near_misses.size(); ++k) {
    const model::NearMiss& miss = m.near_misses[k];
    const bool at_a = miss.block_a >= 0 && miss.block_a < static_cast<int>(n) && in_group[miss.block_a];
    const bool at_b = miss.block_b >= 0 && miss.block_b < static_cast<int>(n) && in_group[miss.block_b];
    if (at_a || at_b) result.near_misses_at_groups.push_back(static_cast<int>(k));
  }
  return result;
}

void falling_groups_mechanism(const model::Model& m, const Connectivity& connectivity, Mechanism& mechanism) {
  mechanism.normalisation = Normalisation::MaxTranslation;
  mechanism.blocks.assign(m.blocks.size(), BlockMotion{});
  for (const UnsupportedGroup& group : connectivity.groups) {
    if (!group.carries_dead_load) continue;
    for (int b : group.blocks) mechanism.blocks[b].translation = m.units.length_to_m * m.gravity;
  }
  fill_interfaces(m, {}, true, mechanism, MotionKind::Certificate);
}

std::string unsupported_verdict_text(const model::Model& m, const Connectivity& connectivity) {
  std::vector<int> falling, alone;
  std::size_t groups = 0;
  for (const UnsupportedGroup& group : connectivity.groups) {
    if (!group.carries_dead_load) continue;
    ++groups;
    falling.insert(falling.end(), group.blocks.begin(), group.blocks.end());
    if (group.touches_nothing) alone.push_back(group.blocks.front());
  }
  std::sort(falling.begin(), falling.end());
  const std::size_t n = falling.size();
  if (n == 1 && alone.size() == 1) {
    return "Cannot stand as modelled: block '" + m.blocks[falling.front()].id +
           "' touches nothing, so no interface joins it to a support." + near_miss_text(connectivity);
  }
  std::string text = "Cannot stand as modelled: " + std::to_string(n) + (n == 1 ? " block is" : " blocks are") +
                     " not connected to any support by interfaces: " + quoted_block_ids(m, falling, 10);
  const std::size_t joined = groups - alone.size();
  std::string parts;
  if (joined > 0) {
    parts = std::to_string(joined) + (joined == 1 ? " group" : " groups") + " of blocks joined only to each other";
  }
  if (!alone.empty()) {
    parts += (parts.empty() ? "" : "; ") + quoted_block_ids(m, alone, 5) + (alone.size() == 1 ? " touches" : " touch") +
             " nothing";
  }
  return text + " (" + parts + ")." + near_miss_text(connectivity);
}

}  // namespace rbla::analysis
