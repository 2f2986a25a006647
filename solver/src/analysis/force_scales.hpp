// Force scales of the conic problem's rows and variables (docs/method.md, "Scaling").
//
// The interior-point tolerances are relative to the largest data and solution entries, so a row
// whose natural forces are far smaller than the largest ones is enforced only to a fraction of
// them: with one force scale for the whole model (the mean free-block weight), a block 1e9 times
// lighter than the one it stands on had its equilibrium ignored (alpha 0.6 instead of 0.5).
// Each block's rows and each interface's variables therefore get their own scale, from the load
// each is expected to carry; models whose carried loads all lie within kForceScaleBand of the
// mean weight keep the single scale (and so the very same conic problem).
#pragma once

#include "model/model.hpp"

#include <vector>

namespace rbla::analysis {

/// Carried loads within this factor of the reference (either way) use the reference itself.
/// Beyond it a scale follows its carried load to within the same factor, so that every block's
/// own right-hand side stays at least 1/kForceScaleBand of its largest entries, five orders of
/// magnitude above the solver's default tolerance of 1e-8.
inline constexpr double kForceScaleBand = 1e3;

/// Two blocks side by side whose carried loads differ by more than these may get a wrong answer
/// (a warning says so). Measured on a light block beside a heavy one, whose own sliding governs
/// (closed form 0.3), and on the arch sample with a light voussoir at the crown carrying the
/// thrust: associative, right to 1e-8 up to 1e16 and wrong from 1e17; non-associative (scheme
/// tolerance 1e-6), 4.5e-6 off at 1e10, 1.5e-5 at 1e11, 8 % at 1e14. Other shapes than the two
/// measured may go wrong earlier.
inline constexpr double kLateralContrastLimit = 1e14;
inline constexpr double kLateralContrastLimitNonAssociative = 1e10;

struct ForceScales {
  double reference = 1.0;          ///< kN: the mean free-block weight (or the mean live load)
  std::vector<double> carried;     ///< kN, per model block: the load it is expected to carry (0 for supports)
  std::vector<double> own;         ///< kN, per model block: its weight plus its point loads (0 for supports)
  std::vector<double> block;       ///< kN, per model block: its equilibrium rows are divided by it
  std::vector<double> interface;   ///< kN, per model interface: its force variables are in units of it
  /// kN, per model interface: the smaller carried load of its free blocks (the reference when
  /// its scale is the reference).
  std::vector<double> interface_load;
  /// The largest ratio of carried loads between two free blocks side by side (no load passed
  /// from one to the other), 1 when there is none, and the two blocks.
  double lateral_contrast = 1.0;
  int lateral_light = -1, lateral_heavy = -1;
  double lateral_limit = kLateralContrastLimit;  ///< the limit force_scales was given
  int num_lateral_over_limit = 0;                 ///< pairs side by side over it
};

/// Loads each block is expected to carry: its own weight and loads plus what the blocks above it
/// pass down, shared among the interfaces below its centroid in proportion to their area (more
/// for flatter joints): a load path from top to bottom along gravity, O(n log n). A block's scale
/// is its carried load through kForceScaleBand around `reference`, raised for a block beside a
/// heavier one (no load passed between them) to a weighted geometric mean of the two, since the
/// heavier one may push through it; an interface's scale is the smaller of its blocks' scales.
/// `lateral_limit`: the contrast between blocks side by side counted in num_lateral_over_limit.
ForceScales force_scales(const model::Model& model, double reference, double lateral_limit);

}  // namespace rbla::analysis
