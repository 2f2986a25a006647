// What the model stage says about a model text: its issues, and helpers to look for one.
#pragma once

#include "io/input_limits.hpp"
#include "io/load_model.hpp"
#include "model/errors.hpp"

#include <string>
#include <vector>

namespace rbla::testing {

/// The issues load_model_text threw for `text` (empty when it accepted the model).
inline std::vector<model::InputIssue> model_issues(const std::string& text, const io::InputLimits& limits = {}) {
  try {
    io::load_model_text(text, limits);
  } catch (const model::ModelError& error) {
    return error.issues();
  }
  return {};
}

/// True when some issue is at exactly `pointer` and its message contains `words`.
inline bool has_issue_at(const std::vector<model::InputIssue>& issues, const std::string& pointer,
                         const std::string& words = "") {
  for (const auto& issue : issues) {
    if (issue.pointer == pointer && issue.message.find(words) != std::string::npos) return true;
  }
  return false;
}

/// One line per issue, for failure messages.
inline std::string describe_issues(const std::vector<model::InputIssue>& issues) {
  std::string text;
  for (const auto& issue : issues) text += "[" + issue.pointer + "] " + issue.message + "\n";
  return text.empty() ? "(accepted)" : text;
}

}  // namespace rbla::testing
