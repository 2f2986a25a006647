// The searches certify brackets only as narrow as their analyses are exact: each analysis stops
// at the model's relative duality gap and residuals (analysis.tolerances, 1e-8 by default), so a
// bracket asked narrower than ten times those is refused, naming the tolerances to lower; lowered,
// the same request runs. Checked on all three searches.
#include "analysis/critical_friction.hpp"
#include "analysis/worst_direction.hpp"
#include "analysis/worst_settlement.hpp"
#include "model/errors.hpp"
#include "validation_helpers.hpp"
#include "model/angles.hpp"

#include <cmath>
#include <functional>
#include <optional>
#include <string>

namespace rbla::validation {
namespace {

model::Model loaded(json model, double analysis_tolerance) {
  model["analysis"]["tolerances"] = {{"relative_gap", analysis_tolerance}, {"feasibility", analysis_tolerance}};
  return rbla::io::load_model_text(model.dump()).model;
}

void expect_refused(const std::function<void()>& search) {
  try {
    search();
    ADD_FAILURE() << "a bracket narrower than the analyses' tolerance was accepted";
  } catch (const model::ModelError& e) {
    ASSERT_EQ(e.issues().size(), 1u);
    EXPECT_EQ(e.issues()[0].pointer, "/analysis/tolerances");
    EXPECT_NE(e.issues()[0].message.find("at most 1e-10"), std::string::npos) << e.issues()[0].message;
  }
}

TEST(SearchTolerance, WorstDirectionRefusesABracketNarrowerThanItsAnalyses) {
  Case s;
  const json block = single_block(1.0, 2.0, s);
  analysis::RadialSearchSettings settings;
  settings.tolerance = 1e-9;
  expect_refused([&] { analysis::find_worst_direction(loaded(block, 1e-8), {}, settings); });
  const auto w = analysis::find_worst_direction(loaded(block, 1e-10), {}, settings);
  EXPECT_EQ(w.verdict, Verdict::Collapse) << w.verdict_text;
}

TEST(SearchTolerance, WorstSettlementRefusesABracketNarrowerThanItsAnalyses) {
  analysis::WorstSettlementSettings settings;
  settings.search.tolerance = 1e-9;
  expect_refused([&] { analysis::find_worst_settlement(loaded(settling_block(1.0), 1e-8), {}, settings); });
  const auto w = analysis::find_worst_settlement(loaded(settling_block(1.0), 1e-10), {}, settings);
  EXPECT_NE(w.verdict, Verdict::SolverFailure) << w.verdict_text;
}

TEST(SearchTolerance, CriticalFrictionRefusesABracketNarrowerThanItsAnalyses) {
  // Standing on a plane inclined at 20 degrees needs mu = tan(20 degrees): 0.6 times 0.6066.
  const json block = inclined_block(20.0 * model::kPi / 180.0, 0.6);
  analysis::ThresholdSettings settings;
  settings.tolerance = 1e-9;
  expect_refused([&] { analysis::find_critical_friction(loaded(block, 1e-8), std::nullopt, {}, settings); });
  const auto c = analysis::find_critical_friction(loaded(block, 1e-10), std::nullopt, {}, settings);
  ASSERT_EQ(c.outcome, analysis::ThresholdOutcome::Bracketed) << c.verdict_text;
  EXPECT_TRUE(c.certified) << c.stop;
  const double mu = std::tan(20.0 * model::kPi / 180.0);
  EXPECT_LE(*c.uniform_friction * *c.factor_lower, mu * (1.0 + 1e-9));
  EXPECT_GE(*c.uniform_friction * *c.factor_upper, mu * (1.0 - 1e-9));
}

// A target counts as carried to within 1e-6 (relative): a bracket of the friction narrower than
// that would be exact for a slightly smaller target, so it is refused.
TEST(SearchTolerance, CriticalFrictionWithATargetRefusesABracketBelowOneInAMillion) {
  Case s;
  const json block = single_block(1.0, 2.0, s);  // alpha = min(mu, 0.5)
  analysis::ThresholdSettings settings;
  settings.tolerance = 1e-7;
  try {
    analysis::find_critical_friction(loaded(block, 1e-10), 0.3, {}, settings);
    ADD_FAILURE() << "accepted";
  } catch (const model::ModelError& e) {
    EXPECT_EQ(e.issues()[0].pointer, "--tolerance");
  }
  settings.tolerance = 1e-6;
  const auto c = analysis::find_critical_friction(loaded(block, 1e-10), 0.3, {}, settings);
  ASSERT_EQ(c.outcome, analysis::ThresholdOutcome::Bracketed) << c.verdict_text;
  EXPECT_LT(relative_error(*c.uniform_friction * *c.factor_upper, 0.3), 2e-6);
}

}  // namespace
}  // namespace rbla::validation
