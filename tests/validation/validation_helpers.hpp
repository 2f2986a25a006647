// Shared helpers of the validation tests: build a model JSON, run the whole pipeline on it.
#pragma once

#include "analysis/limit_analysis.hpp"
#include "io/load_model.hpp"
#include "support/model_builder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace rbla::validation {

using nlohmann::json;
using rbla::analysis::AnalysisResult;
using rbla::analysis::Verdict;
using namespace rbla::testing;

/// The model stage and the analysis, exactly as the CLI runs them.
inline AnalysisResult run(const json& model) {
  const auto loaded = rbla::io::load_model_text(model.dump());
  return rbla::analysis::analyse(loaded.model);
}

inline double relative_error(double got, double expected) {
  return std::abs(got - expected) / std::max(std::abs(expected), 1e-300);
}

/// Options of a load-multiplier analysis.
struct Case {
  double mu = 0.6;
  double unit_weight = 18.0;
  std::string friction_model = "associative";
  std::string formulation = "auto";
  std::string cone = "exact";
  int pyramid_faces = 8;
  json seismic_direction = json::array({1.0, 0.0, 0.0});
};

inline json analysis_of(const Case& s) {
  json a = {{"type", "load_multiplier"},
            {"friction_model", s.friction_model},
            {"formulation", s.formulation},
            {"cone", s.cone},
            {"pyramid_faces", s.pyramid_faces},
            // Non-associative states compatible to 1e-6 (the work balance the tests check).
            {"non_associative", {{"max_iterations", 200}, {"tolerance", 1e-6}}}};
  if (!s.seismic_direction.is_null()) a["seismic"] = {{"direction", s.seismic_direction}};
  return a;
}

inline json finish(json blocks, const Case& s) {
  json model = model_with(std::move(blocks));
  model["defaults"] = {{"unit_weight", s.unit_weight}, {"friction", s.mu}};
  model["analysis"] = analysis_of(s);
  return model;
}

/// The settling block of ClosedForms.SettlementBaseReaction: a block [0, L] x [0, 1] x [0, h]
/// (unit weight 18, friction 0.6) on a fixed support under [0, a] and a moving one under
/// [a + 1e-3, L + 0.5], settling along gravity unless the caller sets a direction.
inline json settling_block(double a, double L = 4.0, double h = 1.0, const std::string& formulation = "auto") {
  json blocks = json::array({box_block("fixed", -0.5, -0.5, -0.5, a, 1.5, 0.0, "fixed"),
                             box_block("moving", a + 1e-3, -0.5, -0.5, L + 0.5, 1.5, 0.0, "moving_support"),
                             box_block("B", 0.0, 0.0, 0.0, L, 1.0, h)});
  json model = model_with(blocks);
  model["defaults"] = {{"unit_weight", 18.0}, {"friction", 0.6}};
  model["analysis"] = {{"type", "settlement"}, {"formulation", formulation}};
  return model;
}

/// A free block [0,b]x[0,depth]x[0,h] on a wider fixed base.
inline json single_block(double b, double h, const Case& s, double depth = 1.0) {
  json blocks = json::array({box_block("base", -0.5, -0.5, -0.5, b + 0.5, depth + 0.5, 0.0, "fixed"),
                             box_block("B", 0.0, 0.0, 0.0, b, depth, h)});
  return finish(blocks, s);
}

/// A column of n equal blocks, b wide, total height H, on a fixed base.
inline json column(int n, double b, double H, const Case& s, double depth = 1.0) {
  json blocks = json::array({box_block("base", -0.5, -0.5, -0.5, b + 0.5, depth + 0.5, 0.0, "fixed")});
  for (int i = 0; i < n; ++i) {
    blocks.push_back(box_block("C" + std::to_string(i), 0.0, 0.0, H * i / n, b, depth, H * (i + 1) / n));
  }
  return finish(blocks, s);
}

/// The drawer: a block M (2 x 1 x 0.5) on a fixed base is pulled along +x under a block T
/// (1 x 1 x 1) which a fixed stop keeps from moving along +x. The stop does not touch M.
inline json drawer(const std::string& friction_model, double mu) {
  json blocks = json::array({box_block("base", -1.0, 0.0, -0.5, 3.0, 1.0, 0.0, "fixed"),
                             box_block("M", 0.0, 0.0, 0.0, 2.0, 1.0, 0.5),
                             box_block("T", 0.5, 0.0, 0.5, 1.5, 1.0, 1.5),
                             box_block("stop", 1.5, 0.0, 0.6, 2.5, 1.0, 1.5, "fixed")});
  Case s;
  s.mu = mu;
  s.friction_model = friction_model;
  s.seismic_direction = nullptr;
  json model = finish(blocks, s);
  model["loads"] = {{"live", json::array({{{"block", "M"}, {"force", {1.0, 0.0, 0.0}}}})}};
  return model;
}

/// Collapse expected: returns alpha (0 when none, after recording a failure).
/// A squat block (1 x 1 x 0.2) on a fixed base, both tilted by `beta` about the y axis: the bed
/// joint slopes at beta, and the centroid stays well inside the contact (tipping would need
/// tan(beta) > 5).
inline json inclined_block(double beta, double mu, bool stacked = false) {
  json blocks = json::array({box_block("base", -1.0, -0.5, -0.3, 1.0, 1.5, 0.0, "fixed"),
                             box_block("block", -0.5, 0.0, 0.0, 0.5, 1.0, 0.2)});
  if (stacked) blocks.push_back(box_block("top", -0.4, 0.1, 0.2, 0.4, 0.9, 0.4));
  for (json& block : blocks) {
    for (json& v : block["vertices"]) {
      const double x = v[0], z = v[2];
      v[0] = std::cos(beta) * x + std::sin(beta) * z;
      v[2] = -std::sin(beta) * x + std::cos(beta) * z;
    }
  }
  Case c;
  c.mu = mu;
  return finish(blocks, c);
}

inline double alpha_of(const AnalysisResult& r) {
  EXPECT_EQ(r.verdict, Verdict::Collapse) << r.verdict_text;
  EXPECT_TRUE(r.load_multiplier.has_value());
  return r.load_multiplier.value_or(0.0);
}

}  // namespace rbla::validation
