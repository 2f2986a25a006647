// An analysis started from the interior point of a nearby model (AnalysisOptions::warm_start,
// as the searches do) lands on the same answer as a cold one, and a point of another size (the
// planar LP's, offered to the 3-D cones) is ignored.
#include "validation_helpers.hpp"

#include <string>

namespace rbla::validation {
namespace {

TEST(WarmStart, LandsOnTheColdAnswerAndKeepsTheNextPoint) {
  auto loaded = rbla::io::load_model_file(std::string(RBLA_SOURCE_DIR) + "/samples/wall_opening.json");
  model::Model m = loaded.model;
  const double cold = *rbla::analysis::analyse(m).load_multiplier;

  conic::Iterate point;
  rbla::analysis::AnalysisOptions warm;
  warm.warm_start = &point;
  model::Model nearby = m;
  for (auto& contact : nearby.interfaces) contact.friction *= 1.05;
  ASSERT_EQ(rbla::analysis::analyse(nearby, warm).verdict, Verdict::Collapse);
  ASSERT_FALSE(point.empty());
  const auto started = rbla::analysis::analyse(m, warm);
  ASSERT_EQ(started.verdict, Verdict::Collapse);
  EXPECT_LT(relative_error(*started.load_multiplier, cold), 1e-7) << *started.load_multiplier << " vs " << cold;
  EXPECT_FALSE(point.empty());

  // The planar LP's point does not fit the 3-D problem: the solve starts cold.
  m.analysis.formulation = model::Formulation::ThreeD;
  const double cold_3d = *rbla::analysis::analyse(m).load_multiplier;
  const auto from_planar = rbla::analysis::analyse(m, warm);
  ASSERT_EQ(from_planar.verdict, Verdict::Collapse);
  EXPECT_LT(relative_error(*from_planar.load_multiplier, cold_3d), 1e-7);
}

}  // namespace
}  // namespace rbla::validation
