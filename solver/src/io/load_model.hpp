// The whole model stage as one library call: read, parse, validate, default, convert units,
// compute geometry, detect interfaces. The CLI and the tests both call this.
#pragma once

#include "geometry/prepare_model.hpp"
#include "io/input_limits.hpp"
#include "model/model.hpp"
#include "model/stage_timings.hpp"

#include <string>

namespace rbla::io {

struct LoadedModel {
  model::Model model;
  model::StageTimings timings;  // total_seconds covers this stage only
  geometry::PrepareReport prepare;
};

/// Throws model::ModelError (with JSON pointers) on any bad input.
LoadedModel load_model_text(const std::string& text, const InputLimits& limits = {});
/// As load_model_text, reading `path` ("-" = standard input: see io/input_file.hpp) as the parser
/// needs it, so only the parsed document is held, never the whole text as well. Throws
/// io::FileError when the path cannot be read.
LoadedModel load_model_file(const std::string& path, const InputLimits& limits = {});

}  // namespace rbla::io
