#include "starting_point.hpp"

#include <algorithm>
#include <cmath>

namespace rbla::conic::detail {

namespace {
// W² = I in ConeSet::pack_W2's layout.
std::vector<double> packed_identity(const std::vector<ScalingBlock>& blocks) {
  std::size_t size = 0;
  for (const auto& block : blocks) size += static_cast<std::size_t>(block.size * block.size);
  std::vector<double> packed(size, 0.0);
  std::size_t at = 0;
  for (const auto& block : blocks) {
    for (Eigen::Index i = 0; i < block.size; ++i)
      packed[at + static_cast<std::size_t>(i * block.size + i)] = 1.0;
    at += static_cast<std::size_t>(block.size * block.size);
  }
  return packed;
}
}  // namespace

bool least_squares_start(NormalEquations& ne, const ScaledProblem& scaled, const ConeSet& cones,
                         const Settings& s, int factor_threads, Variables& v, Info& info) {
  const FactorReport report = ne.factor(packed_identity(cones.scaling_blocks()), s.reg_static,
                                        s.reg_retry_factor, s.reg_max_retries, factor_threads);
  info.assembly_seconds += report.assembly_seconds;
  info.factor_seconds += report.factor_seconds;
  info.num_refactor_retries += report.retries;
  if (!report.ok) return false;
  const auto& A = scaled.A();
  const Vec& b = scaled.b();
  const Vec& c = scaled.c();
  Vec w, y_hat;
  const Vec Ac = A * c;
  ne.solve(b, w, s.refine_max_iter, s.refine_tol_rel * (1.0 + inf_norm(b)));
  const Vec x_hat = A.transpose() * w;
  ne.solve(Ac, y_hat, s.refine_max_iter, s.refine_tol_rel * (1.0 + inf_norm(Ac)));
  const Vec z_hat = c - A.transpose() * y_hat;
  const double shift_x = -cones.min_eigenvalue(x_hat);
  const double shift_z = -cones.min_eigenvalue(z_hat);
  if (!std::isfinite(shift_x) || !std::isfinite(shift_z) || !x_hat.allFinite() ||
      !z_hat.allFinite() || !y_hat.allFinite())
    return false;
  Vec e(x_hat.size());
  cones.set_identity(e);
  v.x = shift_x < 0 ? x_hat : Vec(x_hat + (1.0 + shift_x) * e);
  v.z = shift_z < 0 ? z_hat : Vec(z_hat + (1.0 + shift_z) * e);
  v.y = y_hat;
  return true;
}

bool warm_start(const ScaledProblem& scaled, ConeSet& cones, const Settings& settings,
                const Vec& warm_x, const Vec& warm_y, const Vec& warm_z, Variables& v) {
  const auto& eq = scaled.equilibration();
  if (warm_x.size() != v.x.size() || warm_y.size() != v.y.size() ||
      warm_z.size() != v.z.size() || !warm_x.allFinite() || !warm_y.allFinite() ||
      !warm_z.allFinite())
    return false;
  Vec e(v.x.size());
  cones.set_identity(e);
  const double lambda = settings.warm_start_weight;
  v.x = lambda * (eq.b_scale * warm_x.cwiseQuotient(eq.col_scale)) + (1.0 - lambda) * e;
  v.z = lambda * (eq.c_scale * warm_z.cwiseProduct(eq.col_scale)) + (1.0 - lambda) * e;
  v.y = lambda * (eq.c_scale * warm_y.cwiseQuotient(eq.row_scale));
  const double nu = static_cast<double>(cones.degree());
  v.kappa = v.x.dot(v.z) / nu;
  // Interior check through the scaling itself (it fails outside the cones).
  return std::isfinite(v.kappa) && v.kappa > 0 && cones.update_scaling(v.x, v.z);
}

}  // namespace rbla::conic::detail
