// The static (lower-bound) problem of rigid block limit analysis as a conic program
// (docs/method.md; Portioli et al. 2014, eq. 1; Portioli & Cascini 2016 for the moving support):
//
//   maximise alpha  subject to  A c + f_D + alpha f_L = 0,  contact forces c in their friction sets,
//
// or, under settlement, minimise the base reaction R of the moving supports. The conic layer sees
// only matrices and cones; this file is the only place that turns blocks into them.
#pragma once

#include "model/model.hpp"
#include "rbla/conic/problem.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace rbla::analysis {

using model::Vec3;

/// A planar scene: every free block a right prism along `axis` over the same depth, every
/// interface spanning that depth, every load in the mid-plane (formulation.cpp says why that is
/// exact). Then each block has 3 equations and the problem is a linear program (the capped
/// problem of the non-associative test excepted: its |T| <= r is a two-dimensional cone).
struct PlanarFrame {
  bool planar = false;
  int axis = -1;              ///< extrusion axis (0 x, 1 y, 2 z)
  Vec3 normal = Vec3::Zero();  ///< unit vector along the axis
  Vec3 e1 = Vec3::Zero();      ///< in-plane basis, e1 x e2 = normal
  Vec3 e2 = Vec3::Zero();
  std::string reason;          ///< why the scene is not planar (for messages), when it is not
};

/// Finds the extrusion axis of a planar scene, if there is one (the thinnest qualifying axis).
PlanarFrame detect_planar(const model::Model& model);

/// How friction is represented at a contact point.
enum class FrictionSet {
  Cone,      ///< associative: ||T|| <= mu N (exact second-order cone, or a pyramid)
  Cylinder,  ///< non-associative step: N >= 0 and ||T|| <= r, r fixed (Gilbert et al. 2006)
};

/// Force basis of one variable: the force it exerts on block_b per unit value, in units of its
/// point's force_scale.
struct Generator {
  int variable = 0;
  Vec3 force = Vec3::Zero();
};

/// A contact point of the formulation. In 3-D one per interface corner; in a planar scene one
/// per distinct corner of the interface's projection (two coincident corners of an extruded
/// interface make one planar point, carrying their summed force).
struct FormulationPoint {
  int interface_index = -1;
  std::vector<int> corners;  ///< indices into the interface polygon represented by this point
  Vec3 position = Vec3::Zero();
  double friction = 0.0;
  double force_scale = 1.0;  ///< kN per unit of this point's variables (its interface's scale)
  double load = 1.0;         ///< kN: the smaller load carried by its interface's blocks (ForceScales::interface_load)
  std::vector<Generator> generators;
  int radius_row = -1;  ///< cylinder: the row fixing the radius (rho = r; the pyramid's: sum of the
                        ///< tangential budget and its slack = r)
};

struct FormulationOptions {
  model::ConeKind cone = model::ConeKind::Exact;
  int pyramid_faces = 8;
  FrictionSet friction_set = FrictionSet::Cone;
  bool planar = false;  ///< use `frame` (from detect_planar) and 3 equations per block
  PlanarFrame frame;
  /// Keep every seismic-load entry of the multiplier's column, zero or not, so that the sparsity
  /// pattern is the same for every seismic direction: a search over directions then reuses one
  /// symbolic factorisation (analysis/solver_reuse.hpp). Off for a single analysis, whose
  /// factorisation the explicit zeros would only perturb.
  bool pattern_for_every_direction = false;
};

/// The conic problem plus everything needed to read its solution back as forces and velocities.
struct Formulation {
  conic::ConicProblem problem;
  FormulationOptions options;
  double length_scale = 1.0;  ///< m: moment rows are divided by it
  /// kN: the mean free-block weight. The settlement row and R are in units of it; block rows and
  /// contact variables have their own scales (block_scale, FormulationPoint::force_scale), equal
  /// to it unless the model's loads span more than kForceScaleBand (analysis/force_scales.hpp).
  double force_scale = 1.0;
  int multiplier_variable = 0;  ///< alpha (the copy the objective sees), or R / force_scale under settlement
  int rows_per_block = 6;
  /// First equilibrium row of each block; -1 for fixed supports. Under settlement all moving
  /// supports share one row (their summed load along the settlement direction).
  std::vector<int> block_row;
  /// kN, per block: its force rows are divided by it, its moment rows by it times length_scale.
  std::vector<double> block_scale;
  /// The smallest own load (weight and point loads) of a block with a scale other than
  /// force_scale, relative to that scale; 1 when every block uses force_scale. A solve whose
  /// feasibility tolerance is loosened should loosen it by no more than this times the usual.
  double rhs_resolution = 1.0;
  std::vector<FormulationPoint> points;
  bool settlement = false;
  Vec3 settlement_direction = Vec3::Zero();
  int num_radius_rows = 0;
  int first_radius_row = 0;
  /// Rows alpha_a = alpha_b tying the per-block copies of the load multiplier (last rows).
  int num_tie_rows = 0;
  /// What the formulation could not do well (weight contrasts beyond what scaling resolves).
  std::vector<model::Warning> warnings;

  /// Forces at every formulation point (kN, global frame) from a primal solution x.
  std::vector<Vec3> point_forces(const Eigen::VectorXd& x) const;
  /// Right-hand side with the cylinder radii (kN, one per point) in the radius rows.
  Eigen::VectorXd rhs_with_radii(const std::vector<double>& radii_kN) const;
};

/// Builds the conic problem. Non-dimensionalised (docs/method.md, "Scaling"): forces in units
/// of the mean free-block weight (or, for blocks and interfaces whose carried loads lie far from
/// it, of their own loads: analysis/force_scales.hpp), moments additionally divided by the mean
/// block size, so mm and m models, N and kN, solve identically. Throws model::ModelError for
/// requests the scene cannot meet (planar forced on a 3-D scene).
Formulation build_formulation(const model::Model& model, const FormulationOptions& options);

}  // namespace rbla::analysis
