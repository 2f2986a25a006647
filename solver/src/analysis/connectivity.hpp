// Which free blocks no chain of interfaces joins to a support, checked before any solve.
//
// The forces between the blocks of a group cancel in pairs, so a group joined to no support is in
// equilibrium only if the resultant of its own dead loads vanishes: with weight it falls, whatever
// the rest of the structure does. An infeasible solve would find that too, but its certificate
// (an interior point of the cone of falling motions) moves the whole structure a little and names
// no culprit; on a scene that lost a few joints to CAD noise, the joints are what the user must
// look for. So the groups are found first, by union-find over the interfaces (linear in blocks
// and interfaces), and named in the verdict with the near misses of interface detection that
// touch them.
#pragma once

#include "analysis/analysis_result.hpp"
#include "model/model.hpp"

#include <string>

namespace rbla::analysis {

/// The groups of free blocks joined to no support (largest first, then by first block), with
/// whether each carries dead load, and the near misses (model.near_misses) at their blocks.
Connectivity check_connectivity(const model::Model& model);

/// The certificate of a structure that cannot stand for want of support: every block of a group
/// that carries dead load falls freely along gravity by one length unit of the model (the
/// max_translation normalisation), every other block stays at rest. Fills `mechanism.blocks`
/// and the interfaces (none of which cracks: a group moves as one piece).
void falling_groups_mechanism(const model::Model& model, const Connectivity& connectivity, Mechanism& mechanism);

/// The verdict for people: how many blocks no interface joins to a support, which (the first
/// ones by id), in how many groups, which touch nothing, and the near misses at them.
std::string unsupported_verdict_text(const model::Model& model, const Connectivity& connectivity);

}  // namespace rbla::analysis
