// Reaction of the moving supports in the initial state, before any settlement.
//
// Portioli & Cascini (2016) report the *loss* of base reaction at collapse: the initial reaction
// minus the reaction at collapse. A rigid-block model does not fix the initial reaction (the
// supports make the structure statically indeterminate: every value between the reaction at
// collapse and the largest admissible one is in equilibrium), and the paper does not say how it
// was found. rbla uses the classical engineering estimate instead, stated here so that users can
// reproduce it by hand:
//
//   Before settlement the structure is one rigid body resting on uniformly elastic ground
//   (Winkler springs of equal stiffness, normal to every support interface). The base pressure
//   is then an affine function of position over the contact surface (Navier's formula
//   σ = N/A + M·y/I for a flat base), with no tension: where it would pull, the base lifts and
//   the pressure is recomputed on the part still in contact (the usual no-tension footing
//   iteration). The initial reaction R₀ is the resultant of that pressure on the moving
//   supports, along −d (d = settlement direction), the same component the settlement analysis
//   reports at collapse.
//
// Each group of free blocks connected by free-free interfaces is its own rigid body. The spring
// stiffness cancels out. Without tangential springs the normal pressure carries the dead loads
// on the motions it resists; a motion it resists a thousand times less than the stiffest (the
// sliding of a base that is flat but for CAD imprecision) is held still, and the small part of
// the load along it (up to 5 %) is left to friction. When more is left (a horizontal dead load on
// a flat base), R₀ is not defined.
#pragma once

#include "model/model.hpp"

#include <optional>
#include <string>

namespace rbla::analysis {

struct InitialReaction {
  std::optional<double> value;  ///< kN, R₀ along −d; empty when not defined (see why_not)
  std::string why_not;          ///< one sentence, when value is empty
  bool base_lifts = false;      ///< part of the base is out of contact (no-tension iteration)
  int iterations = 0;           ///< no-tension passes of the group that needed the most
};

/// R₀ of the model's moving supports along −settlement_direction (unit), from geometry and dead
/// loads only (no conic solve).
InitialReaction initial_base_reaction(const model::Model& model, const model::Vec3& settlement_direction);

}  // namespace rbla::analysis
