#include "io/load_model.hpp"

#include "io/input_file.hpp"
#include "io/json_reader.hpp"
#include "io/model_reader.hpp"

#include <chrono>

namespace rbla::io {

namespace {
using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point from, Clock::time_point to) { return std::chrono::duration<double>(to - from).count(); }

/// Reading and parsing (`read`, to a JSON document), then validation and the typed model, then
/// geometry and detection, each timed as the result schema's timings name them.
template <typename Read>
LoadedModel load(Read&& read) {
  const auto start = Clock::now();
  LoadedModel loaded;
  {
    const nlohmann::json document = read();  // freed once the typed model is built
    const auto parsed = Clock::now();
    loaded.model = model_from_json(document);
    loaded.timings.read_seconds = seconds(start, parsed);
    loaded.timings.validate_seconds = seconds(parsed, Clock::now());
  }
  loaded.prepare = geometry::prepare_model(loaded.model);
  loaded.timings.geometry_seconds = loaded.prepare.geometry_seconds;
  loaded.timings.detect_seconds = loaded.prepare.detect_seconds;
  loaded.timings.total_seconds = seconds(start, Clock::now());
  return loaded;
}

}  // namespace

LoadedModel load_model_text(const std::string& text, const InputLimits& limits) {
  return load([&] { return read_json(std::string_view(text), limits); });
}

LoadedModel load_model_file(const std::string& path, const InputLimits& limits) {
  InputFile input(path, limits.max_bytes);
  return load([&] { return read_json(input.stream(), limits); });
}

}  // namespace rbla::io
