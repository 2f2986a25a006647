// Writing the result JSON (schema/result.schema.json). Converts back to the model's units.
#pragma once

#include "analysis/analysis_result.hpp"
#include "model/model.hpp"
#include "model/stage_timings.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace rbla::io {

/// The `model_summary` section: counts, bounding box and total weight in the model's units.
nlohmann::json model_summary_json(const model::Model& model);

/// The `warnings` section: every kind, at most io::kMaxWarningsPerCode instances of each
/// (warning_summary.hpp), the worst among them.
nlohmann::json warnings_json(const std::vector<model::Warning>& warnings);

/// The `warning_summary` section: per code, how many warnings there were and how many are listed.
nlohmann::json warning_summary_json(const std::vector<model::Warning>& warnings);

/// A complete result for a run that stopped after the model stage (status `model_only`):
/// no analysis, no numbers that were not computed.
nlohmann::json model_only_result(const model::Model& model, const model::StageTimings& timings, const std::string& source);

/// How much of a mechanism a result holds (`rbla solve --detail`). The contact points are most
/// of a result (95 % of the 1921-block facade's, 170 MB on a 29 765-block church): a sweep or a
/// search over a large model may need only the values and the block motions.
enum class ResultDetail {
  Points,      ///< every interface with its contact points, their states, velocities and forces
  Interfaces,  ///< every interface with its state and resultant, without its contact points
  Blocks,      ///< block motions and the list of cracked interfaces, no `interfaces` section
};

const char* to_string(ResultDetail detail);
/// The detail named `name` ("points", "interfaces", "blocks"); false when there is none.
bool parse_detail(const std::string& name, ResultDetail& detail);

/// A complete result of an analysis, in the model's units (lengths, forces; rotations in rad),
/// with the mechanism's interfaces to `detail`.
nlohmann::json analysis_result_json(const model::Model& model, const analysis::AnalysisResult& result,
                                    const model::StageTimings& timings, const std::string& source,
                                    ResultDetail detail = ResultDetail::Points);

}  // namespace rbla::io
