// Cracks that mean something (issue 17): the cracked interfaces of a mechanism are its hinge
// lines and sliding joints, not every joint the interior-point solution moves a little.
//
// Expectations from outside rbla: an arch under a horizontal load collapses with four hinges
// (Heyman, The Stone Skeleton, 1995; samples/arch.json has alpha = 0.1774597765 from CLP), a
// barrel vault of the same section laid in running bond along four whole rows of bed joints, and
// a column of blocks overturns as one piece about its base toe ([column] in
// tests/stiff/stiff_cases.hpp: alpha = min(b/H, mu)).
#include "analysis/mechanism.hpp"
#include "io/svg_writer.hpp"
#include "support/vault_builder.hpp"
#include "validation_helpers.hpp"

#include <map>
#include <set>

namespace rbla::validation {
namespace {

/// The cracked interfaces of a vault by the row of bed joints they belong to: the lower of the two
/// rings they join (-1 for a springing on the left abutment, `rings - 1` on the right one), and
/// how many interfaces each row has in all.
struct Rows {
  std::map<int, int> cracked, total;
  int cracked_head_joints = 0;
};

Rows rows_of(const model::Model& m, const AnalysisResult& r) {
  Rows rows;
  for (std::size_t i = 0; i < m.interfaces.size(); ++i) {
    const auto& c = m.interfaces[i];
    const int a = ring_of(m.blocks[c.block_a].id), b = ring_of(m.blocks[c.block_b].id);
    const bool cracked = r.mechanism.interfaces[i].cracked;
    if (a == b) {
      rows.cracked_head_joints += cracked ? 1 : 0;
      continue;
    }
    // A springing joins ring 0 to AL (row -1) or the last ring to AR (row rings - 1).
    const int row = a < 0 || b < 0 ? (std::max(a, b) == 0 ? -1 : std::max(a, b)) : std::min(a, b);
    ++rows.total[row];
    if (cracked) ++rows.cracked[row];
  }
  return rows;
}

TEST(Cracks, FourHingeArchSampleHasExactlyItsFourHinges) {
  const auto loaded = io::load_model_file(std::string(RBLA_SOURCE_DIR) + "/samples/arch.json");
  const auto r = analysis::analyse(loaded.model);
  ASSERT_EQ(r.verdict, Verdict::Collapse) << r.verdict_text;
  EXPECT_NEAR(*r.load_multiplier, 0.1774597765, 1e-6);
  ASSERT_EQ(r.mechanism.cracked_interfaces.size(), 4u);
  for (int i : r.mechanism.cracked_interfaces) {
    EXPECT_EQ(r.mechanism.interfaces[i].state, analysis::InterfaceState::Hinge) << loaded.model.interfaces[i].id;
  }
}

// The vault with +-0.5 mm of independent noise on every vertex (about what a CAD export does):
// the 3-D solve spreads small relative motions over most joints (with the former threshold of
// 1e-5 of the largest relative velocity, 290 of 471 interfaces of a 172-block version counted as
// cracked). The cracks must be four whole rows of bed joints and nothing else.
TEST(Cracks, NoisyBarrelVaultCracksAlongFourHingeLines) {
  for (const double noise : {0.0, 5e-4}) {
    SCOPED_TRACE("noise " + std::to_string(noise));
    VaultSpec spec;
    spec.noise = noise;
    const auto loaded = io::load_model_text(vault_model(spec).dump());
    const auto r = analysis::analyse(loaded.model);
    ASSERT_EQ(r.verdict, Verdict::Collapse) << r.verdict_text;
    EXPECT_FALSE(r.planar);
    // The arch's multiplier: exact for the clean vault; the noise moves contact polygons by
    // fractions of a millimetre on 0.8 m joints.
    EXPECT_LT(relative_error(*r.load_multiplier, 0.1774597765), noise == 0.0 ? 1e-6 : 1e-2) << *r.load_multiplier;
    const Rows rows = rows_of(loaded.model, r);
    EXPECT_EQ(rows.cracked_head_joints, 0);
    ASSERT_EQ(rows.cracked.size(), 4u) << r.mechanism.cracked_interfaces.size() << " cracked";
    for (const auto& [row, n] : rows.cracked) EXPECT_EQ(n, rows.total.at(row)) << "row " << row << " only partly cracked";
    // Pictures draw exactly the cracked interfaces, one outlined polygon titled "<id>: <state>" each.
    const std::string svg = io::mechanism_svg(loaded.model, r);
    std::size_t drawn = 0;
    for (auto at = svg.find("<path stroke="); at != std::string::npos; at = svg.find("<path stroke=", at + 1)) ++drawn;
    EXPECT_EQ(drawn, r.mechanism.cracked_interfaces.size());
  }
}

// A column of 50 blocks of 1 x 1 x 1 m overturns about its base toe at alpha = b/H = 0.02: the
// base joint opens by 1/50 of the top's displacement. It must still count as the crack (against
// the largest displacement of its own block), and every block moves with the column.
TEST(Cracks, TallColumnHingesAtItsBaseAndMovesAsOne) {
  Case s;
  const int n = 50;
  const auto loaded = io::load_model_text(column(n, 1.0, static_cast<double>(n), s).dump());
  const auto r = analysis::analyse(loaded.model);
  EXPECT_LT(relative_error(alpha_of(r), 1.0 / n), 1e-6);
  ASSERT_EQ(r.mechanism.cracked_interfaces.size(), 1u);
  const int crack = r.mechanism.cracked_interfaces.front();
  const auto& joint = loaded.model.interfaces[crack];
  EXPECT_EQ(loaded.model.blocks[joint.block_a].id + "|" + loaded.model.blocks[joint.block_b].id, "base|C0");
  EXPECT_EQ(r.mechanism.interfaces[crack].state, analysis::InterfaceState::Hinge);
  for (int i = 1; i <= n; ++i) EXPECT_TRUE(r.mechanism.blocks.at(i).moving) << i;
}

}  // namespace
}  // namespace rbla::validation
