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

/// For each of `detected`, the block lying between its two blocks, or -1: a block S with a joint
/// to A and a joint to B (among `given` and `detected`) that face as A-B does within
/// `angle_degrees` and overlap it, seen along its normal, by more than 1 % of the smaller.
std::vector<int> blocks_between(const std::vector<model::ContactInterface>& given,
                                const std::vector<model::ContactInterface>& detected, double angle_degrees);

}  // namespace rbla::geometry
