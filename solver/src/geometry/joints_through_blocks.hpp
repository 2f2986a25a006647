// Joints that detection would form through a third block. Detection accepts two faces as touching
// across a gap up to the joint's tolerance; when a third block lies in that gap (a shim, a mortar
// layer or a thin slab drawn as its own block) and touches both faces there, the two blocks do not
// touch: they are held apart by it, and a joint between them would carry forces through the third
// block's volume (a block on a 5 mm shim as wide as 70 % of its base was analysed as resting on
// its whole base, alpha 0.4988 against 0.1996).
#pragma once

#include "model/model.hpp"

#include <vector>

namespace rbla::geometry {

/// For each of `detected` whose faces are `apart` (nowhere touching; `gaps` the farthest apart they
/// are, m), the block lying between its two blocks A and B, or -1: a block S with joints to A and
/// to B (among the model's own interfaces and `detected`) that face as A-B does within
/// `angle_degrees`, overlap it, seen along its normal, by more than 1 % of the smaller, and lie on
/// either side of its plane, a fifth of its gap or more from it (S is in the gap, not beside B
/// at B's level; with two equal layers between A and B, each layer's joint across the other lies a
/// quarter of the gap from the plane, so a quarter itself is too tight). Supports form no joints
/// with each other, so when S and B are both supports S's
/// joint with A suffices (a block on a plinth, both fixed).
std::vector<int> blocks_between(const model::Model& m, const std::vector<model::ContactInterface>& detected,
                                const std::vector<bool>& apart, const std::vector<double>& gaps,
                                double angle_degrees);

}  // namespace rbla::geometry
