// Setup errors: bad input is reported by throwing ModelError, whose issues each name the place
// in the model file (a JSON pointer) and what was expected there. Analysis outcomes such as
// "cannot stand" are not errors and never use this type.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace rbla::model {

struct InputIssue {
  std::string pointer;  // JSON pointer into the model file ("" = the whole document)
  std::string message;
};

class ModelError : public std::runtime_error {
 public:
  explicit ModelError(std::vector<InputIssue> issues)
      : std::runtime_error(summarise(issues)), issues_(std::move(issues)) {}
  ModelError(std::string pointer, std::string message)
      : ModelError(std::vector<InputIssue>{{std::move(pointer), std::move(message)}}) {}
  const std::vector<InputIssue>& issues() const { return issues_; }

 private:
  static std::string summarise(const std::vector<InputIssue>& issues) {
    std::string text;
    for (const InputIssue& issue : issues) {
      if (!text.empty()) text += "\n";
      text += (issue.pointer.empty() ? std::string("(document)") : issue.pointer) + ": " + issue.message;
    }
    return text;
  }
  std::vector<InputIssue> issues_;
};

/// JSON pointer escaping (RFC 6901): '~' -> "~0", '/' -> "~1".
inline std::string pointer_token(const std::string& token) {
  std::string out;
  for (char c : token) {
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else out += c;
  }
  return out;
}

}  // namespace rbla::model
