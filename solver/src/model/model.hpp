// Typed model of a masonry block structure. Nothing here knows about JSON: the io layer builds
// these objects after validation, defaults and unit conversion, and everything downstream reads
// only them.
//
// Internal units: metres and kilonewtons (unit weights kN/m^3). `Units` remembers what the file
// used so results can be written back in the user's units.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace rbla::model {

using Vec3 = Eigen::Vector3d;

/// Scale factors from the file's units to the internal ones (m, kN, kN/m^3).
struct Units {
  std::string length_name = "m";
  std::string force_name = "kN";
  std::string unit_weight_name = "kN/m3";
  double length_to_m = 1.0;            // metres per file length unit
  double force_to_kN = 1.0;            // kilonewtons per file force unit
  double unit_weight_to_kN_m3 = 1.0;   // (kN/m^3) per file unit-weight unit
};

/// A length for messages, given back in the user's unit ("12.5 mm"), to `digits` significant digits.
std::string length_text(double metres, const Units& units, int digits = 3);

enum class BlockRole { Free, Fixed, MovingSupport };
const char* to_string(BlockRole role);

struct Block {
  std::string id;
  std::string label;
  BlockRole role = BlockRole::Free;
  std::vector<Vec3> vertices;                // m
  std::vector<std::vector<int>> faces;       // outward (counter-clockwise seen from outside)
  double unit_weight = 0.0;                  // kN/m^3
  // Computed from the faces by the divergence theorem (geometry/polyhedron.hpp).
  double volume = 0.0;                       // m^3
  Vec3 centroid = Vec3::Zero();              // m
  // As the CAD reported them, when it did (m^3, m); kept for the comparison warning only.
  std::optional<double> cad_volume;
  std::optional<Vec3> cad_centroid;

  double weight() const { return unit_weight * volume; }  // kN
  bool is_support() const { return role != BlockRole::Free; }
};

/// A planar contact between two blocks. The unit normal points from block_a into block_b;
/// (normal, tangent1, tangent2) is a right-handed frame: normal x tangent1 = tangent2.
/// A contact force at a corner is f = N normal + T1 tangent1 + T2 tangent2 acting on block_b,
/// and -f on block_a.
struct ContactInterface {
  std::string id;
  std::string label;          // the CAD's own name, kept for the results
  int block_a = -1;
  int block_b = -1;
  std::vector<Vec3> polygon;  // m, corners in order: the contact points
  Vec3 normal = Vec3::UnitZ();
  Vec3 tangent1 = Vec3::UnitX();
  Vec3 tangent2 = Vec3::UnitY();
  Vec3 centroid = Vec3::Zero();  // m, area centroid of the polygon
  double area = 0.0;             // m^2
  double friction = 0.0;         // Coulomb coefficient mu (dimensionless)
  bool detected = false;         // true when found by interface detection, false when given
  int source_index = -1;         // given: position in the model file's /interfaces; detected: -1
};

/// A force and a moment on a block (kN, kN m), the force applied at `point` (m).
struct PointLoad {
  int block = -1;
  Vec3 force = Vec3::Zero();
  Vec3 point = Vec3::Zero();
  Vec3 moment = Vec3::Zero();
};

enum class AnalysisType { LoadMultiplier, Settlement };
enum class FrictionModel { Associative, NonAssociative };
enum class ConeKind { Exact, PyramidInscribed, PyramidCircumscribed };
enum class Formulation { Auto, ThreeD, Planar };
const char* to_string(AnalysisType value);
const char* to_string(FrictionModel value);
const char* to_string(ConeKind value);
const char* to_string(Formulation value);

struct AnalysisRequest {
  AnalysisType type = AnalysisType::LoadMultiplier;
  std::optional<Vec3> seismic_direction;    // unit, perpendicular to gravity
  Vec3 settlement_direction = -Vec3::UnitZ();  // unit
  FrictionModel friction_model = FrictionModel::Associative;
  ConeKind cone = ConeKind::Exact;
  int pyramid_faces = 8;
  Formulation formulation = Formulation::Auto;
  double tol_relative_gap = 1e-8;
  double tol_feasibility = 1e-8;
  // Non-associative scheme (analysis/non_associative.hpp): steps, the fixed-point test's relative
  // tolerance, the damping of the shifts, and warm starts from the previous step's iterate.
  int non_associative_max_iterations = 50;
  double non_associative_tolerance = 1e-3;
  double non_associative_damping = 0.5;
  bool non_associative_warm_start = true;
  // Go on after a certified state that matches its mechanism in work only, for one that matches
  // point by point (analysis/compatible_states.hpp).
  bool non_associative_pointwise_retry = true;
  // Runs of the scheme with different test schedules (analysis/non_associative.hpp): the
  // conservative certified state is reported, and all the states found.
  int non_associative_trajectories = 1;
  // With a pyramid cone and associative friction: also solve the other pyramid (inscribed and
  // circumscribed bracket the exact cone) and report both.
  bool pyramid_bracket = false;
  // Load multiplier: also check that alpha = 0 is admissible (one more solve; see
  // analysis::stands_only_when_pushed).
  bool check_dead_load = true;
  double time_limit_seconds = 0.0;  // 0: none
};

enum class DetectionMode { Auto, Off, Merge };

/// Interface detection settings (schema: `detection`; the schema's defaults are these,
/// tests/unit/test_schema_defaults.cpp keeps the two equal). By default every joint gets its own distance tolerance,
/// `joint_tolerance` times the size of its smaller face, so that what counts as touching follows
/// the blocks, not the size of the model; `distance_tolerance` or `relative_tolerance` replace
/// that by one tolerance for every joint.
struct DetectionSettings {
  DetectionMode mode = DetectionMode::Auto;
  /// Fraction of a joint's size (the diameter of the smaller of its two faces): the largest
  /// distance between the two faces' fitted planes over their overlap that still counts as
  /// touching, and how far a face may depart from its plane when split faces are merged.
  double joint_tolerance = 0.03;
  /// Of the bounding-box diagonal: one distance tolerance for every joint, when given.
  std::optional<double> relative_tolerance;
  std::optional<double> distance_tolerance;    // m, one tolerance for every joint; overrides the others
  /// Largest angle between one face's outward normal and the other's reversed normal (degrees);
  /// also the largest angle between neighbouring faces of a block merged into one face.
  double angle_tolerance_degrees = 10.0;
  double min_area_fraction = 1e-6;             // of the smaller face
  /// How many of the closest rejected face pairs are kept in `Model::near_misses`.
  int max_near_misses = 50;
};

/// The geometric tolerance of the model (m) where no joint is involved (vertex merging, planarity
/// of given interfaces, extrusion checks): this fraction of the structure's diagonal
/// (Model::structure_box) unless the model gives `detection.distance_tolerance` or
/// `detection.relative_tolerance`.
inline constexpr double kModelRelativeTolerance = 1e-4;

/// A gap wider than this many median block sizes along an axis separates blocks from the
/// structure when its extent is measured (Model::structure_box). Real structures have no such
/// gap between their parts; a survey marker or a terrain tile placed kilometres away does.
inline constexpr double kStructureGapBlocks = 10.0;

/// A pair of faces of different blocks that interface detection looked at and rejected: close and
/// nearly opposite, but outside its tolerances. Kept so that a verdict can say which joints were
/// missed and with which tolerances they would have been accepted.
struct NearMiss {
  int block_a = -1;
  int block_b = -1;
  int face_a = -1;              ///< index into blocks[block_a].faces
  int face_b = -1;              ///< index into blocks[block_b].faces
  double distance = 0.0;        ///< m, largest distance between the two face planes over the overlap
  double angle_degrees = 0.0;   ///< deviation of the outward normals from exactly opposite
  double overlap_area = 0.0;    ///< m^2, overlap of the two faces projected on their mid-plane
  double distance_tolerance = 0.0;  ///< m, the distance this pair had to be within
};

/// Min, median and max of a set of values (all 0 when the set is empty).
struct Spread {
  std::size_t count = 0;
  double min = 0.0;
  double median = 0.0;
  double max = 0.0;
};

/// What interface detection did, for `rbla info` and the result JSON.
/// Accepted joints whose gap is above half their tolerance, and the widest of them.
struct WideGaps {
  std::size_t joints = 0;
  double widest = 0.0;     ///< m
  double tolerance = 0.0;  ///< m, the widest one's
  double nearest = 0.0;    ///< m, the widest one's clearance (the nearest its faces come)
  int block_a = -1, block_b = -1;
};

/// Detected joints whose faces are more than the clearance limit apart over part of their overlap
/// (a face tilted onto its partner): only the part within it is a contact. The first one found.
struct JointsTouchingInPart {
  std::size_t joints = 0;
  double farthest = 0.0;  ///< m, the first one's faces at their farthest
  int block_a = -1, block_b = -1;
  double band = 0.0;      ///< m, how far beyond the nearest the faces bear
};

/// Detected joints dropped because a third block lies between their faces; the first one found.
struct JointsThroughBlocks {
  std::size_t joints = 0;
  int block_a = -1, block_b = -1;
  int between = -1;
};

struct DetectionSummary {
  bool ran = false;
  bool per_joint = true;             ///< tolerances from each joint's size (else one fixed tolerance)
  double joint_tolerance = 0.0;      ///< fraction of the joint size (per_joint)
  double clearance_limit = 0.0;      ///< m, the widest a joint's faces may be apart at their nearest (per_joint)
  double fixed_distance = 0.0;       ///< m (when !per_joint)
  double angle_tolerance_degrees = 0.0;
  Spread distance_tolerances;        ///< m, the distance tolerances the accepted joints were given
  Spread gaps;                       ///< m, largest plane-to-plane distance over each accepted joint
  Spread angles;                     ///< degrees, deviation from opposite of each accepted joint
  double largest_gap_fraction = 0.0; ///< the largest gap of an accepted joint over its tolerance
  WideGaps wide_gaps;
  JointsTouchingInPart touching_in_part;
  JointsThroughBlocks through_blocks;
  std::size_t candidate_block_pairs = 0;
  std::size_t face_pairs_tested = 0;
  std::size_t merged_faces = 0;      ///< faces merged into a neighbouring coplanar face of their block
  std::size_t interfaces_found = 0;
  std::size_t near_misses_total = 0; ///< all near misses; `Model::near_misses` keeps the closest
};

struct BoundingBox {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
  double diagonal() const { return (max - min).norm(); }
};

/// The axis-aligned box of `points` (zero at the origin when there are none).
BoundingBox bounding_box_of(const std::vector<Vec3>& points);

/// Something the user should know that did not stop the run. `pointer` is a JSON pointer
/// into the model file when the warning is about a place in it.
struct Warning {
  std::string code;
  std::string message;
  std::string pointer;
  /// How far off this instance is, in its code's own measure (a length in m, a ratio); the
  /// largest of a code is its worst instance. 0 when the code has no measure.
  double magnitude = 0.0;
};

struct Model {
  std::string title;
  Units units;
  Vec3 gravity = -Vec3::UnitZ();  // unit vector
  std::string gravity_axis = "-z";
  /// The model's `defaults` (the schema's defaults are these initialisers and those of the other
  /// structs here; tests/unit/test_schema_defaults.cpp keeps the two equal). The unit weight is
  /// in the file's unit-weight unit (units.unit_weight_name), as the file gives it.
  double default_unit_weight = 18.0;
  double default_friction = 0.6;
  std::vector<Block> blocks;
  std::vector<ContactInterface> interfaces;
  std::vector<PointLoad> dead_loads;
  std::vector<PointLoad> live_loads;
  AnalysisRequest analysis;
  bool analysis_given = false;
  DetectionSettings detection;
  std::unordered_map<std::string, int> block_index;  // id -> position in `blocks`
  std::vector<Warning> warnings;
  /// Face pairs interface detection rejected but that came close (filled by geometry::prepare_model),
  /// the closest first, at most detection.max_near_misses of them.
  std::vector<NearMiss> near_misses;
  DetectionSummary detection_summary;

  BoundingBox bounding_box() const;
  /// The box of the structure itself: the bounding box without the blocks that a wide gap along
  /// some axis separates from most of the others (structure_box in model.cpp). The default
  /// tolerances are relative to it.
  BoundingBox structure_box() const;
  /// The median of the blocks' bounding-box diagonals (0 without blocks): the block scale that a
  /// ground slab or a far marker block does not set.
  double median_block_size() const;
  std::size_t num_contact_points() const;
  /// The distance tolerance in metres actually used for geometry checks and detection: the
  /// given one, or a fraction (relative_tolerance, else kModelRelativeTolerance) of the diagonal
  /// of structure_box().
  double distance_tolerance() const;
  /// The axes angles in the horizontal plane are measured from and towards: x (y when gravity
  /// is along x) projected on the plane normal to gravity, and up cross that, so that angles
  /// turn counter-clockwise seen from above. With gravity along -z: +x and +y.
  std::pair<Vec3, Vec3> horizontal_axes() const;
  /// For each block, the blocks it shares an interface with (once per interface, in interface
  /// order). Without `through_supports`, interfaces that touch a support are left out: the
  /// contact graph of the free blocks alone.
  std::vector<std::vector<int>> neighbours(bool through_supports = true) const;
  /// The blocks (ascending indices) whose id or label is one of `names`. Names that pick nothing
  /// are appended to `unmatched`.
  std::vector<int> blocks_named(const std::vector<std::string>& names, std::vector<std::string>& unmatched) const;
  /// The interfaces (ascending indices) whose id or label is one of `interface_names`, or that
  /// touch a block whose id or label is one of `block_names`. Names that pick nothing are
  /// appended to `unmatched`.
  std::vector<int> interfaces_named(const std::vector<std::string>& interface_names,
                                    const std::vector<std::string>& block_names,
                                    std::vector<std::string>& unmatched) const;
};

}  // namespace rbla::model
