// What a limit analysis returns, as typed values in internal units (m, kN). The io layer turns
// it into the result JSON in the user's units; the svg writer draws it.
#pragma once

#include "model/model.hpp"
#include "rbla/conic/info.hpp"

#include <optional>
#include <utility>
#include <string>
#include <vector>

namespace rbla::analysis {

using model::Vec3;

/// The answer, in the user's terms (STYLE.md: "domain verdict on top").
enum class Verdict {
  Collapse,       ///< a mechanism forms at the load multiplier (or base reaction) reported
  NoMechanism,    ///< the live load can grow without bound: no collapse (alpha unbounded)
  CannotStand,    ///< the dead load alone cannot be carried: the falling blocks are reported
  SolverFailure,  ///< the conic solver failed numerically; no number is reported
  TimeLimit,      ///< the time limit ran out before an answer
  IterationLimit, ///< the interior-point iteration limit ran out before an answer
  Cancelled,      ///< the progress callback asked to stop
};
const char* to_string(Verdict verdict);  // the result schema's `status` values

/// State of one contact point in the mechanism, from the relative velocity of the two blocks.
enum class ContactState { Closed, Opening, Sliding, OpeningSliding };
/// State of an interface: as its points, or Hinge when some points open and the others stay closed.
enum class InterfaceState { Closed, Opening, Sliding, OpeningSliding, Hinge };
const char* to_string(ContactState state);
const char* to_string(InterfaceState state);

/// Virtual velocity of a block: translation of its centroid and rotation vector (rad), normalised
/// as `Mechanism::normalisation` says.
struct BlockMotion {
  Vec3 translation = Vec3::Zero();
  Vec3 rotation = Vec3::Zero();
  bool moving = false;  ///< part of the mechanism (or of the falling set when it cannot stand)
};

struct PointResult {
  Vec3 position = Vec3::Zero();           ///< m
  double normal_force = 0.0;              ///< kN, compression positive
  double shear1 = 0.0, shear2 = 0.0;      ///< kN, along the interface tangents
  Vec3 relative_velocity = Vec3::Zero();  ///< (normal, t1, t2) components of v_b - v_a, normalised like blocks
  ContactState state = ContactState::Closed;
};

struct InterfaceResult {
  InterfaceState state = InterfaceState::Closed;
  bool cracked = false;          ///< opening or sliding somewhere
  double normal_force = 0.0;     ///< kN, sum over points
  double shear_force = 0.0;      ///< kN, magnitude of the summed shear
  std::vector<PointResult> points;
};

enum class Normalisation { MaxTranslation, UnitSettlement };

struct Mechanism {
  Normalisation normalisation = Normalisation::MaxTranslation;
  std::vector<BlockMotion> blocks;          ///< one per model block (supports at rest, or settling)
  std::vector<InterfaceResult> interfaces;  ///< one per model interface
  std::vector<int> cracked_interfaces;      ///< indices into model.interfaces
  /// Blocks with no load whose motion is arbitrary and larger than any loaded block's
  /// (analysis/unloaded_blocks.hpp); empty in nearly every model.
  std::vector<int> arbitrary_blocks;
};

/// Virtual work of the mechanism (kN m, in the normalised velocities). Static-kinematic check:
/// alpha * live + dead = dissipation, so alpha_kinematic = (dissipation - dead) / live; for
/// settlement, base_reaction_kinematic = (dead - dissipation) / settlement velocity.
struct WorkBalance {
  double live_work = 0.0;
  double dead_work = 0.0;
  double dissipation = 0.0;      ///< friction work mu N |slip| at sliding points (non-associative); 0 otherwise
  double kinematic_value = 0.0;  ///< alpha (dimensionless) or base reaction (kN) from the balance
  double relative_error = 0.0;   ///< |static - kinematic| / max(1, |static|) (force units for reactions)
};

struct Accuracy {
  double relative_gap = 0.0;
  double primal_residual = 0.0;
  double dual_residual = 0.0;
  double equilibrium_residual = 0.0;  ///< kN: largest force imbalance of a block, from the forces reported
  /// Associative pyramids only, when asked (analysis.pyramid_bracket): the value (alpha, or the
  /// base reaction in kN) with the inscribed and with the circumscribed pyramid.
  std::optional<std::pair<double, double>> pyramid_bracket;
};

/// One solve of the non-associative scheme (analysis/non_associative.hpp); step 0 is the
/// associative solve.
struct NonAssociativeStep {
  int iteration = 0;
  double value = 0.0;       ///< alpha, or the base reaction in kN, of the step's state
  /// Work of the normal forces on the normal motion of the contact points (sum N |d_n|), relative
  /// to the value: how far the state is from compatible with a mechanism without dilatancy (0).
  double dilatancy = 0.0;
  double shift_change = 0.0;  ///< largest change of the shifts s_k it produced, relative to the largest
  double max_normal_force_change = 0.0;  ///< kN, largest change of a point's normal force from the previous step
  int interior_point_iterations = 0;
  double seconds = 0.0;       ///< of the step's conic solve
};

/// When the non-associative scheme tests its candidate state (analysis/non_associative.cpp): every
/// `when_close` steps once a step's own state dilates by less than 1 % of its value, and at
/// least every `at_most` steps.
struct TestSchedule {
  int when_close = 3;
  int at_most = 10;
};

/// One run of the non-associative scheme (analysis.non_associative.trajectories runs, each with
/// its own test schedule).
struct NonAssociativeTrajectory {
  TestSchedule schedule;
  double value = 0.0;  ///< alpha, or the base reaction in kN, of the state the run ended with
  bool converged = false;  ///< the state passed the fixed-point test
  /// the state matches its mechanism point by point (AnalysisResult::non_associative_pointwise)
  std::optional<bool> pointwise;
  int steps = 0;
  int checks = 0;
  double seconds = 0.0;  ///< of the run's conic solves
  int step_iterations = 0;  ///< interior-point iterations of the steps' solves
  /// of the other solves: the selections of the conservative state, the fixed-point tests and
  /// the range (the associative solve before the run is in neither)
  int test_iterations = 0;
};

/// What a Sensitivities record differentiates.
enum class SensitivityOf { LoadMultiplier, BaseReaction };

/// First derivatives of alpha, or under settlement of the base reaction R (kN), at the collapse
/// found (analysis/sensitivities.hpp): associative friction only. Where the collapse mechanism
/// would change with the parameter (a kink), these are the derivatives along this mechanism:
/// one-sided values.
struct Sensitivities {
  SensitivityOf quantity = SensitivityOf::LoadMultiplier;
  /// d value / d s with every interface's friction coefficient mu_k scaled to s mu_k, at s = 1.
  double friction_factor = 0.0;
  /// (interface index, d value / d mu_k) for the interfaces where it is not zero.
  std::vector<std::pair<int, double>> interface_friction;
  /// (block index, d value / d unit weight, in 1 / (kN/m^3) for alpha, m^3 for R) for the
  /// blocks that move.
  std::vector<std::pair<int, double>> block_unit_weight;
};

struct ProblemSize {
  long num_variables = 0;
  long num_equality_rows = 0;
  long num_cones = 0;
  long num_nonzeros = 0;
};

/// Free blocks that no chain of interfaces joins to a support (analysis/connectivity.hpp): they
/// are joined among themselves (or a single block) and to nothing that could hold them.
struct UnsupportedGroup {
  std::vector<int> blocks;        ///< indices into model.blocks, ascending
  bool touches_nothing = false;   ///< a single block with no interface at all
  bool carries_dead_load = true;  ///< false: weightless and unloaded, nothing makes it fall
};

/// What the connectivity check found before any solve.
struct Connectivity {
  bool checked = false;
  std::vector<UnsupportedGroup> groups;
  std::size_t num_near_misses = 0;         ///< model.near_misses.size()
  std::vector<int> near_misses_at_groups;  ///< indices into model.near_misses with a block of a group
  /// Blocks in groups that carry dead load: the structure cannot stand while they exist.
  std::size_t num_falling_blocks() const {
    std::size_t n = 0;
    for (const auto& group : groups) n += group.carries_dead_load ? group.blocks.size() : 0;
    return n;
  }
};

struct AnalysisResult {
  Verdict verdict = Verdict::SolverFailure;
  std::string verdict_text;  ///< one sentence for people

  model::AnalysisType type = model::AnalysisType::LoadMultiplier;
  model::FrictionModel friction_model = model::FrictionModel::Associative;
  model::ConeKind cone = model::ConeKind::Exact;
  int pyramid_faces = 0;
  bool planar = false;
  int planar_axis = -1;  ///< 0, 1, 2 for x, y, z when planar

  std::optional<double> load_multiplier;  ///< when Collapse in a load-multiplier analysis
  std::optional<double> base_reaction;    ///< kN, when Collapse in a settlement analysis
  /// The smallest admissible load multiplier, when it is above zero: the structure stands only
  /// while pushed by at least this much live load (CannotStand).
  std::optional<double> minimum_load_multiplier;
  /// kN, the reaction before settlement (analysis/initial_reaction.hpp: the structure as one rigid
  /// body on uniformly elastic ground); with Collapse under settlement, when defined.
  std::optional<double> initial_base_reaction;
  bool initial_base_lifts = false;  ///< part of the base is out of contact in that initial state
  /// NoMechanism under settlement because every state that holds the structure pushes the moving
  /// supports back against the settlement direction (analysis/settlement_bound.hpp); false when
  /// their reaction along it merely can fall to 0.
  bool settlement_pushes_back = false;
  Vec3 settlement_direction = Vec3::Zero();

  Mechanism mechanism;  ///< filled for Collapse and CannotStand (falling blocks)
  WorkBalance work;
  Accuracy accuracy;

  Connectivity connectivity;
  bool solver_ran = false;                        ///< false when no conic solve ran (solver_info is then empty)
  conic::Info solver_info;                        ///< of the last conic solve
  std::vector<conic::IterationRow> interior_point_history;  ///< of the last conic solve
  std::vector<NonAssociativeStep> non_associative;
  bool non_associative_converged = false;
  std::string non_associative_stop;  ///< why the scheme stopped, for people
  int non_associative_checks = 0;    ///< fixed-point tests (solves of the capped problem)
  /// Of the last test: how much more the capped problem carries than the state, relative to
  /// its value (alpha_capped - alpha, or R - R_capped, over the value); 0 at a fixed point.
  double non_associative_gap = 0.0;
  /// The values of all states compatible with the mechanism found (alpha, or R in kN): non-
  /// associative collapse is not unique; the conservative end is the one reported.
  std::optional<std::pair<double, double>> non_associative_range;
  /// Whether the certified mechanism admits states compatible with it point by point (no force
  /// where it opens, the full friction where it slides; compatible_states.hpp): true when it
  /// does (the state reported and the range are then such states), false when no equilibrated
  /// state is (the certificate holds in work only). Empty when not checked.
  std::optional<bool> non_associative_pointwise;
  /// When non_associative_pointwise is false, in the state reported: the largest normal force
  /// at a point that opens, and the largest shortfall of friction at a point that slides, both
  /// over the largest normal force of any point.
  double non_associative_open_force = 0.0;
  double non_associative_friction_shortfall = 0.0;
  /// The associative value of the same model (alpha, or R in kN), the scheme's first solve. Every
  /// non-associative collapse state has forces admissible for the associative problem, so its
  /// alpha is at most this and its R at least this (static theorem; Drucker 1954): a proven
  /// one-sided bound, whatever state the scheme certifies. Set when the scheme ran.
  std::optional<double> non_associative_bound;
  /// Every run of the scheme, in schedule order; non_associative_reported is the one whose state
  /// is reported (the conservative certified one).
  std::vector<NonAssociativeTrajectory> non_associative_trajectories;
  int non_associative_reported = 0;
  std::optional<Sensitivities> sensitivities;  ///< associative collapse only
  ProblemSize size;

  double assemble_seconds = 0.0;
  double solve_seconds = 0.0;
  double mechanism_seconds = 0.0;
  std::vector<model::Warning> warnings;
};

}  // namespace rbla::analysis
