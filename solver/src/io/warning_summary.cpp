#include "io/warning_summary.hpp"

#include <algorithm>
#include <map>

namespace rbla::io {

namespace {

std::string located(const model::Warning& warning) {
  return warning.pointer.empty() ? std::string() : " at " + warning.pointer;
}

}  // namespace

std::vector<WarningKind> summarise_warnings(const std::vector<model::Warning>& warnings) {
  std::vector<WarningKind> kinds;
  std::map<std::string, std::size_t> kind_of_code;
  for (std::size_t i = 0; i < warnings.size(); ++i) {
    const auto [entry, added] = kind_of_code.emplace(warnings[i].code, kinds.size());
    if (added) kinds.push_back({warnings[i].code, 0, i});
    WarningKind& kind = kinds[entry->second];
    ++kind.count;
    if (warnings[i].magnitude > warnings[kind.worst].magnitude) kind.worst = i;
  }
  return kinds;
}

std::vector<std::size_t> listed_warnings(const std::vector<model::Warning>& warnings) {
  const std::vector<WarningKind> kinds = summarise_warnings(warnings);
  std::map<std::string, const WarningKind*> kind_of_code;
  for (const WarningKind& kind : kinds) kind_of_code[kind.code] = &kind;
  std::map<std::string, std::size_t> listed;
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < warnings.size(); ++i) {
    const WarningKind& kind = *kind_of_code[warnings[i].code];
    std::size_t& n = listed[kind.code];
    // Room is kept for the worst instance until it comes.
    const bool room = n + (i < kind.worst ? 1 : 0) < kMaxWarningsPerCode;
    if (i == kind.worst || room) {
      out.push_back(i);
      ++n;
    }
  }
  return out;
}

std::vector<std::string> warning_lines(const std::vector<model::Warning>& warnings, bool all) {
  std::vector<std::string> lines;
  if (all) {
    for (const model::Warning& warning : warnings) {
      lines.push_back("[" + warning.code + "]" + located(warning) + ": " + warning.message);
    }
    return lines;
  }
  for (const WarningKind& kind : summarise_warnings(warnings)) {
    const model::Warning& worst = warnings[kind.worst];
    if (kind.count == 1) {
      lines.push_back("[" + kind.code + "]" + located(worst) + ": " + worst.message);
      continue;
    }
    const bool measured = worst.magnitude > 0.0;
    lines.push_back("[" + kind.code + "] " + std::to_string(kind.count) + " times; " +
                    (measured ? "the worst" : "the first") + located(worst) + ": " + worst.message +
                    " (the result JSON lists them; -v prints each)");
  }
  return lines;
}

}  // namespace rbla::io
