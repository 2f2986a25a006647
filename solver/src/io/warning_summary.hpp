// Warnings by kind. A model from a CAD export can carry a warning per face (1131 non_planar_face
// warnings on one vault): people get one line per kind with its count and its worst instance,
// the result JSON a bounded list with every kind's count. One place for both, so the counts on
// standard error and in the file agree.
#pragma once

#include "model/model.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace rbla::io {

/// Instances of one warning code kept in the result JSON's `warnings` (the worst among them);
/// `warning_summary` gives the full count.
inline constexpr std::size_t kMaxWarningsPerCode = 100;

struct WarningKind {
  std::string code;
  std::size_t count = 0;
  std::size_t worst = 0;  ///< index of the worst instance (largest magnitude, else the first)
};

/// One entry per code, in the order of their first appearance.
std::vector<WarningKind> summarise_warnings(const std::vector<model::Warning>& warnings);

/// The indices of the warnings the result JSON lists: per code the worst and the first others,
/// kMaxWarningsPerCode in all, in their original order.
std::vector<std::size_t> listed_warnings(const std::vector<model::Warning>& warnings);

/// Lines for standard error (without a prefix): one per kind, the count and the worst instance,
/// or with `all` every warning on its own line.
std::vector<std::string> warning_lines(const std::vector<model::Warning>& warnings, bool all);

}  // namespace rbla::io
