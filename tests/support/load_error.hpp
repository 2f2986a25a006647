// The model stage's answer to a model, as the text a user reads: for tests of its messages.
#pragma once

#include "io/load_model.hpp"
#include "model/errors.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace rbla::testing {

/// The ModelError message io::load_model_text gives for `model`, or "" when it loads.
inline std::string load_error(const nlohmann::json& model) {
  try {
    rbla::io::load_model_text(model.dump());
  } catch (const rbla::model::ModelError& error) {
    return error.what();
  }
  return "";
}

}  // namespace rbla::testing
