// Checks shared by the stiff tests: run a model the way the CLI does, and find NaN or Inf
// anywhere in the typed result and in the result JSON.
#pragma once

#include "analysis/limit_analysis.hpp"
#include "io/load_model.hpp"
#include "io/model_reader.hpp"
#include "io/result_writer.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace rbla::stiff {

struct StiffRun {
  io::LoadedModel loaded;
  analysis::AnalysisResult result;
};

inline StiffRun run_model(const nlohmann::json& model) {
  StiffRun r;
  r.loaded = io::load_model_text(model.dump());
  r.result = analysis::analyse(r.loaded.model);
  return r;
}

/// The value the case is about: alpha, or the base reaction (kN) of a settlement analysis.
inline double value_of(const analysis::AnalysisResult& r) {
  if (r.base_reaction) return *r.base_reaction;
  return r.load_multiplier.value_or(std::nan(""));
}

/// Names of every non-finite number in the typed result (empty when none).
inline std::vector<std::string> non_finite_fields(const analysis::AnalysisResult& r) {
  std::vector<std::string> bad;
  auto check = [&](double v, const std::string& what) {
    if (!std::isfinite(v)) bad.push_back(what + " = " + std::to_string(v));
  };
  auto check3 = [&](const model::Vec3& v, const std::string& what) {
    for (int k = 0; k < 3; ++k) check(v[k], what + "[" + std::to_string(k) + "]");
  };
  if (r.load_multiplier) check(*r.load_multiplier, "load_multiplier");
  if (r.base_reaction) check(*r.base_reaction, "base_reaction");
  for (std::size_t i = 0; i < r.mechanism.blocks.size(); ++i) {
    check3(r.mechanism.blocks[i].translation, "block " + std::to_string(i) + " translation");
    check3(r.mechanism.blocks[i].rotation, "block " + std::to_string(i) + " rotation");
  }
  for (std::size_t i = 0; i < r.mechanism.interfaces.size(); ++i) {
    const auto& f = r.mechanism.interfaces[i];
    const std::string name = "interface " + std::to_string(i);
    check(f.normal_force, name + " normal_force");
    check(f.shear_force, name + " shear_force");
    for (std::size_t k = 0; k < f.points.size(); ++k) {
      const std::string p = name + " point " + std::to_string(k);
      check(f.points[k].normal_force, p + " N");
      check(f.points[k].shear1, p + " T1");
      check(f.points[k].shear2, p + " T2");
      check3(f.points[k].relative_velocity, p + " relative velocity");
    }
  }
  check(r.work.live_work, "work.live_work");
  check(r.work.dead_work, "work.dead_work");
  check(r.work.dissipation, "work.dissipation");
  check(r.work.kinematic_value, "work.kinematic_value");
  check(r.work.relative_error, "work.relative_error");
  check(r.accuracy.relative_gap, "accuracy.relative_gap");
  check(r.accuracy.primal_residual, "accuracy.primal_residual");
  check(r.accuracy.dual_residual, "accuracy.dual_residual");
  check(r.accuracy.equilibrium_residual, "accuracy.equilibrium_residual");
  for (const auto& step : r.non_associative) check(step.value, "non_associative step value");
  return bad;
}

/// JSON pointers of null values (nlohmann writes NaN and Inf as null) in a result document.
inline void null_pointers(const nlohmann::json& j, const std::string& at, std::vector<std::string>& out) {
  if (j.is_null()) {
    out.push_back(at);
  } else if (j.is_number_float() && !std::isfinite(j.get<double>())) {
    out.push_back(at);
  } else if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) null_pointers(it.value(), at + "/" + it.key(), out);
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) null_pointers(j[i], at + "/" + std::to_string(i), out);
  }
}

/// The result JSON as `rbla solve -o` writes it, parsed back from its text.
inline nlohmann::json result_document(const StiffRun& run) {
  const nlohmann::json doc = io::analysis_result_json(run.loaded.model, run.result, run.loaded.timings, "stiff");
  return nlohmann::json::parse(doc.dump());
}

}  // namespace rbla::stiff
