// The time each stage of one run took: filled by the model stage (io/load_model) and the CLI,
// written by the result writer. Its own header so that the loader, the first floor of io, does
// not include the writer, the last.
#pragma once

namespace rbla::model {

/// Stage times of one run, in seconds; a stage that did not run stays 0.
struct StageTimings {
  double read_seconds = 0.0;
  double validate_seconds = 0.0;
  double geometry_seconds = 0.0;
  double detect_seconds = 0.0;
  double write_seconds = 0.0;
  double total_seconds = 0.0;
};

}  // namespace rbla::model
