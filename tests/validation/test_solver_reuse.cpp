// One conic solver kept between the analyses of a search (AnalysisOptions::reuse,
// analysis/solver_reuse.hpp): every analysis gets the answer and the iteration count of a new
// solver on its own, the symbolic analysis runs once per shape of problem, and a problem of
// another shape gets a solver of its own.
#include "validation_helpers.hpp"

#include <string>
#include <vector>

namespace rbla::validation {
namespace {

model::Model wall_opening() {
  return rbla::io::load_model_file(std::string(RBLA_SOURCE_DIR) + "/samples/wall_opening.json").model;
}

/// The sample at a friction factor, a unit-weight factor and a seismic direction in the wall's
/// plane turned towards its normal by `out_of_plane` (radians).
model::Model varied(const model::Model& base, double friction, double weight, double out_of_plane) {
  model::Model m = base;
  for (auto& contact : m.interfaces) contact.friction *= friction;
  for (auto& block : m.blocks) block.unit_weight *= weight;
  m.analysis.seismic_direction = model::Vec3(std::cos(out_of_plane), std::sin(out_of_plane), 0.0);
  return m;
}

struct Outcome {
  double value = 0.0;
  int iterations = 0;
};

Outcome outcome(const AnalysisResult& r) {
  EXPECT_EQ(r.verdict, Verdict::Collapse);
  return {r.load_multiplier.value_or(0.0), r.solver_info.iterations};
}

/// Each model analysed on the kept solvers and on a new solver of its own (the same formulation:
/// a search's keeps the seismic column's zeros, FormulationOptions::pattern_for_every_direction),
/// and by a plain analysis, whose formulation drops them: the same value to the solves' accuracy
/// (`plain_tolerance`, relative).
void expect_reuse_matches_new_solvers(const std::vector<model::Model>& family, int expected_builds,
                                      double plain_tolerance = 1e-7) {
  rbla::analysis::SolverReuse solvers;
  rbla::analysis::AnalysisOptions reusing;
  reusing.reuse = &solvers;
  for (std::size_t k = 0; k < family.size(); ++k) {
    rbla::analysis::SolverReuse own;
    rbla::analysis::AnalysisOptions alone;
    alone.reuse = &own;
    const Outcome fresh = outcome(rbla::analysis::analyse(family[k], alone));
    const Outcome reused = outcome(rbla::analysis::analyse(family[k], reusing));
    const Outcome plain = outcome(rbla::analysis::analyse(family[k]));
    EXPECT_LT(relative_error(reused.value, fresh.value), 1e-10) << "model " << k;
    EXPECT_EQ(reused.iterations, fresh.iterations) << "model " << k;
    EXPECT_LT(relative_error(reused.value, plain.value), plain_tolerance) << "model " << k;
  }
  EXPECT_EQ(solvers.built(), expected_builds);
  EXPECT_EQ(solvers.built() + solvers.reused(), static_cast<int>(family.size()));
}

TEST(SolverReuse, FrictionAndWeightsInThePlaneOneSymbolicAnalysis) {
  const model::Model base = wall_opening();
  std::vector<model::Model> family;
  for (double friction : {1.0, 0.7, 1.3}) family.push_back(varied(base, friction, 1.0, 0.0));
  family.push_back(varied(base, 1.0, 1.4, 0.0));
  expect_reuse_matches_new_solvers(family, 1);
}

TEST(SolverReuse, DirectionsAndFrictionWithThreeDimensionalCones) {
  model::Model base = wall_opening();
  base.analysis.formulation = model::Formulation::ThreeD;
  // Along x and along y a force component and a moment component vanish, and not in between:
  // the searches' formulation keeps them, so one pattern serves every direction.
  std::vector<model::Model> family;
  for (double turn : {0.0, 0.5}) family.push_back(varied(base, 1.0, 1.0, turn));
  family.push_back(varied(base, 1.0, 1.0, 0.0));
  family.back().analysis.seismic_direction = model::Vec3(0.0, 1.0, 0.0);
  family.push_back(varied(base, 0.8, 1.0, 0.5));
  expect_reuse_matches_new_solvers(family, 1);
}

TEST(SolverReuse, NonAssociativeStepsOnAKeptSolver) {
  model::Model base = wall_opening();
  base.analysis.friction_model = model::FrictionModel::NonAssociative;
  std::vector<model::Model> family;
  for (double friction : {1.0, 0.8}) family.push_back(varied(base, friction, 1.0, 0.0));
  // The reported state is an end of the optimal face of the problem shifted by the certified
  // mechanism's slip rates, so the mechanism's own accuracy (a dual, 1e-6 or so) reaches the
  // value: the two formulations agreed to 1.3e-7.
  expect_reuse_matches_new_solvers(family, 1, 1e-6);
}

TEST(SolverReuse, AnotherShapeGetsASolverOfItsOwnAndTwoAreKept) {
  const model::Model planar = varied(wall_opening(), 1.0, 1.0, 0.0);
  model::Model cones = planar;
  cones.analysis.formulation = model::Formulation::ThreeD;
  model::Model pyramid = cones;
  pyramid.analysis.cone = model::ConeKind::PyramidInscribed;
  // planar, cones: two built; planar, cones again: both kept; pyramid: a third, in place of the
  // planar one (used least recently); planar: built again.
  expect_reuse_matches_new_solvers({planar, cones, planar, cones, pyramid, cones, planar}, 4);
}

}  // namespace
}  // namespace rbla::validation
