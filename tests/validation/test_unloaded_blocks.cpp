// Blocks that no load acts on (analysis/unloaded_blocks.hpp): their motion does no work, so the
// solver's mechanism may carry any amount of it. The reported mechanism must be the exact one of
// the loaded blocks with the weightless ones at rest or riding along, not a lift-off that marks
// joints as cracked and blocks as moving.
#include "analysis/formulation.hpp"
#include "analysis/mechanism.hpp"
#include "analysis/unloaded_blocks.hpp"
#include "rbla/conic/solver.hpp"
#include "validation_helpers.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rbla::validation {
namespace {

using model::Vec3;

/// A block C0 (0.5 wide, 1 high) rocks on a fixed base at alpha = b/h = 0.5 (mu = 0.6); C1, as
/// large, stands on it, and `loose`, small, stands on the base beside it: both weightless.
json column_with_weightless_blocks(const std::string& formulation, const std::string& friction_model) {
  json blocks = json::array({box_block("base", -0.5, -0.5, -0.5, 1.0, 1.5, 0.0, "fixed"),
                             box_block("C0", 0.0, 0.0, 0.0, 0.5, 1.0, 1.0),
                             box_block("C1", 0.0, 0.0, 1.0, 0.5, 1.0, 2.0),
                             box_block("loose", 0.7, 0.0, 0.0, 0.9, 1.0, 0.3)});
  blocks[2]["unit_weight"] = 0.0;
  blocks[3]["unit_weight"] = 0.0;
  Case s;
  s.formulation = formulation;
  s.friction_model = friction_model;
  return finish(blocks, s);
}

Vec3 carried_translation(const AnalysisResult& r, int from, const Vec3& from_centroid, const Vec3& to_centroid) {
  const auto& motion = r.mechanism.blocks[from];
  return motion.translation + motion.rotation.cross(to_centroid - from_centroid);
}

TEST(UnloadedBlocks, RideWithTheMechanismOrStayAtRest) {
  const Vec3 g0(0.25, 0.5, 0.5), g1(0.25, 0.5, 1.5);
  for (const std::string formulation : {"planar", "3d"}) {
    for (const std::string friction_model : {"associative", "non_associative"}) {
      SCOPED_TRACE(formulation + " " + friction_model);
      const json model = column_with_weightless_blocks(formulation, friction_model);
      const AnalysisResult r = run(model);
      EXPECT_LT(relative_error(alpha_of(r), 0.5), 1e-6);
      const auto& c0 = r.mechanism.blocks[1];
      const auto& c1 = r.mechanism.blocks[2];
      const auto& loose = r.mechanism.blocks[3];
      const double scale = c0.translation.norm();
      ASSERT_GT(scale, 0.0);
      // C0 turns about its toe (0.5, y, 0); C1 turns with it, as one piece.
      EXPECT_LT((c1.translation - carried_translation(r, 1, g0, g1)).norm(), 1e-6 * scale);
      EXPECT_LT((c1.rotation - c0.rotation).norm(), 1e-6 * c0.rotation.norm());
      EXPECT_LT(loose.translation.norm() + loose.rotation.norm(), 1e-9 * scale);
      EXPECT_TRUE(c0.moving);
      EXPECT_TRUE(c1.moving);
      EXPECT_FALSE(loose.moving);
      // Only the base joint under C0 cracks.
      ASSERT_EQ(r.mechanism.cracked_interfaces.size(), 1u) << r.verdict_text;
      const auto loaded = rbla::io::load_model_text(model.dump());
      const auto& cracked = loaded.model.interfaces[r.mechanism.cracked_interfaces[0]];
      EXPECT_EQ(cracked.block_a + cracked.block_b, 1) << "the base (0) and C0 (1)";
      EXPECT_LT(r.work.relative_error, 1e-6);
      for (const auto& w : r.warnings) EXPECT_NE(w.code, "unloaded_block_motion") << w.message;
    }
  }
}

// A weightless lintel U spans a rocking pier A and a fixed pillar P: at rest, A's rising heel
// would enter U; riding with A, U would enter P; with P it is at rest. No candidate fits, so an
// arbitrary lift of U (here added by hand, larger than any loaded motion) is kept and reported.
TEST(UnloadedBlocks, AnUnsettledBlockIsReported) {
  json blocks = json::array({box_block("base", -0.5, -0.5, -0.5, 2.0, 1.5, 0.0, "fixed"),
                             box_block("A", 0.0, 0.0, 0.0, 0.5, 1.0, 1.0),
                             box_block("P", 1.0, 0.0, 0.0, 1.5, 1.0, 1.0, "fixed"),
                             box_block("U", 0.0, 0.0, 1.0, 1.5, 1.0, 1.2)});
  blocks[3]["unit_weight"] = 0.0;
  Case s;
  s.formulation = "3d";
  const auto loaded = rbla::io::load_model_text(finish(blocks, s).dump());
  const model::Model& m = loaded.model;
  const analysis::Formulation f = analysis::build_formulation(m, {});
  conic::ConicSolver solver(f.problem, conic::Settings{});
  conic::Solution solution = solver.solve();
  ASSERT_TRUE(conic::has_solution(solution.info.status));
  ASSERT_EQ(analysis::unloaded_blocks(m, f), std::vector<int>{3});

  // A lift of U alone keeps the dual feasible and its objective: still an optimal mechanism.
  std::vector<analysis::BlockMotion> motions = analysis::block_velocities(m, f, solution.y);
  double largest = 0.0;
  for (const Vec3& v : m.blocks[1].vertices) {
    largest = std::max(largest, analysis::point_velocity(m, motions, 1, v).norm());
  }
  ASSERT_GT(largest, 0.0);
  motions[3].translation += Vec3(0.0, 0.0, 10.0 * largest);
  analysis::set_block_multipliers(f, 3, motions[3], solution.y);
  const analysis::UnloadedBlocks settled = analysis::settle_unloaded_blocks(m, f, f.problem.c, solution.y);
  EXPECT_TRUE(settled.settled.empty());
  EXPECT_EQ(settled.unsettled, std::vector<int>{3});
}

}  // namespace
}  // namespace rbla::validation
