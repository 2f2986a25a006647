// The whole model stage as one library call: read, parse, validate, default, convert units,
// compute geometry, detect interfaces. The CLI and the tests both call this.
#pragma once

#include "geometry/prepare_model.hpp"
#include "io/result_writer.hpp"
#include "model/model.hpp"

#include <string>

namespace rbla::io {

struct LoadedModel {
  model::Model model;
  StageTimings timings;          // total_seconds covers this stage only
  geometry::PrepareReport prepare;
};

/// Throws model::ModelError (with JSON pointers) on any bad input.
LoadedModel load_model_text(const std::string& text);
/// As load_model_text, reading `path` ("-" = standard input); the read time is included.
LoadedModel load_model_file(const std::string& path);

}  // namespace rbla::io
