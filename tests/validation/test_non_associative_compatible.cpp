// The non-associative value and range are those of the states compatible with the reported
// mechanism, checked by a linear program built here from the result's block motions and contact
// points and the model's weights, not by the scheme's own formulation.
//
// A state (forces c, mechanism v) is a non-associative collapse state when c is in equilibrium at
// the load value and inside every friction cone, v does not interpenetrate nor dilate where it
// slides, and the two are compatible: a point that opens carries no force, a point that slides
// carries mu N against its slip, a point that stays closed anything in its cone
// (docs/method.md, "Non-associative friction"). Given v, these states form a polytope; rbla reports
// its lowest load multiplier and the range of it. An independent review found the reported value
// and range were those of another set (the states optimal for the step that led to the mechanism):
// on a 44-block wall rbla reported 0.5177 and the range [0.5177, 0.5177], where the states
// compatible with its own mechanism go from 0.4868 to 0.5195.
//
// Planar scenes (walls in the x-z plane under in-plane seismic load +x): force N n + T t at each
// contact point, t = y x n in the plane, three equilibrium equations per free block.

#include "validation_helpers.hpp"

#include "analysis/compatible_states.hpp"
#include "rbla/conic/solver.hpp"

#include <gtest/gtest.h>

#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <vector>

namespace rbla::validation {
namespace {

enum class PointMotion { Opens, SlidesPositive, SlidesNegative, Closed };

struct ContactPoint {
  int block_a = -1, block_b = -1;  // force N n + T t acts on b, its opposite on a
  model::Vec3 position, normal, tangent;
  double friction = 0.0;
  PointMotion motion = PointMotion::Closed;
};

model::Vec3 velocity_at(const model::Model& m, const AnalysisResult& r, int block, const model::Vec3& p) {
  if (m.blocks[block].is_support()) return model::Vec3::Zero();
  const auto& motion = r.mechanism.blocks[block];
  return motion.translation + motion.rotation.cross(p - m.blocks[block].centroid);
}

/// Every contact point of the result with its motion in the reported mechanism: opening or sliding
/// when its normal or tangential relative velocity exceeds `threshold` times the largest one.
std::vector<ContactPoint> classify_points(const model::Model& m, const AnalysisResult& r, double threshold) {
  std::vector<ContactPoint> points;
  std::vector<model::Vec3> velocities;
  for (std::size_t i = 0; i < m.interfaces.size(); ++i) {
    const model::ContactInterface& c = m.interfaces[i];
    for (const auto& p : r.mechanism.interfaces[i].points) {
      ContactPoint q;
      q.block_a = c.block_a;
      q.block_b = c.block_b;
      q.position = p.position;
      q.normal = c.normal;
      q.tangent = model::Vec3::UnitY().cross(c.normal).normalized();
      q.friction = c.friction;
      points.push_back(q);
      velocities.push_back(velocity_at(m, r, c.block_b, p.position) - velocity_at(m, r, c.block_a, p.position));
    }
  }
  double largest = 0.0;
  for (const model::Vec3& d : velocities) largest = std::max(largest, d.norm());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double dn = velocities[k].dot(points[k].normal), dt = velocities[k].dot(points[k].tangent);
    EXPECT_GT(dn, -threshold * largest) << "the reported mechanism interpenetrates at point " << k;
    if (dn > threshold * largest) points[k].motion = PointMotion::Opens;
    else if (std::abs(dt) > threshold * largest)
      points[k].motion = dt > 0 ? PointMotion::SlidesPositive : PointMotion::SlidesNegative;
  }
  return points;
}

/// Builds min (sign = +1) or max (sign = -1) alpha over the states compatible with the points'
/// motions as a conic problem in standard form (A x = b, x >= 0): alpha = a+ - a-; per closed point
/// N, T+, T-, and the slacks of mu N -+ T >= 0; per sliding point N alone, T = -+ mu N against its
/// slip; opening points carry nothing.
class CompatibleStates {
 public:
  CompatibleStates(const model::Model& m, const std::vector<ContactPoint>& points) : m_(m) {
    for (std::size_t b = 0; b < m.blocks.size(); ++b) {
      if (!m.blocks[b].is_support()) row_of_block_[b] = 3 * free_blocks_++;
    }
    rows_ = 3 * free_blocks_;
    add_load_columns();
    for (const ContactPoint& q : points) add_point(q);
  }

  std::optional<double> extreme(double sign) const {
    const conic::Solution s = solve(sign);
    if (s.info.status != conic::SolveStatus::Solved) return std::nullopt;
    return s.x[0] - s.x[1];
  }

  /// Whether the LP has no feasible point: the solver's certificate of primal infeasibility.
  bool none() const { return solve(1.0).info.status == conic::SolveStatus::PrimalInfeasible; }

 private:
  conic::Solution solve(double sign) const {
    conic::ConicProblem problem;
    problem.A.resize(rows_, columns_);
    problem.A.setFromTriplets(entries_.begin(), entries_.end());
    problem.A.makeCompressed();
    problem.b = Eigen::VectorXd::Zero(rows_);
    for (std::size_t b = 0; b < m_.blocks.size(); ++b) {
      if (row_of_block_.count(b)) problem.b[row_of_block_.at(b) + 1] = m_.blocks[b].weight();  // dead load down
    }
    problem.c = Eigen::VectorXd::Zero(columns_);
    problem.c[0] = sign;
    problem.c[1] = -sign;
    problem.cones.num_nonneg = columns_;
    conic::ConicSolver solver(problem);
    return solver.solve();
  }

  int column() { return columns_++; }
  int row() { return rows_++; }
  void add(int row, int column, double value) { entries_.emplace_back(row, column, value); }

  /// The live load alpha W d at each free block's centroid (d = +x): columns a+ and a-.
  void add_load_columns() {
    const int plus = column(), minus = column();
    for (const auto& [block, row] : row_of_block_) {
      const double w = m_.blocks[block].weight();
      add(row, plus, w);
      add(row, minus, -w);
    }
  }

  /// Force direction f (per unit of the column) at the point on its two blocks.
  void add_force(const ContactPoint& q, int column, const model::Vec3& f) {
    for (const auto& [block, sign] : {std::pair{q.block_b, 1.0}, std::pair{q.block_a, -1.0}}) {
      const auto it = row_of_block_.find(block);
      if (it == row_of_block_.end()) continue;
      const model::Vec3 arm = q.position - m_.blocks[block].centroid;
      add(it->second, column, sign * f.x());
      add(it->second + 1, column, sign * f.z());
      add(it->second + 2, column, sign * (arm.z() * f.x() - arm.x() * f.z()));  // moment about +y
    }
  }

  void add_point(const ContactPoint& q) {
    if (q.motion == PointMotion::Opens) return;
    const int n = column();
    if (q.motion != PointMotion::Closed) {
      // T = -mu N along the slip: the force is N (n -+ mu t).
      const double against = q.motion == PointMotion::SlidesPositive ? -1.0 : 1.0;
      add_force(q, n, q.normal + against * q.friction * q.tangent);
      return;
    }
    const int plus = column(), minus = column();
    add_force(q, n, q.normal);
    add_force(q, plus, q.tangent);
    add_force(q, minus, -q.tangent);
    for (const double side : {1.0, -1.0}) {  // mu N - side T - slack = 0
      const int r = row(), slack = column();
      add(r, n, q.friction);
      add(r, plus, -side);
      add(r, minus, side);
      add(r, slack, -1.0);
    }
  }

  const model::Model& m_;
  std::map<std::size_t, int> row_of_block_;
  int free_blocks_ = 0, rows_ = 0, columns_ = 0;
  std::vector<Eigen::Triplet<double>> entries_;
};

struct WallScene {
  std::string name;
  json model;
};

/// Walls under in-plane seismic load (+x, mu 0.6) at rbla's default scheme settings. Before the
/// fix the first gave 0.513980 (its mechanism's states: 0.508650 to 0.515040), the second 0.321637
/// with the range [0.321637, 0.321637] (0.351598 at the other end), the sample 0.446377 with the
/// range [0.446377, 0.446377] (0.440310 to 0.452765).
std::vector<WallScene> wall_scenes() {
  std::vector<WallScene> s;
  const Case c;
  s.push_back({"running bond 6 x 10", finish(running_bond_blocks(6, 10), c)});
  s.push_back({"running bond 10 x 8, blocks 0.44 x 0.5 x 0.38", finish(running_bond_blocks(10, 8, 1.0, 0.44, 0.38, 0.5), c)});
  std::ifstream file(std::string(RBLA_SOURCE_DIR) + "/samples/wall_opening.json");
  const json opening = json::parse(file);
  s.push_back({"samples/wall_opening.json", opening});
  // Not here: the same wall at mu 0.8 or 10, whose certified mechanisms admit no exactly compatible
  // state (the next test).
  for (WallScene& scene : s) {
    scene.model["analysis"]["friction_model"] = "non_associative";
    scene.model["analysis"].erase("non_associative");
  }
  return s;
}

TEST(NonAssociativeCompatibleStates, ReportedValueAndRangeAreThoseOfTheMechanism) {
  for (const WallScene& scene : wall_scenes()) {
    SCOPED_TRACE(scene.name);
    const auto loaded = rbla::io::load_model_text(scene.model.dump());
    const AnalysisResult r = rbla::analysis::analyse(loaded.model);
    ASSERT_EQ(r.verdict, Verdict::Collapse) << r.verdict_text;
    ASSERT_TRUE(r.non_associative_converged);
    ASSERT_TRUE(r.planar);
    ASSERT_TRUE(r.non_associative_range.has_value());
    EXPECT_EQ(r.non_associative_pointwise, std::optional<bool>(true));
    const auto points = classify_points(loaded.model, r, 1e-5);
    const CompatibleStates states(loaded.model, points);
    const auto low = states.extreme(+1.0), high = states.extreme(-1.0);
    ASSERT_TRUE(low && high) << "no state is compatible with the reported mechanism";
    const double alpha = *r.load_multiplier;
    EXPECT_NEAR(alpha, *low, 1e-5 * alpha) << "range by the independent LP [" << *low << ", " << *high << "]";
    EXPECT_NEAR(r.non_associative_range->first, *low, 1e-5 * alpha);
    EXPECT_NEAR(r.non_associative_range->second, *high, 1e-5 * alpha);
  }
}

// The fixed-point test bounds work, not forces: on samples/wall_opening.json at mu 0.8 and 10 the
// certified state keeps force at points its mechanism opens (an independent review's LP found no
// exactly compatible state, at every velocity threshold from 1e-4 to 1e-6). rbla must say so
// (pointwise false, with the warning and the measures), and this LP, built at rbla's own
// threshold, must agree that no state matches.
TEST(NonAssociativeCompatibleStates, AMechanismNoStateMatchesIsReportedAsSuch) {
  std::ifstream file(std::string(RBLA_SOURCE_DIR) + "/samples/wall_opening.json");
  const json opening = json::parse(file);
  for (const double mu : {0.8, 10.0}) {
    SCOPED_TRACE("mu " + std::to_string(mu));
    json model = opening;
    model["defaults"]["friction"] = mu;
    model["analysis"]["friction_model"] = "non_associative";
    const auto loaded = rbla::io::load_model_text(model.dump());
    const AnalysisResult r = rbla::analysis::analyse(loaded.model);
    ASSERT_EQ(r.verdict, Verdict::Collapse) << r.verdict_text;
    ASSERT_TRUE(r.non_associative_converged);
    ASSERT_EQ(r.non_associative_pointwise, std::optional<bool>(false));
    EXPECT_GT(r.non_associative_open_force + r.non_associative_friction_shortfall, 1e-4);
    EXPECT_TRUE(std::any_of(r.warnings.begin(), r.warnings.end(),
                            [](const auto& w) { return w.code == "non_associative_not_pointwise"; }));
    const CompatibleStates states(loaded.model, classify_points(loaded.model, r, analysis::kMovingPointFraction));
    EXPECT_TRUE(states.none()) << "the independent LP found a state compatible with the mechanism";
  }
}

}  // namespace
}  // namespace rbla::validation
