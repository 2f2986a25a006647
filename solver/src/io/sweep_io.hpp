// The files of a parameter study (`rbla sweep`, docs/sweeps.md): the axes as the command line
// gives them, one result file per point, the CSV summary, its picture and the Slurm script.
#pragma once

#include "analysis/sweep.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace rbla::io {

/// "name=low:high:count" (grid) or "name=low:high" (random sample). Throws model::ModelError
/// naming `option` and what is wrong.
analysis::SweepAxis parse_sweep_axis(const std::string& text, bool grid, const std::string& option);

/// "point_000012.json": the result file of point 12 in the output folder.
std::string point_file_name(int index);

/// The `sweep_point` section of a point's result file: its index and parameter values.
nlohmann::json sweep_point_json(const std::vector<analysis::SweepAxis>& axes, const analysis::SweepPoint& point);

/// One row of the summary, read back from a point's result file.
struct SweepRow {
  analysis::SweepPoint point;
  /// The result's status; "missing", "unreadable", or "mismatched" (the file is another
  /// sweep's: its sweep_point differs from this point)
  std::string status = "missing";
  std::optional<double> value;     ///< load_multiplier, or base_reaction.at_collapse (model units)
  double seconds = 0.0;            ///< the point's total run time
};
SweepRow read_sweep_row(const std::string& path, const std::vector<analysis::SweepAxis>& axes,
                        const analysis::SweepPoint& point);

/// index, one column per parameter, status, value, seconds.
std::string sweep_csv(const std::vector<analysis::SweepAxis>& axes, const std::vector<SweepRow>& rows,
                      const std::string& value_name);

/// One panel per parameter: the value of every point against that parameter.
std::string sweep_svg(const std::vector<analysis::SweepAxis>& axes, const std::vector<SweepRow>& rows,
                      const std::string& value_name);

/// A Slurm batch script running `command` (already a list of words) as a job array of `tasks`
/// tasks, each adding `--task $SLURM_ARRAY_TASK_ID --tasks <tasks>`. Words are single-quoted.
std::string slurm_script(const std::vector<std::string>& command, int tasks);

}  // namespace rbla::io
