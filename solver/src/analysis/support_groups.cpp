#include "analysis/support_groups.hpp"

#include "analysis/text.hpp"
#include "model/errors.hpp"

#include <algorithm>
#include <cmath>

namespace rbla::analysis {
namespace {

std::string group_words(const model::Model& m, const std::vector<int>& blocks) {
  std::string words;
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    words += (k == 0 ? "'" : k + 1 == blocks.size() ? " and '" : ", '") + m.blocks[blocks[k]].id + "'";
  }
  return (blocks.size() == 1 ? "the support " : "the supports ") + words;
}

/// The group with the largest R / R0 found, among those whose search collapsed.
std::optional<int> top_group(const std::vector<SupportGroupSearch>& groups) {
  std::optional<int> top;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const WorstSettlement& s = groups[g].search;
    if (s.verdict != Verdict::Collapse || !s.ratio) continue;
    if (!top || *s.ratio > *groups[*top].search.ratio) top = static_cast<int>(g);
  }
  return top;
}

/// The other groups that may reach the top group's value: no certified bound below it by more
/// than the searches' relative tolerance (each value is only known to it; mirror-image groups
/// differ by rounding).
std::vector<int> contenders_of(const std::vector<SupportGroupSearch>& groups, int top, double tolerance) {
  const double value = *groups[top].search.ratio;
  std::vector<int> contenders;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    if (static_cast<int>(g) == top) continue;
    const WorstSettlement& s = groups[g].search;
    const bool bounded_below = s.verdict == Verdict::Collapse && s.upper_bound &&
                               *s.upper_bound < value - tolerance * std::abs(value);
    if (!bounded_below) contenders.push_back(static_cast<int>(g));
  }
  return contenders;
}

void conclude(const model::Model& m, double tolerance, SupportGroupRanking& r) {
  r.most_harmful = top_group(r.groups);
  if (!r.most_harmful) {
    r.verdict_text = "No candidate group reached a collapse along any direction tried: " +
                     r.groups.front().search.verdict_text;
    return;
  }
  const SupportGroupSearch& top = r.groups[*r.most_harmful];
  r.contenders = contenders_of(r.groups, *r.most_harmful, tolerance);
  r.certain = r.contenders.empty();
  r.verdict_text = "Most harmful of " + std::to_string(r.groups.size()) + " candidate groups: " +
                   group_words(m, top.blocks) + " settling, R / R0 = " + format(*top.search.ratio);
  if (r.certain) {
    r.verdict_text += "; every other group's largest R / R0 is certified below it by more than the tolerance (" +
                      format(100.0 * tolerance) + " %).";
    return;
  }
  r.verdict_text += "; not certain: ";
  for (std::size_t k = 0; k < r.contenders.size(); ++k) {
    const SupportGroupSearch& other = r.groups[r.contenders[k]];
    r.verdict_text += (k > 0 ? "; " : "") + group_words(m, other.blocks) +
                      (other.search.upper_bound ? " may reach " + format(*other.search.upper_bound)
                                                : std::string(" has no certified bound (") +
                                                      (other.search.verdict == Verdict::Collapse
                                                           ? std::string("non-associative friction or an unfinished search")
                                                           : other.search.verdict_text) +
                                                      ")");
  }
  r.verdict_text += ".";
}

/// One group's search; a refusal (R0 not positive over the cone, say) names the group.
WorstSettlement search_group(const model::Model& model, const std::vector<int>& group, const std::string& option,
                             const AnalysisOptions& options, const WorstSettlementSettings& settings) {
  const model::Model alone = settling_only(model, group, option);
  try {
    return find_worst_settlement(alone, options, settings);
  } catch (const model::ModelError& e) {
    std::vector<model::InputIssue> issues = e.issues();
    for (model::InputIssue& issue : issues) issue.message = "with " + group_words(model, group) + " settling: " + issue.message;
    issues.insert(issues.begin(), {option, "the candidate group of " + group_words(model, group) + " cannot be searched"});
    throw model::ModelError(issues);
  }
}

}  // namespace

model::Model settling_only(const model::Model& model, const std::vector<int>& blocks, const std::string& option) {
  model::Model m = model;
  for (int b : blocks) {
    if (!m.blocks[b].is_support()) {
      throw model::ModelError(option, "block '" + m.blocks[b].id + "' is not a support: only supports can settle");
    }
  }
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    if (!m.blocks[b].is_support()) continue;
    const bool settles = std::find(blocks.begin(), blocks.end(), static_cast<int>(b)) != blocks.end();
    m.blocks[b].role = settles ? model::BlockRole::MovingSupport : model::BlockRole::Fixed;
  }
  return m;
}

SupportGroupRanking rank_support_groups(const model::Model& model, const std::vector<std::vector<int>>& groups,
                                        const std::string& option, const AnalysisOptions& options,
                                        const WorstSettlementSettings& settings) {
  if (groups.empty()) throw model::ModelError(option, "no candidate group given");
  for (const auto& group : groups) {
    if (group.empty()) throw model::ModelError(option, "a candidate group names no block");
  }
  const auto start = Clock::now();
  SupportGroupRanking r;
  std::optional<double> best;
  for (const auto& group : groups) {
    SupportGroupSearch g{group, search_group(model, group, option, options, settings)};
    const bool leads = g.search.verdict == Verdict::Collapse && g.search.ratio && (!best || *g.search.ratio > *best);
    if (leads) {
      best = g.search.ratio;
      // Only the leader keeps its whole analysis: a model and a result per group would grow
      // with the number of groups.
      for (SupportGroupSearch& other : r.groups) {
        other.search.model_at_worst = model::Model{};
        other.search.at_worst = AnalysisResult{};
      }
    } else if (best || !r.groups.empty()) {
      g.search.model_at_worst = model::Model{};
      g.search.at_worst = AnalysisResult{};
    }
    r.groups.push_back(std::move(g));
  }
  conclude(model, settings.search.tolerance, r);
  r.seconds = seconds_since(start);
  return r;
}

}  // namespace rbla::analysis
