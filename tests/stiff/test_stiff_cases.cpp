// Numerical stability on stiff and extreme models (issue 7): every fast case of
// tests/stiff/stiff_cases.hpp must give the expected verdict, the closed-form value within the
// accuracy the case states (and why), no NaN or Inf anywhere in the typed result, and a result
// JSON that is valid against schema/result.schema.json (which admits no null, so no NaN either).
#include "stiff_cases.hpp"
#include "stiff_checks.hpp"

#include <gtest/gtest.h>

#include <iomanip>
#include <set>
#include <sstream>

namespace rbla::stiff {
namespace {

using analysis::Verdict;

Verdict verdict_of(Expect e) {
  switch (e) {
    case Expect::Collapse: return Verdict::Collapse;
    case Expect::NoMechanism: return Verdict::NoMechanism;
    case Expect::CannotStand: return Verdict::CannotStand;
    case Expect::TimeLimit: return Verdict::TimeLimit;
  }
  return Verdict::SolverFailure;
}

std::vector<StiffCase> fast_cases() {
  std::vector<StiffCase> out;
  for (auto& c : stiff_cases()) {
    if (!c.slow) out.push_back(std::move(c));
  }
  return out;
}

std::string test_name(const ::testing::TestParamInfo<StiffCase>& info) {
  std::string s;
  for (const char ch : info.param.name) {
    if (std::isalnum(static_cast<unsigned char>(ch))) s += ch;
    else if (ch == '.') s += 'p';
    else if (ch == '-') s += 'm';
    else s += '_';
  }
  return s;
}

class StiffCaseTest : public ::testing::TestWithParam<StiffCase> {};

TEST_P(StiffCaseTest, VerdictValueAndNoNaN) {
  const StiffCase& c = GetParam();
  SCOPED_TRACE(c.varies + " | reference: " + c.source);
  const StiffRun run = run_model(c.model);
  const auto& r = run.result;
  ASSERT_STREQ(analysis::to_string(r.verdict), analysis::to_string(verdict_of(c.expect))) << r.verdict_text << " (" << r.solver_info.iterations
                                             << " ipm iterations, " << r.solver_info.failure_reason << ")";

  if (c.expect == Expect::Collapse) {
    const double value = value_of(r);
    double allowed = c.rel_tol * std::abs(c.reference) + c.abs_tol;
    if (r.friction_model == model::FrictionModel::NonAssociative && !r.non_associative_converged) {
      // An unconverged scheme must say so (warning); its state is then admissible but only as
      // close as the default-tolerance bound below.
      bool warned = false;
      for (const auto& w : r.warnings) warned |= w.code == "non_associative_not_converged";
      EXPECT_TRUE(warned) << "an unconverged non-associative run must warn";
      allowed = 1e-3 * std::abs(c.reference) + c.abs_tol;
    }
    EXPECT_LE(std::abs(value - c.reference), allowed)
        << std::setprecision(12) << "value " << value << " reference " << c.reference << " (rel err "
        << std::abs(value - c.reference) / std::abs(c.reference) << "); tolerance: " << c.tol_reason;
    // Static value = kinematic work balance (|static - kinematic| / max(1, |static|)).
    EXPECT_LT(r.work.relative_error, 1e-6) << "kinematic " << r.work.kinematic_value;
    // Every free block in equilibrium, relative to the largest block weight in the model.
    double w_max = 0.0;
    for (const auto& b : run.loaded.model.blocks) {
      if (!b.is_support()) w_max = std::max(w_max, b.weight());
    }
    EXPECT_LE(r.accuracy.equilibrium_residual, 1e-7 * w_max) << "largest free block weight " << w_max << " kN";
    bool any_moving = false;
    for (const auto& b : r.mechanism.blocks) any_moving |= b.moving;
    EXPECT_TRUE(any_moving) << "a collapse needs a mechanism";
    if (r.friction_model == model::FrictionModel::NonAssociative) {
      // The scheme stops at a state that passes its fixed-point test to the model's tolerance
      // (relative to the value), which needs the solves to resolve the value to it: required where
      // tolerance x |value| >= 1e-7 (the solves' absolute accuracy on a multiplier).
      const bool settlement = r.base_reaction.has_value();
      const double na_tol = c.model["analysis"]["non_associative"].value("tolerance", 1e-3);
      if (settlement || na_tol * std::abs(value) >= 1e-7) {
        EXPECT_TRUE(r.non_associative_converged) << r.non_associative.size() << " steps at tolerance " << na_tol
                                                 << ", fixed-point gap " << r.non_associative_gap << " after "
                                                 << r.non_associative_checks << " tests";
      }
      // Never on the unsafe side of the associative value of the same model (to the solves'
      // accuracy: 1e-7 of max(1, |value|), as the closed-form tolerances above).
      nlohmann::json associative = c.model;
      associative["analysis"]["friction_model"] = "associative";
      const StiffRun a = run_model(associative);
      ASSERT_STREQ(analysis::to_string(a.result.verdict), "collapse") << a.result.verdict_text;
      const double av = value_of(a.result), slack = 1e-7 * std::max(1.0, std::abs(av));
      if (settlement) EXPECT_GE(value, av - slack) << std::setprecision(12) << "associative " << av << ", non-associative " << value;
      else EXPECT_LE(value, av + slack) << std::setprecision(12) << "associative " << av << ", non-associative " << value;
      // And at rbla's default scheme settings, what users run.
      nlohmann::json fallback = c.model;
      fallback["analysis"].erase("non_associative");
      const StiffRun d = run_model(fallback);
      ASSERT_STREQ(analysis::to_string(d.result.verdict), "collapse") << d.result.verdict_text;
      const double dv = value_of(d.result);
      EXPECT_LE(std::abs(dv - c.reference), 1e-3 * std::abs(c.reference) + c.abs_tol)
          << std::setprecision(12) << "default settings: " << dv << " vs " << c.reference;
      if (settlement || 1e-3 * std::abs(dv) >= 1e-7) {
        EXPECT_TRUE(d.result.non_associative_converged)
            << "default settings: " << d.result.non_associative.size() << " steps, gap " << d.result.non_associative_gap;
      }
    }
  } else {
    EXPECT_FALSE(r.load_multiplier.has_value());
    EXPECT_FALSE(r.base_reaction.has_value());
  }
  if (c.expect == Expect::CannotStand) {
    bool any_falling = false;
    for (const auto& b : r.mechanism.blocks) any_falling |= b.moving;
    EXPECT_TRUE(any_falling) << "the certificate should name the falling blocks";
  }

  const auto bad = non_finite_fields(r);
  EXPECT_TRUE(bad.empty()) << bad.size() << " non-finite values, first: " << (bad.empty() ? "" : bad.front());

  const nlohmann::json doc = result_document(run);
  std::vector<std::string> nulls;
  null_pointers(doc, "", nulls);
  EXPECT_TRUE(nulls.empty()) << nulls.size() << " null or non-finite values in the result JSON, first at "
                             << (nulls.empty() ? "" : nulls.front());
  const auto issues = io::validate_result_text(doc.dump());
  EXPECT_TRUE(issues.empty()) << "result JSON invalid: " << (issues.empty() ? "" : issues[0].pointer + ": " + issues[0].message);
}

INSTANTIATE_TEST_SUITE_P(Stiff, StiffCaseTest, ::testing::ValuesIn(fast_cases()), test_name);

// The catalogue itself: unique names, a reference and a stated tolerance for every collapse, and
// every axis of issue 7 covered at its extremes.
TEST(StiffCatalogue, NamesUniqueAndReferencesGiven) {
  std::set<std::string> names;
  for (const auto& c : stiff_cases()) {
    EXPECT_TRUE(names.insert(c.name).second) << "duplicate case name " << c.name;
    EXPECT_FALSE(c.source.empty()) << c.name;
    if (c.expect == Expect::Collapse) {
      EXPECT_TRUE(std::isfinite(c.reference)) << c.name;
      EXPECT_GT(c.rel_tol * std::abs(c.reference) + c.abs_tol, 0.0) << c.name;
      // No tolerance wider than 1e-4 relative to the reference: a looser one would hide errors.
      EXPECT_LE(c.rel_tol * std::abs(c.reference) + c.abs_tol, 1e-4 * std::abs(c.reference) + 1e-7) << c.name;
    }
  }
}

}  // namespace
}  // namespace rbla::stiff
