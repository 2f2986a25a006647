// Reading a conic solution back as contact forces and a collapse mechanism.
#pragma once

#include "analysis/analysis_result.hpp"
#include "analysis/formulation.hpp"
#include "model/model.hpp"

#include <Eigen/Core>

#include <vector>

namespace rbla::analysis {

/// Block velocities from the equality multipliers y. The multipliers of a block's equilibrium
/// rows are minus its virtual velocity (the dual of A c = b is c^T.. = y^T A, so y^T A c is the
/// virtual power of the contact forces; METHOD.md, "Kinematic (dual) side"). Moment rows were
/// divided by the length scale, so rotations are rescaled by it. Not yet normalised.
std::vector<BlockMotion> block_velocities(const model::Model& model, const Formulation& formulation,
                                          const Eigen::VectorXd& y);

/// Velocity of a point p of block i: u_i + theta_i x (p - g_i).
Vec3 point_velocity(const model::Model& model, const std::vector<BlockMotion>& motions, int block, const Vec3& p);

/// Scales the motions so the largest vertex speed of a free block (MaxTranslation) or the
/// settlement velocity (UnitSettlement) equals `target` metres; marks the moving blocks. Returns
/// the factor applied (0 when the motion is zero).
double normalise(const model::Model& model, const Formulation& formulation, Normalisation normalisation,
                 double target, std::vector<BlockMotion>& motions);

/// Per-interface forces (from the point forces), relative velocities and states, and the list
/// of cracked interfaces. `associative` decides whether dilatant sliding counts as sliding.
void fill_interfaces(const model::Model& model, const Formulation& formulation, const std::vector<Vec3>& point_forces,
                     bool associative, Mechanism& mechanism);

}  // namespace rbla::analysis
