// Which of several candidate groups of supports is the most harmful to settle
// (docs/worst_settlement.md, "Candidate groups"): for each group, the model with only that group
// settling (every other support fixed) and its most harmful direction (find_worst_settlement);
// the groups are ranked by that largest R / R0.
//
// The ranking is certain when the top group's R / R0 (a value found, so a lower bound on its
// largest) exceeds every other group's certified upper bound by more than the searches' relative
// tolerance: associative friction, every search bracketed. Otherwise the groups whose bound
// reaches that far are named: any of them may be as harmful.
#pragma once

#include "analysis/worst_settlement.hpp"

#include <optional>
#include <string>
#include <vector>

namespace rbla::analysis {

struct SupportGroupSearch {
  std::vector<int> blocks;  ///< indices of the supports that settle
  /// The group's search; its model_at_worst and at_worst are kept for the most harmful group only.
  WorstSettlement search;
};

struct SupportGroupRanking {
  std::vector<SupportGroupSearch> groups;  ///< in the order given
  std::optional<int> most_harmful;         ///< index into groups: the largest R / R0 found
  bool certain = false;                    ///< no other group can reach it (see above)
  std::vector<int> contenders;             ///< other groups that may be as harmful
  std::string verdict_text;                ///< one sentence for people
  double seconds = 0.0;
};

/// `model` with exactly the supports `blocks` settling and every other support fixed. Throws
/// model::ModelError (naming `option`) when a block is not a support.
model::Model settling_only(const model::Model& model, const std::vector<int>& blocks, const std::string& option);

/// Searches each group's most harmful direction and ranks the groups. Throws model::ModelError
/// (naming `option`) for an empty list, an empty group or a block that is not a support, and as
/// find_worst_settlement does.
SupportGroupRanking rank_support_groups(const model::Model& model, const std::vector<std::vector<int>>& groups,
                                        const std::string& option, const AnalysisOptions& options = {},
                                        const WorstSettlementSettings& settings = {});

}  // namespace rbla::analysis
