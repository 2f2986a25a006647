// libFuzzer harness over the whole model stage, from bytes: JSON parse, schema validation, typed
// model, geometry checks and interface detection (io::load_model_text, what `rbla` runs).
//
// A rejection with model::ModelError is the documented answer to bad input and is not a finding.
// Anything else is: a crash or sanitizer report, any other exception escaping (uncaught, so it
// aborts), a hang or runaway memory (libFuzzer's -timeout and -rss_limit_mb), and an accepted
// model that breaks what prepare_model promises the analysis (checked below; a violation aborts).
#include "io/load_model.hpp"
#include "model/errors.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

[[noreturn]] void broken(const char* what) {
  std::fprintf(stderr, "fuzz_model: accepted model breaks an invariant: %s\n", what);
  std::abort();
}

bool finite(const rbla::model::Vec3& v) { return v.allFinite(); }

/// What the analysis relies on after a successful load: finite geometry, positive volumes, valid
/// block references and a right-handed orthonormal frame on every interface.
void check_invariants(const rbla::model::Model& m) {
  const int num_blocks = static_cast<int>(m.blocks.size());
  for (const auto& block : m.blocks) {
    if (!(std::isfinite(block.volume) && block.volume > 0.0)) broken("block volume not finite and positive");
    if (!finite(block.centroid)) broken("block centroid not finite");
    if (!std::isfinite(block.unit_weight)) broken("unit weight not finite");
  }
  for (const auto& face : m.interfaces) {
    if (face.block_a < 0 || face.block_a >= num_blocks || face.block_b < 0 || face.block_b >= num_blocks ||
        face.block_a == face.block_b) {
      broken("interface block references");
    }
    if (face.polygon.empty()) broken("interface without contact points");
    for (const auto& p : face.polygon) {
      if (!finite(p)) broken("contact point not finite");
    }
    if (!(std::isfinite(face.area) && face.area >= 0.0)) broken("interface area");
    if (!finite(face.centroid)) broken("interface centroid not finite");
    if (!(std::isfinite(face.friction) && face.friction >= 0.0)) broken("interface friction");
    const double tol = 1e-6;
    if (std::abs(face.normal.norm() - 1.0) > tol || std::abs(face.tangent1.norm() - 1.0) > tol ||
        std::abs(face.tangent2.norm() - 1.0) > tol || std::abs(face.normal.dot(face.tangent1)) > tol ||
        (face.normal.cross(face.tangent1) - face.tangent2).norm() > tol) {
      broken("interface frame not right-handed orthonormal");
    }
  }
  for (const auto* loads : {&m.dead_loads, &m.live_loads}) {
    for (const auto& load : *loads) {
      if (load.block < 0 || load.block >= num_blocks) broken("load block reference");
      if (!finite(load.force) || !finite(load.moment) || !finite(load.point)) broken("load not finite");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const rbla::io::LoadedModel loaded = rbla::io::load_model_text(text);
    check_invariants(loaded.model);
  } catch (const rbla::model::ModelError&) {
    // Expected rejection of bad input.
  }
  return 0;
}
