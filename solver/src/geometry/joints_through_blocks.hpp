// Joints that detection would form through a third block. Detection accepts two faces as touching
// across a gap up to the joint's tolerance; when a third block lies in that gap (a shim, a mortar
// layer drawn as its own block) and touches both faces there, the two blocks do not touch: they
// are held apart by it, and a joint between them would carry forces through the third block's
// volume (a block on a 5 mm shim as wide as 70 % of its base was analysed as resting on its whole
// base, alpha 0.4988 against 0.2).
#pragma once

#include "model/model.hpp"

#include <vector>

namespace rbla::geometry {

struct JointThroughBlock {
  int block_a = -1, block_b = -1;  ///< the two blocks of the joint dropped
  int between = -1;                ///< the block lying between them
};

/// Removes from `interfaces` every detected joint A-B whose contact overlaps, seen along its
/// normal, a joint of A with a third block S that also has a joint with B there, all three facing
/// the same way within `angle_degrees`. Returns what was removed, in the order found.
std::vector<JointThroughBlock> drop_joints_through_blocks(std::vector<model::ContactInterface>& interfaces,
                                                          double angle_degrees);

}  // namespace rbla::geometry
