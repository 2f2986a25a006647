// Which candidate group of supports is the most harmful to settle (analysis/support_groups.hpp),
// against the closed form of a block spanning two supports.
//
// A block [0, L] x [0, 1] x [0, h] of weight W rests on a left support under [0, a] and a right
// one under [b, L], a < L/2 < b. When one support settles vertically the block turns about the
// inner edge of the other, and the settling support's reaction at collapse is the one that
// balances the weight about that edge (tests/validation/test_worst_settlement.cpp):
//     right settling: N*_R = W (L/2 - a) / (L - a),    left settling: N*_L = W (b - L/2) / b.
// A tilted settlement only lowers R / R0 (the same file: R / R0 = (N* - mu tan(theta) ...) / R0),
// so each group's most harmful direction is vertical and its harm N* / R0, with R0 the reaction
// on that support before settlement. Mirror-symmetric supports (b = L - a) harm alike: no ranking
// between them can be certain.
#include "analysis/support_groups.hpp"
#include "validation_helpers.hpp"
#include "model/angles.hpp"

#include <string>
#include <vector>

namespace rbla::validation {
namespace {

using rbla::analysis::SupportGroupRanking;

using rbla::model::kPi;

json spanning_block(double a, double b, double L, double h) {
  json blocks = json::array({box_block("left", -0.5, -0.5, -0.5, a, 1.5, 0.0, "fixed"),
                             box_block("right", b, -0.5, -0.5, L + 0.5, 1.5, 0.0, "moving_support"),
                             box_block("B", 0.0, 0.0, 0.0, L, 1.0, h)});
  json model = model_with(blocks);
  model["defaults"] = {{"unit_weight", 18.0}, {"friction", 0.6}};
  model["analysis"] = {{"type", "settlement"}, {"formulation", "3d"}};
  return model;
}

SupportGroupRanking rank(const model::Model& m) {
  const int left = 0, right = 1;
  rbla::analysis::WorstSettlementSettings settings;
  settings.cone_angle = 20.0 * kPi / 180.0;
  return rbla::analysis::rank_support_groups(m, {{left}, {right}}, "groups", {}, settings);
}

const rbla::analysis::SettlementEvaluation& worst_of(const rbla::analysis::WorstSettlement& w) {
  return w.evaluations.at(static_cast<std::size_t>(w.worst.value()));
}

TEST(SupportGroups, TheSupportWhoseSettlementLeavesMoreOfItsReactionIsTheMostHarmful) {
  const double a = 1.0, b = 2.5, L = 4.0, h = 1.0;
  const auto loaded = rbla::io::load_model_text(spanning_block(a, b, L, h).dump());
  const double W = 18.0 * L * h;
  const double n_left = W * (b - L / 2) / b, n_right = W * (L / 2 - a) / (L - a);
  const SupportGroupRanking r = rank(loaded.model);
  ASSERT_EQ(r.groups.size(), 2u);
  const auto& left = r.groups[0].search;
  const auto& right = r.groups[1].search;
  ASSERT_EQ(left.verdict, Verdict::Collapse) << left.verdict_text;
  ASSERT_EQ(right.verdict, Verdict::Collapse) << right.verdict_text;
  ASSERT_TRUE(left.certified && right.certified);
  // Each group's worst direction is vertical, its R the closed form's.
  EXPECT_LT(worst_of(left).tilt, 1e-6);
  EXPECT_LT(worst_of(right).tilt, 1e-6);
  EXPECT_LT(relative_error(*worst_of(left).base_reaction, n_left), 1e-6) << *worst_of(left).base_reaction;
  EXPECT_LT(relative_error(*worst_of(right).base_reaction, n_right), 1e-6) << *worst_of(right).base_reaction;
  // The ranking is the order of N* / R0, with each group's own R0.
  const double harm_left = n_left / worst_of(left).initial_reaction;
  const double harm_right = n_right / worst_of(right).initial_reaction;
  ASSERT_GT(std::abs(harm_left - harm_right), 0.05) << harm_left << " vs " << harm_right;
  ASSERT_TRUE(r.most_harmful);
  EXPECT_EQ(*r.most_harmful, harm_right > harm_left ? 1 : 0) << r.verdict_text;
  EXPECT_TRUE(r.certain) << r.verdict_text;
  EXPECT_TRUE(r.contenders.empty());
  // Only the most harmful group keeps its analysis.
  const auto& top = r.groups[*r.most_harmful].search;
  const auto& other = r.groups[1 - *r.most_harmful].search;
  EXPECT_TRUE(top.at_worst.base_reaction.has_value());
  EXPECT_TRUE(other.model_at_worst.blocks.empty());
}

TEST(SupportGroups, MirroredSupportsHarmAlikeAndTheRankingSaysItIsNotCertain) {
  const double a = 1.0, L = 4.0, h = 1.0;
  const auto loaded = rbla::io::load_model_text(spanning_block(a, L - a, L, h).dump());
  const SupportGroupRanking r = rank(loaded.model);
  ASSERT_TRUE(r.most_harmful) << r.verdict_text;
  const double left = *r.groups[0].search.ratio, right = *r.groups[1].search.ratio;
  EXPECT_LT(relative_error(left, right), 1e-6) << left << " vs " << right;
  EXPECT_FALSE(r.certain) << r.verdict_text;
  ASSERT_EQ(r.contenders.size(), 1u);
  EXPECT_EQ(r.contenders[0], 1 - *r.most_harmful);
  EXPECT_NE(r.verdict_text.find("not certain"), std::string::npos) << r.verdict_text;
}

TEST(SupportGroups, EachGroupIsTheSearchOfTheModelWithOnlyItSettling) {
  const auto loaded = rbla::io::load_model_text(spanning_block(1.0, 2.5, 4.0, 1.0).dump());
  const SupportGroupRanking r = rank(loaded.model);
  for (int g : {0, 1}) {
    const model::Model alone = rbla::analysis::settling_only(loaded.model, {g}, "groups");
    EXPECT_EQ(alone.blocks[g].role, model::BlockRole::MovingSupport);
    EXPECT_EQ(alone.blocks[1 - g].role, model::BlockRole::Fixed);
    rbla::analysis::WorstSettlementSettings settings;
    settings.cone_angle = 20.0 * kPi / 180.0;
    const auto separate = rbla::analysis::find_worst_settlement(alone, {}, settings);
    ASSERT_TRUE(separate.ratio && r.groups[g].search.ratio);
    EXPECT_LT(relative_error(*r.groups[g].search.ratio, *separate.ratio), 1e-9);
  }
}

TEST(SupportGroups, RefusesAFreeBlockAndAnEmptyGroupNamingTheOption) {
  const auto loaded = rbla::io::load_model_text(spanning_block(1.0, 2.5, 4.0, 1.0).dump());
  try {
    rbla::analysis::rank_support_groups(loaded.model, {{0}, {2}}, "--candidate-group");
    FAIL() << "a free block settled";
  } catch (const model::ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("--candidate-group"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'B' is not a support"), std::string::npos) << e.what();
  }
  EXPECT_THROW(rbla::analysis::rank_support_groups(loaded.model, {{0}, {}}, "--candidate-group"), model::ModelError);
  // A support that carries nothing before settlement has no R / R0: refused, the group named.
  json lonely = spanning_block(1.0, 2.5, 4.0, 1.0);
  lonely["blocks"].push_back(box_block("far", 10.0, 0.0, -0.5, 11.0, 1.0, 0.0, "fixed"));
  const auto with_far = rbla::io::load_model_text(lonely.dump());
  try {
    rbla::analysis::rank_support_groups(with_far.model, {{0}, {3}}, "--candidate-group");
    FAIL() << "a support that carries nothing was ranked";
  } catch (const model::ModelError& e) {
    EXPECT_EQ(e.issues().front().pointer, "--candidate-group") << e.what();
    EXPECT_NE(std::string(e.what()).find("'far'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(rbla::analysis::rank_support_groups(loaded.model, {}, "--candidate-group"), model::ModelError);
}

}  // namespace
}  // namespace rbla::validation
