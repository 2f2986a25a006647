// libFuzzer harness from bytes through the whole analysis, as `rbla solve` runs it: the model
// stage (io::load_model_text), the formulation, the conic solves, the verdict and mechanism,
// the result JSON (checked against schema/result.schema.json) and both SVG pictures.
//
// Small limits keep each input quick: models with more than kMaxBlocks blocks or
// kMaxContactPoints contact points stop after the model stage; the analysis gets a time limit of
// kTimeLimitSeconds and at most kMaxNonAssociativeSteps non-associative steps (both smaller
// values from the model are kept).
//
// Not findings: a rejection with model::ModelError (bad input, or a request the scene cannot
// meet), and any verdict, including solver failures (a fuzzed model may be numerically hopeless;
// the verdict must then say so). Findings: crashes and sanitizer reports, any other exception,
// hangs and runaway memory, and results that break what a verdict promises (checked below).
#include "analysis/limit_analysis.hpp"
#include "io/load_model.hpp"
#include "io/result_writer.hpp"
#include "io/schema_validation.hpp"
#include "io/svg_writer.hpp"
#include "model/errors.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

constexpr std::size_t kMaxBlocks = 64;
constexpr std::size_t kMaxContactPoints = 1024;
constexpr double kTimeLimitSeconds = 2.0;
constexpr int kMaxNonAssociativeSteps = 5;

[[noreturn]] void broken(const std::string& what) {
  std::fprintf(stderr, "fuzz_analysis: the result breaks an invariant: %s\n", what.c_str());
  std::abort();
}

bool finite(const rbla::model::Vec3& v) { return v.allFinite(); }

using rbla::analysis::Verdict;

/// What the verdict promises: a number exactly when there is a collapse, finite forces and
/// velocities, one entry per block and interface where a mechanism is reported.
void check_result(const rbla::model::Model& m, const rbla::analysis::AnalysisResult& r) {
  const bool settlement = m.analysis.type == rbla::model::AnalysisType::Settlement;
  const bool collapse = r.verdict == Verdict::Collapse;
  const auto& value = settlement ? r.base_reaction : r.load_multiplier;
  if (collapse != value.has_value()) broken("a number without a collapse, or a collapse without a number");
  if (value && !std::isfinite(*value)) broken("collapse value not finite");
  if (r.verdict_text.empty()) broken("empty verdict text");
  if (collapse || r.verdict == Verdict::CannotStand) {
    if (r.mechanism.blocks.size() != m.blocks.size()) broken("mechanism block count");
    if (r.mechanism.interfaces.size() != m.interfaces.size()) broken("mechanism interface count");
    for (const auto& motion : r.mechanism.blocks) {
      if (!finite(motion.translation) || !finite(motion.rotation)) broken("block velocity not finite");
    }
    for (std::size_t i = 0; i < r.mechanism.interfaces.size(); ++i) {
      const auto& face = r.mechanism.interfaces[i];
      if (face.points.size() != m.interfaces[i].polygon.size()) broken("contact point count");
      if (!std::isfinite(face.normal_force) || !std::isfinite(face.shear_force)) broken("interface force not finite");
      for (const auto& p : face.points) {
        if (!std::isfinite(p.normal_force) || !std::isfinite(p.shear1) || !std::isfinite(p.shear2) ||
            !finite(p.relative_velocity)) {
          broken("contact point force or velocity not finite");
        }
      }
    }
    for (int i : r.mechanism.cracked_interfaces) {
      if (i < 0 || static_cast<std::size_t>(i) >= m.interfaces.size()) broken("cracked interface index");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  rbla::io::LoadedModel loaded;
  try {
    loaded = rbla::io::load_model_text(text);
  } catch (const rbla::model::ModelError&) {
    return 0;  // bad input, rejected as documented
  }
  rbla::model::Model& m = loaded.model;
  if (m.blocks.size() > kMaxBlocks || m.num_contact_points() > kMaxContactPoints) return 0;
  rbla::model::AnalysisRequest& request = m.analysis;
  request.time_limit_seconds = request.time_limit_seconds > 0.0
                                   ? std::min(request.time_limit_seconds, kTimeLimitSeconds)
                                   : kTimeLimitSeconds;
  request.non_associative_max_iterations = std::min(request.non_associative_max_iterations, kMaxNonAssociativeSteps);

  rbla::analysis::AnalysisOptions options;
  options.threads = 1;  // deterministic, and one core per fuzzing worker
  rbla::analysis::AnalysisResult result;
  try {
    result = rbla::analysis::analyse(m, options);
  } catch (const rbla::model::ModelError&) {
    return 0;  // a request the scene cannot meet (a planar formulation forced on a 3-D scene)
  }
  check_result(m, result);
  const nlohmann::json json = rbla::io::analysis_result_json(m, result, loaded.timings, "fuzz");
  const auto issues = rbla::io::validate_against_schema(json, rbla::io::SchemaKind::Result, 1);
  if (!issues.empty()) broken("result JSON fails the schema at " + issues[0].pointer + ": " + issues[0].message);
  if (rbla::io::mechanism_svg(m, result).empty() || rbla::io::convergence_svg(result).empty()) {
    broken("empty SVG picture");
  }
  return 0;
}
