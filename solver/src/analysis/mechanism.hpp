// Reading a conic solution back as contact forces and a collapse mechanism: block velocities,
// which blocks move, which interfaces crack.
#pragma once

#include "analysis/analysis_result.hpp"
#include "analysis/formulation.hpp"
#include "model/model.hpp"

#include <Eigen/Core>

#include <vector>

namespace rbla::analysis {

/// Which blocks belong to a mechanism (or fall, in a cannot-stand certificate: MotionKind): a
/// block whose largest vertex displacement is at least this fraction of the largest of any block,
/// and every block joined to such a block through interfaces that do not crack (it moves with it,
/// as one rigid piece). Interior-point mechanisms and certificates lie in the relative interior of their
/// optimal faces, so every block carries some motion: on a 1919-block facade that lost three
/// ground joints, the 12 blocks of the falling corner moved by 0.24 to 1 of the largest
/// displacement and the next block by 0.038, while all 1919 moved by more than 1e-4 of it.
inline constexpr double kMovingFraction = 0.05;

/// An interface cracks (opens or slides) when one of its blocks belongs to the mechanism and the
/// relative displacement at one of its points is at least this fraction of the largest vertex
/// displacement of its two blocks. That reference carries both the mechanism's scale and the
/// blocks' size (a block turning by theta moves by theta times its size), so a hinge at the foot
/// of a tall wall counts as much as one at its top, where a fraction of the largest displacement
/// of the whole mechanism would lose it (its opening is the wall's thickness over its height
/// times that). A block rocking on its joint opens it by width / diagonal of its own largest
/// displacement: 2 % keeps the hinges of blocks up to 1:50. Points use the same threshold.
inline constexpr double kCrackFraction = 0.02;

/// Block velocities from the equality multipliers y. The multipliers of a block's equilibrium
/// rows are minus its virtual velocity (the dual of A c = b is c^T.. = y^T A, so y^T A c is the
/// virtual power of the contact forces; docs/method.md, "The kinematic side: the mechanism"). Moment rows were
/// divided by the length scale, so rotations are rescaled by it. Not yet normalised.
std::vector<BlockMotion> block_velocities(const model::Model& model, const Formulation& formulation,
                                          const Eigen::VectorXd& y);

/// The inverse of block_velocities for one free block: writes the multipliers of its rows that
/// give it `motion` (in a planar formulation only the in-plane part of the motion is kept).
void set_block_multipliers(const Formulation& formulation, int block, const BlockMotion& motion,
                           Eigen::VectorXd& y);

/// Velocity of a point p of block i: u_i + theta_i x (p - g_i).
Vec3 point_velocity(const model::Model& model, const std::vector<BlockMotion>& motions, int block, const Vec3& p);

/// Relative velocity (block_b minus block_a) at every point of the formulation, for the mechanism
/// whose equality multipliers are y (block_velocities).
std::vector<Vec3> formulation_point_velocities(const model::Model& model, const Formulation& formulation,
                                               const Eigen::VectorXd& y);

/// Largest vertex speed of one block under `motion` (m per unit of the motion).
double block_speed(const model::Block& block, const BlockMotion& motion);

/// Largest vertex speed of every block (m per unit of the motions).
std::vector<double> block_speeds(const model::Model& model, const std::vector<BlockMotion>& motions);

/// Scales the motions so the largest vertex speed of a free block (MaxTranslation) or the
/// settlement velocity (UnitSettlement) equals `target` metres. Returns the factor applied (0 when
/// the motion is zero). Which blocks move is decided with the interfaces (fill_interfaces).
double normalise(const model::Model& model, const Formulation& formulation, Normalisation normalisation,
                 double target, std::vector<BlockMotion>& motions);

/// Contact forces of the formulation points shared among the interface corners they stand for
/// (kN, one list per model interface, in polygon order).
std::vector<std::vector<Vec3>> corner_forces(const model::Model& model, const Formulation& formulation,
                                             const std::vector<Vec3>& point_forces);

/// What the block motions are: a collapse mechanism, or the certificate of a structure that
/// cannot stand. A certificate is any motion on which the dead load does positive work, and the
/// solver's lies inside the cone of them: besides the blocks that fall it may lift others a
/// little (a rocking corner at the far end of a wall moved by 5 % of the largest displacement).
/// Only blocks that go down (positive work of their dead load) start its falling set.
enum class MotionKind { Mechanism, Certificate };

/// Per-interface forces, relative velocities and states, the list of cracked interfaces
/// (kCrackFraction) and the blocks that move (kMovingFraction), from the block motions already in
/// `mechanism.blocks`. `corner_forces` as corner_forces() gives them, or empty for no forces.
/// `associative` decides whether dilatant sliding counts as sliding.
void fill_interfaces(const model::Model& model, const std::vector<std::vector<Vec3>>& corner_forces,
                     bool associative, Mechanism& mechanism, MotionKind kind = MotionKind::Mechanism);

}  // namespace rbla::analysis
