#include "io/load_model.hpp"

#include "io/model_reader.hpp"

#include <chrono>

namespace rbla::io {

namespace {
using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point from, Clock::time_point to) { return std::chrono::duration<double>(to - from).count(); }
}  // namespace

LoadedModel load_model_text(const std::string& text) {
  const auto start = Clock::now();
  LoadedModel loaded;
  loaded.model = parse_model(text);
  const auto parsed = Clock::now();
  loaded.prepare = geometry::prepare_model(loaded.model);
  loaded.timings.validate_seconds = seconds(start, parsed);
  loaded.timings.geometry_seconds = loaded.prepare.geometry_seconds;
  loaded.timings.detect_seconds = loaded.prepare.detect_seconds;
  loaded.timings.total_seconds = seconds(start, Clock::now());
  return loaded;
}

LoadedModel load_model_file(const std::string& path) {
  const auto start = Clock::now();
  const std::string text = read_text(path);
  const double read_seconds = seconds(start, Clock::now());
  LoadedModel loaded = load_model_text(text);
  loaded.timings.read_seconds = read_seconds;
  loaded.timings.total_seconds += read_seconds;
  return loaded;
}

}  // namespace rbla::io
