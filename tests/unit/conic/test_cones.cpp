// Identities of the cone operations (NT scaling, Jordan algebra, step to the boundary).
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>

#include "../../../solver/src/conic/cone.hpp"

using namespace rbla::conic::detail;

namespace {

Vec random_interior_soc(std::mt19937& rng, int q, double margin) {
  std::normal_distribution<double> normal;
  Vec v(q);
  for (int i = 1; i < q; ++i) v[i] = normal(rng);
  v[0] = v.tail(q - 1).norm() + margin;
  return v;
}

}  // namespace

TEST(ConicCones, SocNesterovToddScalingIdentities) {
  std::mt19937 rng(7);
  for (int q : {2, 3, 5}) {
    for (double margin : {1.0, 1e-3, 1e-6}) {
      SecondOrderCones cone(0, {q});
      const Vec x = random_interior_soc(rng, q, margin);
      const Vec z = random_interior_soc(rng, q, 0.5);
      ASSERT_TRUE(cone.update_scaling(x, z));
      Vec lambda(q), wz(q), winv_x(q), back(q), w2v(q), wwv(q), tmp(q);
      cone.lambda(lambda);
      cone.mul_W(z, wz);
      cone.mul_Winv(x, winv_x);
      const double scale = x.norm() + z.norm();
      EXPECT_LT((wz - lambda).norm(), 1e-9 * scale) << "q=" << q << " margin=" << margin;
      EXPECT_LT((winv_x - lambda).norm(), 1e-9 * scale) << "q=" << q << " margin=" << margin;
      // W W⁻¹ = I, W² (dense, packed) = W W.
      const Vec v = random_interior_soc(rng, q, 0.1) - random_interior_soc(rng, q, 0.2);
      cone.mul_Winv(v, tmp);
      cone.mul_W(tmp, back);
      EXPECT_LT((back - v).norm(), 1e-9 * v.norm());
      std::vector<double> packed(static_cast<std::size_t>(q * q));
      cone.pack_W2(packed.data());
      w2v = Eigen::Map<Eigen::MatrixXd>(packed.data(), q, q) * v;
      cone.mul_W(v, tmp);
      cone.mul_W(tmp, wwv);
      EXPECT_LT((w2v - wwv).norm(), 1e-9 * (1 + wwv.norm()));
      // The cached step from λ equals the general one at v = λ.
      EXPECT_EQ(cone.max_step_from_lambda(v), cone.max_step(lambda, v));
      // λ ∘ (λ \ d) = d.
      Vec divided(q), product(q);
      cone.lambda_divide(v, divided);
      cone.jordan_product(lambda, divided, product);
      EXPECT_LT((product - v).norm(), 1e-8 * (1 + v.norm()));
    }
  }
}

TEST(ConicCones, SocMaxStepMatchesBisection) {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 50; ++trial) {
    const int q = 2 + trial % 4;
    SecondOrderCones cone(0, {q});
    const Vec v = random_interior_soc(rng, q, 0.3);
    Vec d(q);
    for (int i = 0; i < q; ++i) d[i] = normal(rng);
    const double step = cone.max_step(v, d);
    auto inside = [&](double a) { return SecondOrderCones::jordan_norm(v + a * d) > 0; };
    if (std::isinf(step)) {
      EXPECT_TRUE(inside(1e6));
      continue;
    }
    EXPECT_TRUE(inside(step * (1 - 1e-9)));
    EXPECT_FALSE(inside(step * (1 + 1e-6)));
  }
}

TEST(ConicCones, SocRunEqualsItsConesOneByOne) {
  // A run of cones of mixed sizes stored flat gives, cone by cone, what each cone gives alone.
  std::mt19937 rng(5);
  const std::vector<Eigen::Index> dims{3, 2, 5, 3, 1, 4};
  const Eigen::Index n = 18;
  Vec x(n), z(n), a(n), b(n);
  Eigen::Index start = 0;
  for (Eigen::Index q : dims) {
    x.segment(start, q) = random_interior_soc(rng, static_cast<int>(q), 0.3);
    z.segment(start, q) = random_interior_soc(rng, static_cast<int>(q), 0.7);
    a.segment(start, q) = random_interior_soc(rng, static_cast<int>(q), 0.2) - random_interior_soc(rng, static_cast<int>(q), 0.1);
    b.segment(start, q) = random_interior_soc(rng, static_cast<int>(q), 0.4) - random_interior_soc(rng, static_cast<int>(q), 0.5);
    start += q;
  }
  SecondOrderCones run(0, dims);
  ASSERT_TRUE(run.update_scaling(x, z));
  EXPECT_EQ(run.degree(), 6);
  Vec lambda(n), w(n), winv(n), w2(n), product(n), divided(n), centred(n);
  run.lambda(lambda);
  run.mul_W(a, w);
  run.mul_Winv(a, winv);
  run.mul_W2(a, w2);
  run.jordan_product(a, b, product);
  run.lambda_divide(a, divided);
  run.centrality_correction(product, 0.1, 2.0, centred);
  std::vector<double> packed(9 + 4 + 25 + 9 + 1 + 16);  // Σ q²
  ASSERT_EQ(run.pack_W2(packed.data()), packed.data() + packed.size());
  std::vector<ScalingBlock> blocks;
  run.append_scaling_blocks(blocks);
  ASSERT_EQ(blocks.size(), dims.size());
  double step = std::numeric_limits<double>::infinity();
  double lambda_step = std::numeric_limits<double>::infinity();
  start = 0;
  std::size_t packed_at = 0;
  for (std::size_t k = 0; k < dims.size(); ++k) {
    const Eigen::Index q = dims[k];
    EXPECT_EQ(blocks[k].first, start);
    EXPECT_EQ(blocks[k].size, q);
    SecondOrderCones one(0, {q});
    ASSERT_TRUE(one.update_scaling(x.segment(start, q), z.segment(start, q)));
    Vec expected(q);
    one.lambda(expected);
    EXPECT_EQ(lambda.segment(start, q), expected);
    one.mul_W(a.segment(start, q), expected);
    EXPECT_EQ(w.segment(start, q), expected);
    one.mul_Winv(a.segment(start, q), expected);
    EXPECT_EQ(winv.segment(start, q), expected);
    one.mul_W2(a.segment(start, q), expected);
    EXPECT_EQ(w2.segment(start, q), expected);
    one.jordan_product(a.segment(start, q), b.segment(start, q), expected);
    EXPECT_EQ(product.segment(start, q), expected);
    one.lambda_divide(a.segment(start, q), expected);
    EXPECT_EQ(divided.segment(start, q), expected);
    one.centrality_correction(product.segment(start, q), 0.1, 2.0, expected);
    EXPECT_EQ(centred.segment(start, q), expected);
    std::vector<double> one_packed(static_cast<std::size_t>(q * q));
    one.pack_W2(one_packed.data());
    for (std::size_t i = 0; i < one_packed.size(); ++i) EXPECT_EQ(packed[packed_at + i], one_packed[i]);
    packed_at += one_packed.size();
    step = std::min(step, one.max_step(x.segment(start, q), a.segment(start, q)));
    lambda_step = std::min(lambda_step, one.max_step_from_lambda(a.segment(start, q)));
    start += q;
  }
  EXPECT_EQ(run.max_step(x, a), step);
  EXPECT_EQ(run.max_step_from_lambda(a), lambda_step);
}

TEST(ConicCones, NonnegativeScalingAndStep) {
  NonnegativeCone cone(0, 3);
  const Vec x = (Vec(3) << 1.0, 4.0, 1e-6).finished();
  const Vec z = (Vec(3) << 4.0, 1.0, 1e2).finished();
  ASSERT_TRUE(cone.update_scaling(x, z));
  Vec lambda(3), wz(3);
  cone.lambda(lambda);
  cone.mul_W(z, wz);
  EXPECT_NEAR((wz - lambda).norm(), 0.0, 1e-12);
  EXPECT_NEAR(lambda[0], 2.0, 1e-14);
  const Vec d = (Vec(3) << -2.0, 1.0, -1e-6).finished();
  EXPECT_DOUBLE_EQ(cone.max_step(x, d), 0.5);
  EXPECT_FALSE(cone.update_scaling(-x, z));
}

TEST(ConicCones, StepsFromLambdaListEachBlockingFactor) {
  // What σ's step past the first blockers reads (StepStrategy::sigma_step): one step per factor
  // that the direction takes to its boundary before `limit`, each the factor's own step, so the
  // smallest is max_step_from_lambda.
  std::mt19937 rng(11);
  const std::vector<Eigen::Index> dims{3, 2, 5, 3};
  const Eigen::Index n = 13;
  Vec x(n), z(n), a(n);
  Eigen::Index start = 0;
  for (Eigen::Index q : dims) {
    x.segment(start, q) = random_interior_soc(rng, static_cast<int>(q), 0.3);
    z.segment(start, q) = random_interior_soc(rng, static_cast<int>(q), 0.7);
    a.segment(start, q) = random_interior_soc(rng, static_cast<int>(q), 0.2) - random_interior_soc(rng, static_cast<int>(q), 0.1);
    start += q;
  }
  SecondOrderCones run(0, dims);
  ASSERT_TRUE(run.update_scaling(x, z));
  std::vector<double> all;
  run.append_steps_from_lambda(a, std::numeric_limits<double>::infinity(), all);
  std::vector<double> expected;
  start = 0;
  for (Eigen::Index q : dims) {
    SecondOrderCones one(0, {q});
    ASSERT_TRUE(one.update_scaling(x.segment(start, q), z.segment(start, q)));
    const double step = one.max_step_from_lambda(a.segment(start, q));
    if (step < std::numeric_limits<double>::infinity()) expected.push_back(step);
    start += q;
  }
  ASSERT_FALSE(expected.empty());
  EXPECT_EQ(all, expected);
  EXPECT_EQ(*std::min_element(all.begin(), all.end()), run.max_step_from_lambda(a));
  const double limit = *std::max_element(expected.begin(), expected.end());
  std::vector<double> below;
  run.append_steps_from_lambda(a, limit, below);
  EXPECT_EQ(below.size(), expected.size() - 1);

  NonnegativeCone orthant(0, 4);
  ASSERT_TRUE(orthant.update_scaling((Vec(4) << 1.0, 4.0, 1.0, 2.0).finished(),
                                     (Vec(4) << 4.0, 1.0, 1.0, 2.0).finished()));
  // λ = (2, 2, 1, 2): steps 2/4 = 0.5 and 1/0.5 = 2; the rising entries never block.
  std::vector<double> steps;
  orthant.append_steps_from_lambda((Vec(4) << -4.0, 1.0, -0.5, 0.0).finished(), 10.0, steps);
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_DOUBLE_EQ(steps[0], 0.5);
  EXPECT_DOUBLE_EQ(steps[1], 2.0);
  steps.clear();
  orthant.append_steps_from_lambda((Vec(4) << -4.0, 1.0, -0.5, 0.0).finished(), 1.0, steps);
  EXPECT_EQ(steps, std::vector<double>{0.5});
}
