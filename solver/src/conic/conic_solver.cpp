// Interior-point loop. Homogeneous self-dual embedding (HSDE) of the standard-form pair
// (Ye, Todd, Mizuno 1994; conic form as in ECOS, Domahidi et al. 2013, and CVXOPT):
//
//   A x − b τ = 0,   −Aᵀy + c τ − z = 0,   bᵀy − cᵀx − κ = 0,   x, z ∈ K,  τ, κ ≥ 0.
//
// Newton step with NT scaling W (λ = W z = W⁻¹ x) and right-hand sides (η, d, d_κ):
//   A dx − b dτ = −η r_p,   −Aᵀdy + c dτ − dz = −η r_d,   bᵀdy − cᵀdx − dκ = −η r_g,
//   λ ∘ (W dz + W⁻¹ dx) = d,   κ dτ + τ dκ = d_κ,
// with r_p = A x − bτ, r_d = −Aᵀy + cτ − z, r_g = bᵀy − cᵀx − κ. Eliminating dz and dx:
//   dx = W² (Aᵀdy − c dτ + r₁),   r₁ = W⁻¹(λ \ d) − η r_d,
//   M dy = −η r_p − A W² r₁ + (A W² c + b) dτ,   M = A W² Aᵀ.
// Writing dy = p + q dτ with M q = A W² c + b (once per iteration) and M p = −η r_p − A W² r₁,
// the last two equations give the scalar
//   dτ = (−η r_g − bᵀp + cᵀW²(Aᵀp + r₁) + d_κ/τ) / (bᵀq − cᵀW²(Aᵀq − c) + κ/τ),
// whose denominator equals ‖W(Aᵀq − c)‖² + κ/τ > 0.
// Mehrotra predictor–corrector: predictor η = 1, d = −λ∘λ, d_κ = −τκ; corrector η = 1 − σ,
// σ = (1 − α_aff)³, d = −λ∘λ − (W⁻¹dx_a)∘(W dz_a) + σμe, d_κ = −τκ − dτ_a dκ_a + σμ.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <limits>

#include "cone.hpp"
#include "equilibration.hpp"
#include "normal_equations.hpp"
#include "sparse_cholesky.hpp"
#include "rbla/conic/solver.hpp"

namespace rbla::conic {

using detail::Vec;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// MemAvailable from /proc/meminfo in bytes, 0 when it cannot be read (not Linux).
double available_memory_bytes() {
  std::FILE* file = std::fopen("/proc/meminfo", "r");
  if (!file) return 0.0;
  char line[256];
  double kib = 0.0;
  while (std::fgets(line, sizeof line, file)) {
    if (std::sscanf(line, "MemAvailable: %lf kB", &kib) == 1) break;
  }
  std::fclose(file);
  return kib * 1024.0;
}

double inf_norm(const Vec& v) { return v.size() ? v.lpNorm<Eigen::Infinity>() : 0.0; }

/// Quality of the current iterate, measured on the original (unscaled) problem.
struct Metrics {
  Vec x, y, z;  // iterate / τ, original units
  double primal_objective = 0, dual_objective = 0;
  double gap_abs = 0, gap_rel = 0, res_primal = 0, res_dual = 0;
  double primal_cert = std::numeric_limits<double>::infinity();  // ‖Aᵀȳ + z̄‖∞ (bᵀȳ = 1)
  double dual_cert = std::numeric_limits<double>::infinity();    // ‖A x̄‖∞ (cᵀx̄ = −1)
  Vec y_cert, z_cert, x_cert;

  /// ≤ 1 exactly when meets(tol_feas, tol_gap_abs, tol_gap_rel): how far from converged.
  double merit(double tol_feas, double tol_gap_abs, double tol_gap_rel) const {
    return std::max({res_primal / tol_feas, res_dual / tol_feas,
                     std::min(gap_abs / tol_gap_abs, gap_rel / tol_gap_rel)});
  }

  bool meets(double tol_feas, double tol_gap_abs, double tol_gap_rel) const {
    return res_primal <= tol_feas && res_dual <= tol_feas &&
           (gap_abs <= tol_gap_abs || gap_rel <= tol_gap_rel);
  }
};

}  // namespace

struct ConicSolver::Impl {
  ConicProblem problem;
  Settings settings;
  ProgressCallback callback;
  detail::ConeSet cones;
  std::vector<detail::ScalingBlock> blocks;
  detail::Equilibration equilibration;
  Eigen::SparseMatrix<double> A;  // equilibrated
  Vec b, c;                       // equilibrated
  std::vector<bool> is_dense;
  // The second thread (Settings::threads), for problems of at least split_min_rows rows: the
  // split normal matrix, its assembly, the products with A and the cone operations.
  std::unique_ptr<detail::ForkJoin> fork_join;
  Eigen::SparseMatrix<double, Eigen::RowMajor> A_rows;  // with fork_join: A by rows
  Eigen::Index row_split = 0, col_split = 0;            // where the helper's half starts
  std::unique_ptr<detail::NormalEquations> normal;
  // Built on first need: the same normal equations with the dense columns inside the sparse
  // factor, used when the bordered dense-column solve loses accuracy (late iterations).
  std::unique_ptr<detail::NormalEquations> normal_without_dense;
  std::vector<double> packed_W2;
  double setup_seconds = 0;
  double symbolic_seconds = 0;
  bool has_warm_start = false;
  Vec warm_x, warm_y, warm_z;  // original units, consumed by the next solve()

  Impl(ConicProblem p, Settings s) : problem(std::move(p)), settings(std::move(s)) {
    const auto start = Clock::now();
    auto messages = problem.validate();
    if (!messages.empty()) throw ConicSetupError::from_messages("invalid conic problem", messages);
    messages = settings.validate();
    if (!messages.empty())
      throw ConicSetupError::from_messages("invalid solver settings", messages);
    if (settings.threads >= 2 && problem.A.rows() >= settings.split_min_rows)
      fork_join = std::make_unique<detail::ForkJoin>();
    cones = detail::ConeSet(problem.cones.num_nonneg, problem.cones.soc_dims, fork_join.get());
    blocks = cones.scaling_blocks();
    std::size_t packed_size = 0;
    for (const auto& blk : blocks) packed_size += static_cast<std::size_t>(blk.size * blk.size);
    packed_W2.assign(packed_size, 0.0);
    detect_dense_columns();
    rescale();
    const auto symbolic_start = Clock::now();
    normal = std::make_unique<detail::NormalEquations>(A, blocks, is_dense, settings.ordering,
                                                       fork_join.get());
    symbolic_seconds = seconds_since(symbolic_start);
    check_memory();
    setup_seconds = seconds_since(start);
  }

  // Refuses a factor larger than the memory limit (Settings::memory_limit_bytes) before the
  // numeric factorisation allocates it.
  void check_memory() const {
    double limit = settings.memory_limit_bytes;
    if (limit == 0) limit = 0.8 * available_memory_bytes();
    const double need = normal->factor_bytes();
    if (limit > 0 && need > limit) {
      char text[400];
      std::snprintf(text, sizeof text,
                    "the Cholesky factor of the normal matrix (%lld rows, %ld nonzeros in L) "
                    "needs %.2f GB, more than the %.2f GB this solve may use; use a coarser "
                    "model, the planar formulation or a pyramid cone, or a machine with more "
                    "memory",
                    static_cast<long long>(A.rows()), normal->factor_nonzeros(),
                    need / 1e9, limit / 1e9);
      throw ConicResourceError(text);
    }
  }

  // Dense columns: see Settings::dense_column_*. Only nonnegative variables qualify, because an
  // SOC's W² couples its columns and cannot be split off column by column.
  void detect_dense_columns() {
    const Eigen::Index n = problem.A.cols();
    is_dense.assign(static_cast<std::size_t>(n), false);
    if (!settings.dense_columns || settings.dense_column_max == 0) return;
    const double mean = static_cast<double>(problem.A.nonZeros()) /
                        static_cast<double>(std::max<Eigen::Index>(n, 1));
    const double threshold = std::max(static_cast<double>(settings.dense_column_min_nnz),
                                      settings.dense_column_ratio * mean);
    std::vector<std::pair<long, Eigen::Index>> candidates;
    for (Eigen::Index j = 0; j < problem.cones.num_nonneg; ++j) {
      const long nnz = problem.A.outerIndexPtr()[j + 1] - problem.A.outerIndexPtr()[j];
      if (static_cast<double>(nnz) >= threshold) candidates.push_back({nnz, j});
    }
    std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) {
      return a.first != b.first ? a.first > b.first : a.second < b.second;
    });
    const std::size_t keep =
        std::min(candidates.size(), static_cast<std::size_t>(settings.dense_column_max));
    for (std::size_t k = 0; k < keep; ++k)
      is_dense[static_cast<std::size_t>(candidates[k].second)] = true;
  }

  // Recomputes the equilibration from the current problem data and refreshes A, b, c.
  void rescale() {
    if (settings.equilibrate) {
      equilibration = detail::ruiz_equilibration(
          problem.A, problem.b, problem.c, blocks, settings.equilibrate_max_iter,
          settings.equilibrate_min_scaling, settings.equilibrate_max_scaling);
    } else {
      equilibration = detail::identity_equilibration(problem.A.rows(), problem.A.cols());
    }
    detail::apply_equilibration(equilibration, problem.A, A);
    if (fork_join) {
      // Row-major copy for A v by rows; each thread takes rows (or, for Aᵀ v, columns) holding
      // half of the nonzeros.
      A_rows = A;
      const auto half_of = [](const int* outer, Eigen::Index size) {
        const int half = outer[size] / 2;
        return static_cast<Eigen::Index>(std::lower_bound(outer, outer + size + 1, half) - outer);
      };
      row_split = half_of(A_rows.outerIndexPtr(), A_rows.outerSize());
      col_split = half_of(A.outerIndexPtr(), A.outerSize());
    }
    b = equilibration.b_scale * equilibration.row_scale.cwiseProduct(problem.b);
    c = equilibration.c_scale * equilibration.col_scale.cwiseProduct(problem.c);
    if (normal) normal->set_A_values(A);
    if (normal_without_dense) normal_without_dense->set_A_values(A);
  }

  // out = A v and out = Aᵀ v for the scaled A, on both threads when there are two: A v by the
  // rows of A_rows, Aᵀ v by the columns of A, both one dot product per compressed vector.
  void multiply_A(const Vec& v, Vec& out) const {
    if (!fork_join) {
      out.noalias() = A * v;
      return;
    }
    dot_each_vector(A_rows, row_split, v, out);
  }
  void multiply_At(const Vec& v, Vec& out) const {
    if (!fork_join) {
      out.noalias() = A.transpose() * v;
      return;
    }
    dot_each_vector(A, col_split, v, out);
  }
  // out[k] = (compressed vector k of S) · v, vectors [0, split) on this thread, the rest on the
  // helper's.
  template <class Sparse>
  void dot_each_vector(const Sparse& S, Eigen::Index split, const Vec& v, Vec& out) const {
    const Eigen::Index count = S.outerSize();
    out.resize(count);
    const int* outer = S.outerIndexPtr();
    const int* inner = S.innerIndexPtr();
    const double* values = S.valuePtr();
    auto range = [&](Eigen::Index begin, Eigen::Index end) {
      for (Eigen::Index k = begin; k < end; ++k) {
        double sum = 0;
        for (int p = outer[k]; p < outer[k + 1]; ++p) sum += values[p] * v[inner[p]];
        out[k] = sum;
      }
    };
    const std::function<void()> first = [&] { range(0, split); };
    const std::function<void()> second = [&] { range(split, count); };
    fork_join->run(first, second);
  }

  // scaled_Ax, scaled_Aty: Ã x and Ãᵀ y when the caller has them (only used with fork_join).
  Metrics evaluate(const Vec& x, const Vec& y, const Vec& z, double tau,
                   const Vec* scaled_Ax = nullptr, const Vec* scaled_Aty = nullptr) const {
    const auto& eq = equilibration;
    Metrics r;
    const Vec x_hat = eq.col_scale.cwiseProduct(x);  // ∝ x, original units up to 1/(s_b τ)
    const Vec y_hat = eq.row_scale.cwiseProduct(y);
    const Vec z_hat = z.cwiseQuotient(eq.col_scale);
    r.x = x_hat / (eq.b_scale * tau);
    r.y = y_hat / (eq.c_scale * tau);
    r.z = z_hat / (eq.c_scale * tau);
    const auto& P = problem;
    r.primal_objective = P.c.dot(r.x);
    r.dual_objective = P.b.dot(r.y);
    // Both gaps: |cᵀx − bᵀy| alone can be small while the complementarity xᵀz is not, when the
    // dual residual's contribution r_dᵀx cancels it (many variables, large x); ECOS uses xᵀz.
    r.gap_abs = std::max(std::abs(r.primal_objective - r.dual_objective), std::abs(r.x.dot(r.z)));
    r.gap_rel = r.gap_abs /
                std::max(1.0, std::min(std::abs(r.primal_objective), std::abs(r.dual_objective)));
    Vec Ax, Aty;
    if (fork_join) {
      // Through the scaled matrix on both threads: A = D⁻¹ Ã E⁻¹ (equilibration.hpp), so
      // A x_orig = D⁻¹ Ã x / (s_b τ) and Aᵀ y_orig = E⁻¹ Ãᵀ y / (s_c τ); the certificates'
      // products are these rescaled.
      if (scaled_Ax)
        Ax = *scaled_Ax;
      else
        multiply_A(x, Ax);
      Ax = Ax.cwiseQuotient(eq.row_scale) / (eq.b_scale * tau);
      if (scaled_Aty)
        Aty = *scaled_Aty;
      else
        multiply_At(y, Aty);
      Aty = Aty.cwiseQuotient(eq.col_scale) / (eq.c_scale * tau);
    } else {
      Ax = P.A * r.x;
      Aty = P.A.transpose() * r.y;
    }
    r.res_primal = inf_norm(Ax - P.b) / std::max(1.0, inf_norm(P.b) + inf_norm(r.x));
    r.res_dual =
        inf_norm(Aty + r.z - P.c) / std::max(1.0, inf_norm(P.c) + inf_norm(r.y) + inf_norm(r.z));
    const double bty = P.b.dot(y_hat);
    if (bty > 0) {
      r.y_cert = y_hat / bty;
      r.z_cert = z_hat / bty;
      r.primal_cert = fork_join ? inf_norm(Aty * (eq.c_scale * tau / bty) + r.z_cert)
                                : inf_norm(P.A.transpose() * r.y_cert + r.z_cert);
    }
    const double ctx = P.c.dot(x_hat);
    if (ctx < 0) {
      r.x_cert = x_hat / (-ctx);
      r.dual_cert = fork_join ? inf_norm(Ax * (eq.b_scale * tau / -ctx))
                              : inf_norm(P.A * r.x_cert);
    }
    return r;
  }

  // Accuracy the Newton directions need: bounds on the errors of the primal equation,
  // e_p = A dx − b dτ + η r_p, and of the gap equation, e_g (the refinement's targets).
  struct DirectionAccuracy {
    // ‖e_p‖∞, |e_g| at or below this are as good as exact: a step of length α leaves
    // (1 − αη) r_p + α e_p, so e_p ≤ 1e-3 ‖r_p‖ does not slow the Newton decrease of r_p.
    // refine_tol_rel (1 + ‖b‖τ) is an absolute floor.
    double exact = 0;
    // Larger errors are still harmless while r_p stays where it cannot change the answer. Step
    // after step, r_p settles near e_p / η (it gains α e_p and loses αη r_p), r_g near e_g / η.
    // In original units r_p moves the objective gap by y_origᵀ r_orig = ŷᵀr̂ / (s_c s_b τ²)
    // (cᵀx − bᵀy = xᵀz − r_dᵀx + yᵀr_p) and the feasibility measure by ‖D⁻¹ r̂‖∞ / (s_b τ);
    // r_g is the gap itself, scaled by s_c s_b τ (evaluate()). A tenth of what would use up the
    // gap or the feasibility tolerance is allowed: the budgets below are for |ŷ|ᵀ|e_p|,
    // ‖D⁻¹ e_p‖∞ and |e_g| at η = 1. The objective is judged by the measured |ŷ|ᵀ|e_p| rather
    // than ‖ŷ‖₁ ‖e_p‖∞: late in the façade solves the error of a plain correction sits on rows
    // where ŷ is small (8051 blocks, iteration 45: |ŷ|ᵀ|e_p| = 1.2e-11 to 1.8e-10 against a
    // budget of 1.4e-9, ‖ŷ‖₁ ‖e_p‖∞ ≈ 6e-8). Refinement bringing ‖e_p‖∞ under ‖ŷ‖₁-based
    // targets took 519 of the 939 solves at 30323 blocks, mostly in CG passes that could not
    // get there (the error's floor is the cancellation in A W² (Aᵀp + r₁), which CG on M does
    // not reach).
    double objective = 0;
    double feasibility = 0;
    double gap = 0;
    // An ‖e_p‖∞ that meets the budgets at η = 1 whatever ŷ: the CG target in M (whose residual
    // is not e_p) and the scale of the refinement's failure test.
    double uniform = 0;

    // Whether errors (e_p, e_g) of a direction with this η are acceptable; abs_y = |ŷ|.
    bool accepts(const Vec& ep, double eg, double eta, const Vec& abs_y, const Vec& row_scale) const {
      const double error = std::max(inf_norm(ep), std::abs(eg));
      if (error <= exact) return true;
      if (!(std::abs(eg) <= eta * gap)) return false;
      const double limit = eta * feasibility;
      double weighted = 0;
      for (Eigen::Index i = 0; i < ep.size(); ++i) {
        const double e = std::abs(ep[i]);
        if (!(e <= limit * row_scale[i])) return false;
        weighted += abs_y[i] * e;
      }
      return weighted <= eta * objective;
    }
  };
  DirectionAccuracy direction_accuracy(const Vec& rp, const Vec& y, double tau,
                                       const Metrics& metrics) const {
    const auto& eq = equilibration;
    DirectionAccuracy a;
    a.exact = std::max(settings.refine_tol_rel * (1.0 + inf_norm(b) * tau), 1e-3 * inf_norm(rp));
    const double gap_scale = eq.c_scale * eq.b_scale * tau;
    a.gap = 0.1 * settings.tol_gap_rel * std::max(1.0, std::abs(metrics.primal_objective)) * gap_scale;
    a.objective = a.gap * tau;
    a.feasibility = 0.1 * settings.tol_feas *
                    std::max(1.0, inf_norm(problem.b) + inf_norm(metrics.x)) * eq.b_scale * tau;
    const double y_norm = y.lpNorm<1>();
    const double min_row_scale = eq.row_scale.size() > 0 ? eq.row_scale.minCoeff() : 1.0;
    double uniform = std::min(a.feasibility * min_row_scale, a.gap);
    if (y_norm > 0) uniform = std::min(uniform, a.objective / y_norm);
    a.uniform = std::max(a.exact, uniform);
    return a;
  }

  Solution solve(bool allow_least_squares_start);
  /// False (x, y, z untouched) when the point could not be computed.
  bool least_squares_start(detail::NormalEquations* ne, int factor_threads, const Vec& e, Vec& x,
                           Vec& y, Vec& z, Info& info);

  // The warm-start blend (see ConicSolver::set_warm_start) in the scaled variables, with τ = 1:
  // x = col_scale ∘ x̂ / b_scale etc. inverted (see evaluate()). False if not usable.
  bool warm_start(const Vec& e, Vec& x, Vec& y, Vec& z, double& kappa) {
    const auto& eq = equilibration;
    if (warm_x.size() != x.size() || warm_y.size() != y.size() || warm_z.size() != z.size() ||
        !warm_x.allFinite() || !warm_y.allFinite() || !warm_z.allFinite())
      return false;
    const double lambda = settings.warm_start_weight;
    x = lambda * (eq.b_scale * warm_x.cwiseQuotient(eq.col_scale)) + (1.0 - lambda) * e;
    z = lambda * (eq.c_scale * warm_z.cwiseProduct(eq.col_scale)) + (1.0 - lambda) * e;
    y = lambda * (eq.c_scale * warm_y.cwiseQuotient(eq.row_scale));
    const double nu = static_cast<double>(cones.degree());
    kappa = x.dot(z) / nu;
    // Interior check through the scaling itself (it fails outside the cones).
    return std::isfinite(kappa) && kappa > 0 && cones.update_scaling(x, z);
  }
};

namespace {

void print_banner(std::ostream& out, const ConicProblem& p, int dense, long nnz_M, long nnz_L,
                  double flops, double bytes, const std::string& backend) {
  char line[512];
  std::snprintf(
      line, sizeof line,
      "rbla conic interior point (HSDE, NT scaling, Mehrotra predictor-corrector)\n"
      "  rows %lld, variables %lld, nnz(A) %lld, nonnegative %lld, second-order cones %zu\n"
      "  dense columns %d, nnz(M) %ld, nnz(L) %ld, factor %.2e flops %.0f MB, %s\n",
      static_cast<long long>(p.A.rows()), static_cast<long long>(p.A.cols()),
      static_cast<long long>(p.A.nonZeros()), static_cast<long long>(p.cones.num_nonneg),
      p.cones.soc_dims.size(), dense, nnz_M, nnz_L, flops, bytes / 1e6, backend.c_str());
  out << line
      << "iter  primal obj       dual obj         gap_rel   res_pri   res_dual  mu        "
         "tau       kappa     step    sigma   ref\n";
}

void print_row(std::ostream& out, const IterationRow& r) {
  char line[256];
  std::snprintf(line, sizeof line,
                "%4d  %+.9e  %+.9e  %8.2e  %8.2e  %8.2e  %8.2e  %8.2e  %8.2e  %6.4f  %6.4f  %3d\n",
                r.iteration, r.primal_objective, r.dual_objective, r.gap_rel, r.res_primal,
                r.res_dual, r.mu, r.tau, r.kappa, r.step, r.sigma, r.refine_steps);
  out << line;
}

}  // namespace

// Least-squares starting point (CVXOPT conelp's default, also ECOS's): x̂ = argmin ‖x‖ s.t.
// A x = b and (ŷ, ẑ) = argmin ‖z‖ s.t. Aᵀy + z = c, both through M = A Aᵀ (the normal matrix
// at W = I: one extra factorisation), each shifted into the cone along e by one plus its most
// negative eigenvalue when it is not interior already. Measured against x = z = e on the façade
// problems: settlement 21 → 15 iterations (planar LP and 3-D), seismic 31 → 30 (LP) and
// 31 → 28 (3-D); a 400-block 3-D wall 19 → 18; the small wall-with-opening sample 16 → 19.
bool ConicSolver::Impl::least_squares_start(detail::NormalEquations* ne, int factor_threads,
                                            const Vec& e, Vec& x, Vec& y, Vec& z, Info& info) {
  const Settings& s = settings;
  std::fill(packed_W2.begin(), packed_W2.end(), 0.0);
  std::size_t at = 0;
  for (const auto& block : blocks) {
    for (Eigen::Index i = 0; i < block.size; ++i)
      packed_W2[at + static_cast<std::size_t>(i * block.size + i)] = 1.0;
    at += static_cast<std::size_t>(block.size * block.size);
  }
  const detail::FactorReport report =
      ne->factor(packed_W2, s.reg_static, s.reg_retry_factor, s.reg_max_retries, factor_threads);
  info.assembly_seconds += report.assembly_seconds;
  info.factor_seconds += report.factor_seconds;
  info.num_refactor_retries += report.retries;
  if (!report.ok) return false;
  Vec w, y_hat;
  const Vec Ac = A * c;
  ne->solve(b, w, s.refine_max_iter, s.refine_tol_rel * (1.0 + inf_norm(b)));
  const Vec x_hat = A.transpose() * w;
  ne->solve(Ac, y_hat, s.refine_max_iter, s.refine_tol_rel * (1.0 + inf_norm(Ac)));
  const Vec z_hat = c - A.transpose() * y_hat;
  const double shift_x = -cones.min_eigenvalue(x_hat);
  const double shift_z = -cones.min_eigenvalue(z_hat);
  if (!std::isfinite(shift_x) || !std::isfinite(shift_z) || !x_hat.allFinite() ||
      !z_hat.allFinite() || !y_hat.allFinite())
    return false;
  x = shift_x < 0 ? x_hat : Vec(x_hat + (1.0 + shift_x) * e);
  z = shift_z < 0 ? z_hat : Vec(z_hat + (1.0 + shift_z) * e);
  y = y_hat;
  return true;
}

Solution ConicSolver::Impl::solve(bool allow_least_squares_start) {
  const auto start = Clock::now();
  {
    const auto messages = settings.validate();
    if (!messages.empty())
      throw ConicSetupError::from_messages("invalid solver settings", messages);
  }
  const Settings& s = settings;
  // One BLAS thread except inside the factorisations (Settings::blas_threads).
  const int factor_threads = s.blas_threads > 0 ? s.blas_threads : detail::current_blas_threads();
  const detail::BlasThreads one_blas_thread(1);
  std::ostream* log = s.verbose ? (s.log_stream ? s.log_stream : &std::cout) : nullptr;

  Info info;
  info.backend = normal->backend_name();
  info.setup_seconds = setup_seconds;
  info.symbolic_seconds = symbolic_seconds;
  info.num_dense_columns = normal->num_dense_columns();
  info.num_factor_nonzeros = normal->factor_nonzeros();
  info.factor_bytes = normal->factor_bytes();
  if (log)
    print_banner(*log, problem, info.num_dense_columns, normal->num_matrix_nonzeros(),
                 info.num_factor_nonzeros, normal->factor_flops(), info.factor_bytes,
                 info.backend);

  const Eigen::Index n = A.cols();
  const Eigen::Index m = A.rows();
  const double nu = static_cast<double>(cones.degree());
  Vec x(n), z(n), y = Vec::Zero(m), e(n);
  cones.set_identity(e);
  x = e;
  z = e;
  double tau = 1.0, kappa = 1.0;
  if (has_warm_start) {
    has_warm_start = false;
    info.warm_started = warm_start(e, x, y, z, kappa);
    if (!info.warm_started) {
      x = e;
      z = e;
      y.setZero();
      kappa = 1.0;
    }
  }

  detail::NormalEquations* ne = normal.get();
  if (!info.warm_started && s.least_squares_start && allow_least_squares_start)
    info.least_squares_start = least_squares_start(ne, factor_threads, e, x, y, z, info);
  Vec rp, rd, lambda, W2c, Atq_c, dxq, q, q_rhs, tmp, tmp2, ds, ds_tilde, r1, rhs, p;
  Vec scaled_Ax, scaled_Aty;  // Ã x and Ãᵀ y of the current iterate (residuals, evaluate())
  Vec dx_a, dy_a, dz_a, dx, dy, dz, scaled_dx, scaled_dz, lambda_sq, corr, ep, dp, ddx, abs_y;
  Vec trial_s, trial_z, trial_v, ds_c, cdx, cdy, cdz;
  double rg = 0;
  double last_step = 0, last_sigma = 0;
  int last_refine = 0;
  Metrics metrics;
  Iterate snapshot;
  SolveStatus status = SolveStatus::NumericalFailure;
  Metrics best_metrics;
  double best_merit = std::numeric_limits<double>::infinity();
  // Infeasibility certificates whose residual stagnates: on some nearly infeasible problems the
  // embedding's iterates shrink towards zero together (τ and κ alike), and the normalised
  // certificate stops improving above tol_infeas.
  Metrics best_primal_cert, best_dual_cert;
  int primal_cert_improved_at = 0, dual_cert_improved_at = 0;
  int short_steps = 0;

  for (int iter = 0;; ++iter) {
    multiply_A(x, scaled_Ax);
    rp = scaled_Ax - b * tau;
    multiply_At(y, scaled_Aty);
    rd = -scaled_Aty + c * tau - z;
    rg = b.dot(y) - c.dot(x) - kappa;
    const double mu = (x.dot(z) + tau * kappa) / (nu + 1.0);
    metrics = evaluate(x, y, z, tau, &scaled_Ax, &scaled_Aty);
    const DirectionAccuracy accuracy = direction_accuracy(rp, y, tau, metrics);
    const double refine_target = accuracy.uniform;
    abs_y = y.cwiseAbs();
    // Late iterations of degenerate problems can lose accuracy; the best iterate is kept for the
    // reduced-accuracy fallback.
    const double merit = metrics.merit(s.tol_feas, s.tol_gap_abs, s.tol_gap_rel);
    if (!(merit >= best_merit)) {
      best_merit = merit;
      best_metrics = metrics;
    }
    IterationRow row;
    row.iteration = iter;
    row.primal_objective = metrics.primal_objective;
    row.dual_objective = metrics.dual_objective;
    row.gap_rel = metrics.gap_rel;
    row.res_primal = metrics.res_primal;
    row.res_dual = metrics.res_dual;
    row.mu = mu;
    row.tau = tau;
    row.kappa = kappa;
    row.step = last_step;
    row.sigma = last_sigma;
    row.refine_steps = last_refine;
    row.elapsed_seconds = seconds_since(start);
    info.history.push_back(row);
    info.iterations = iter;
    if (log) print_row(*log, row);

    if (s.snapshot_gap_rel > 0 && snapshot.empty() && metrics.gap_rel < s.snapshot_gap_rel)
      snapshot = {metrics.x, metrics.y, metrics.z};
    if (metrics.meets(s.tol_feas, s.tol_gap_abs, s.tol_gap_rel)) {
      status = SolveStatus::Solved;
      break;
    }
    if (metrics.primal_cert <= s.tol_infeas) {
      status = SolveStatus::PrimalInfeasible;
      break;
    }
    if (metrics.dual_cert <= s.tol_infeas) {
      status = SolveStatus::DualInfeasible;
      break;
    }
    if (metrics.primal_cert < 0.5 * best_primal_cert.primal_cert) {
      best_primal_cert = metrics;
      primal_cert_improved_at = iter;
    }
    if (metrics.dual_cert < 0.5 * best_dual_cert.dual_cert) {
      best_dual_cert = metrics;
      dual_cert_improved_at = iter;
    }
    if (tau < kappa && best_primal_cert.primal_cert <= s.reduced_tol_infeas &&
        iter - primal_cert_improved_at > s.stall_max_iter) {
      status = SolveStatus::PrimalInfeasible;
      metrics = best_primal_cert;
      info.failure_reason = "certificate stagnated above tol_infeas (reduced accuracy)";
      break;
    }
    if (tau < kappa && best_dual_cert.dual_cert <= s.reduced_tol_infeas &&
        iter - dual_cert_improved_at > s.stall_max_iter) {
      status = SolveStatus::DualInfeasible;
      metrics = best_dual_cert;
      info.failure_reason = "certificate stagnated above tol_infeas (reduced accuracy)";
      break;
    }
    if (!std::isfinite(mu) || !std::isfinite(tau) || !std::isfinite(kappa)) {
      status = SolveStatus::NumericalFailure;
      info.failure_reason = "non-finite iterate";
      break;
    }
    if (iter >= s.max_iter) {
      status = SolveStatus::IterationLimit;
      break;
    }
    if (seconds_since(start) >= s.time_limit_seconds) {
      status = SolveStatus::TimeLimit;
      break;
    }
    if (callback && !callback(row)) {
      status = SolveStatus::Cancelled;
      break;
    }

    // ---- Scaling and factorisation ----
    if (!cones.update_scaling(x, z)) {
      status = SolveStatus::NumericalFailure;
      info.failure_reason = "iterate left the cone interior (NT scaling undefined)";
      break;
    }
    cones.lambda(lambda);
    cones.pack_W2(packed_W2);
    double alpha = 0, sigma = 0, dtau = 0, dkappa = 0;
    int refine_steps = 0;
    bool factor_failed = false;
    for (int attempt = 0; attempt < 2; ++attempt) {
      bool refinement_failed = false;
      const detail::FactorReport report =
          ne->factor(packed_W2, s.reg_static, s.reg_retry_factor, s.reg_max_retries, factor_threads);
      info.assembly_seconds += report.assembly_seconds;
      info.factor_seconds += report.factor_seconds;
      info.num_refactor_retries += report.retries;
      if (!report.ok) {
        factor_failed = true;
        break;
      }

      const auto solve_start = Clock::now();
      double denominator = 0;  // of dτ, set with q below

      // Refinement of a direction on the unreduced residuals: the normal equations lose accuracy
      // through the cancellation in A W² (Aᵀp + r₁) when W² is ill-conditioned (late iterations),
      // so the error of the primal equation  e_p = A dx − b dτ + η r_p  is measured directly
      // (A dx is accurate) and corrected by the same elimination with right-hand side
      // (−e_p, 0, −e_g, 0). dx is updated incrementally and dz is formed once at the end from the
      // dual equation, which keeps W dz + W⁻¹dx unchanged (the refinement never reads dz).
      // dz_current: out_dz already belongs to (out_dx, out_dy, out_dτ); it is then formed again
      // only if a correction changed them. Returns whether one did (the step is then measured
      // again).
      auto refine_direction = [&](double eta, double d_kappa, bool dz_current, Vec& out_dx, Vec& out_dy,
                                  Vec& out_dz, double& out_dtau, double& out_dkappa) {
        bool corrected = false;
        double previous = std::numeric_limits<double>::infinity();
        double ddtau = 0;  // the last correction's, with dp and ddx (to take it back)
        for (int pass = 0; pass < s.refine_max_iter; ++pass) {
          multiply_A(out_dx, ep);
          ep += eta * rp - b * out_dtau;
          const double eg = b.dot(out_dy) - c.dot(out_dx) - out_dkappa + eta * rg;
          double error = std::max(inf_norm(ep), std::abs(eg));
          const bool accepted = accuracy.accepts(ep, eg, eta, abs_y, equilibration.row_scale);
          // A correction that made the error larger is taken back: the factor is then too far
          // from the operator the error is measured with for refinement to converge (rounding
          // in the assembled M, whose NT blocks late in a solve have condition numbers past
          // 1/ε). Late in the 30323-block solve each further correction multiplied the error
          // by 2 to 90, to ‖e_p‖∞ = 7 from 1e-2, and those directions blocked the step
          // (α < 1e-4) four times in eight iterations.
          const bool worse = pass >= 1 && !accepted && !(error <= previous);
          if (worse) {
            out_dy -= dp + q * ddtau;
            out_dx -= ddx + dxq * ddtau;
            out_dtau -= ddtau;
            out_dkappa = (d_kappa - kappa * out_dtau) / tau;
            error = previous;
          }
          // The plain first correction is not judged by the halving test: when the smallest
          // eigenvalue of M falls below the static regularisation δ (nearly infeasible problems,
          // where W² → 0 on most variables), one regularised solve removes only a fraction
          // λ/(λ + δ) of the error along that eigenvector, and stopping there left ~40% of r_p in
          // every direction: the embedding then shrank all iterates together and the
          // infeasibility certificate stalled near 1e-5. CG on the exact M does remove it.
          if (accepted || worse || (pass >= 2 && !(error < 0.5 * previous))) {
            // An error above the residual being removed means the solves are not usable.
            if (!accepted && error > std::max(1e3 * refine_target, inf_norm(rp)))
              refinement_failed = true;
            break;
          }
          previous = error;
          ep = -ep;
          // First a plain correction (one triangular solve); if that was not enough, CG on M.
          refine_steps += 1 + ne->solve(ep, dp, pass == 0 ? 0 : s.refine_max_iter, refine_target);
          multiply_At(dp, tmp);
          cones.mul_W2(tmp, ddx);
          ddtau = (-eg - b.dot(dp) + c.dot(ddx)) / denominator;
          out_dy += dp + q * ddtau;
          out_dx += ddx + dxq * ddtau;
          out_dtau += ddtau;
          out_dkappa = (d_kappa - kappa * out_dtau) / tau;
          corrected = true;
        }
        if (corrected || !dz_current) {
          multiply_At(out_dy, out_dz);
          out_dz = -out_dz + c * out_dtau + eta * rd;
        }
        return corrected;
      };
      // The right-hand side of M p = −η r_p − A W² r₁ (in rhs; r₁ in r1).
      auto direction_rhs = [&](double eta, const Vec& d) {
        cones.lambda_divide(d, ds_tilde);
        cones.mul_Winv(ds_tilde, r1);
        r1 -= eta * rd;
        cones.mul_W2(r1, tmp);
        multiply_A(tmp, rhs);
        rhs = -eta * rp - rhs;
      };
      // The direction from p (and r1) of direction_rhs.
      auto direction_from_p = [&](double eta, double d_kappa, bool refine, Vec& out_dx, Vec& out_dy,
                                  Vec& out_dz, double& out_dtau, double& out_dkappa) {
        multiply_At(p, tmp);
        tmp += r1;
        cones.mul_W2(tmp, out_dx);
        out_dtau = (-eta * rg - b.dot(p) + c.dot(out_dx) + d_kappa / tau) / denominator;
        out_dy = p + q * out_dtau;
        out_dx += dxq * out_dtau;
        out_dkappa = (d_kappa - kappa * out_dtau) / tau;
        if (refine) {
          refine_direction(eta, d_kappa, false, out_dx, out_dy, out_dz, out_dtau, out_dkappa);
        } else {
          multiply_At(out_dy, out_dz);
          out_dz = -out_dz + c * out_dtau + eta * rd;
        }
      };
      // Solves the Newton system for (η, d, d_κ) with one plain solve (see the header comment):
      // the direction has that solve's error, about 1e-8 late in a solve, until refine_direction.
      auto direction = [&](double eta, const Vec& d, double d_kappa, Vec& out_dx, Vec& out_dy,
                           Vec& out_dz, double& out_dtau, double& out_dkappa) {
        direction_rhs(eta, d);
        refine_steps += ne->solve(rhs, p, 0, refine_target);
        direction_from_p(eta, d_kappa, false, out_dx, out_dy, out_dz, out_dtau, out_dkappa);
      };
      // Largest step keeping x, z in K and τ, κ ≥ 0, measured in the scaled space around λ.
      auto max_step = [&](const Vec& ddx, const Vec& ddz, double dtau, double dkappa) {
        cones.mul_Winv(ddx, scaled_dx);
        cones.mul_W(ddz, scaled_dz);
        double alpha =
            std::min(cones.max_step_from_lambda(scaled_dx), cones.max_step_from_lambda(scaled_dz));
        if (dtau < 0) alpha = std::min(alpha, -tau / dtau);
        if (dkappa < 0) alpha = std::min(alpha, -kappa / dkappa);
        return alpha;
      };

      // ---- Predictor (affine scaling) ----
      cones.jordan_product(lambda, lambda, lambda_sq);
      ds = -lambda_sq;
      double dtau_a = 0, dkappa_a = 0;
      // The predictor only sets σ and the second-order term, heuristics that do not need the
      // refined accuracy; the direction taken is solved from its full right-hand side and
      // refined. One solve less per iteration (1920-block seismic 3-D: 265 → 213 solves with the
      // other two changes in this step; 8051 blocks: 680 → 514). Refined while τ < κ, where the
      // embedding heads for an infeasibility certificate: there a plain solve can miss much of
      // the step (see refine_direction), and an unrefined predictor left the certificate of a
      // nearly infeasible arch (ConicNearCritical) stalled just above tol_infeas.
      //
      // M q = A W² c + b (for dτ, in every direction) and the predictor's M p share one pass over
      // the factor: the triangular solves are memory bound (30323 blocks, one BLAS thread per
      // domain: 56-60 ms for one right-hand side, 67-75 ms for two).
      //
      // q is solved plainly. Its error reaches a direction only through q, W²(Aᵀq − c) and the
      // denominator, which every direction and correction uses consistently (the gap equation
      // holds for whatever q was computed), so what it leaves in the primal equation is part of
      // the e_p each refinement measures and removes. Refining q to 1e-13 by CG cost a solve
      // and a product with M per iteration and bought nothing: 1920-block 3-D seismic 28 → 29
      // iterations and 166 → 165 solves, settlement 15 → 15; 8051 blocks 50 → 47 iterations,
      // 355 → 308 solves. Only a denominator that rounding made non-positive (it is
      // ‖W(Aᵀq − c)‖² + κ/τ for the exact q) sends q back to CG.
      cones.mul_W2(c, W2c);
      multiply_A(W2c, q_rhs);
      q_rhs += b;
      direction_rhs(1.0, ds);
      ne->solve_pair(q_rhs, rhs, q, p);
      auto finish_q = [&] {
        multiply_At(q, Atq_c);
        Atq_c -= c;
        cones.mul_W2(Atq_c, dxq);
        denominator = b.dot(q) - c.dot(dxq) + kappa / tau;
      };
      finish_q();
      if (!(denominator > 0)) {
        const double q_target = s.refine_tol_rel * (1.0 + inf_norm(q_rhs));
        refine_steps += ne->solve(q_rhs, q, s.refine_max_iter, q_target);
        finish_q();
      }
      direction_from_p(1.0, -tau * kappa, tau < kappa, dx_a, dy_a, dz_a, dtau_a, dkappa_a);
      const double alpha_aff = std::min(1.0, max_step(dx_a, dz_a, dtau_a, dkappa_a));
      sigma = std::clamp(std::pow(1.0 - alpha_aff, 3), 0.0, 1.0);

      // ---- Corrector (Mehrotra second-order term + centring) ----
      cones.mul_Winv(dx_a, scaled_dx);
      cones.mul_W(dz_a, scaled_dz);
      cones.jordan_product(scaled_dx, scaled_dz, corr);
      ds = -lambda_sq - corr + (sigma * mu) * e;
      direction(1.0 - sigma, ds, -tau * kappa - dtau_a * dkappa_a + sigma * mu, dx, dy, dz, dtau,
                dkappa);
      alpha = s.step_fraction * std::min(1.0, max_step(dx, dz, dtau, dkappa));

      // ---- Gondzio multiple centrality correctors (Gondzio 1996; Colombo & Gondzio 2008) ----
      // Degenerate problems (most contact points end at the cone apex with a zero dual too)
      // have a few pairs that block every step: at 8051 blocks 2 to 12 of 103530 cones, in
      // mirror pairs, mostly well centred (λ's smallest eigenvalue² 0.6-1.0 μ) but turned by
      // the direction by more than their size. Each corrector asks for a longer step α̃, looks
      // at the complementarity products the current direction would give there, moves the
      // outliers back into [β_min σμ, β_max σμ] and re-solves with the same factor (one
      // triangular solve: about 1/10 of a factorisation at 30323 blocks). It is kept only if
      // the step grows by 1 %. α̃ = α + 0.3 and three correctors were the best of the variants
      // tried on the façade problems (1.5α + 0.3, 2α, α + 0.1 … 0.5; 1 to 5 correctors):
      // 45 → 31 iterations on the 1920-block seismic LP, 29 → 21 under settlement, 28 → 19 in
      // 3-D.
      double kappa_rhs = -tau * kappa - dtau_a * dkappa_a + sigma * mu;
      for (int k = 0; k < s.max_centrality_correctors && alpha < s.step_fraction; ++k) {
        const double alpha_trial = std::min(1.0, alpha + 0.3);
        // scaled_dx = W⁻¹dx and scaled_dz = W dz are already there: the last max_step call was
        // for the current direction (the corrector's, when one was just accepted).
        trial_s = lambda + alpha_trial * scaled_dx;
        trial_z = lambda + alpha_trial * scaled_dz;
        cones.jordan_product(trial_s, trial_z, trial_v);
        const double lo = 0.1 * sigma * mu, hi = 10.0 * sigma * mu;
        cones.centrality_correction(trial_v, lo, hi, corr);
        const double kappa_change = detail::centrality_change(
            (tau + alpha_trial * dtau) * (kappa + alpha_trial * dkappa), lo, hi);
        ds_c = ds + corr;
        double cdtau = 0, cdkappa = 0;
        direction(1.0 - sigma, ds_c, kappa_rhs + kappa_change, cdx, cdy, cdz, cdtau, cdkappa);
        ++info.num_centrality_correctors;
        const double alpha_c = s.step_fraction * std::min(1.0, max_step(cdx, cdz, cdtau, cdkappa));
        if (!(alpha_c >= 1.01 * alpha)) break;
        ds.swap(ds_c);
        kappa_rhs += kappa_change;
        dx.swap(cdx);
        dy.swap(cdy);
        dz.swap(cdz);
        dtau = cdtau;
        dkappa = cdkappa;
        alpha = alpha_c;
        ++info.num_centrality_correctors_accepted;
      }
      // Only the direction that is taken is refined. The corrector and the centrality correctors
      // are judged by their unrefined steps: refinement moved no step length by more than 0.005
      // on the 8051-block façade, nor by more than 0.01 in any conic test (infeasible twins and
      // the near-critical arch included). Refining each kept corrector wasted that work whenever
      // a later one replaced it: 8051 blocks 317 → 281 solves (48 → 47 iterations), 30323 blocks
      // 683 → 564 (79 → 82 iterations), 109.0 → 101.9 s in the same minutes.
      if (refine_direction(1.0 - sigma, kappa_rhs, true, dx, dy, dz, dtau, dkappa))
        alpha = s.step_fraction * std::min(1.0, max_step(dx, dz, dtau, dkappa));
      info.solve_seconds += seconds_since(solve_start);
      if (!refinement_failed || ne->num_dense_columns() == 0) break;
      // The bordered dense-column solve lost accuracy: move the dense columns into the sparse
      // factor (one more symbolic analysis, slower factorisations) for the rest of this solve.
      if (!normal_without_dense) {
        const auto start_symbolic = Clock::now();
        normal_without_dense = std::make_unique<detail::NormalEquations>(
            A, blocks, std::vector<bool>(is_dense.size(), false), s.ordering,
            fork_join.get());
        info.symbolic_seconds += seconds_since(start_symbolic);
      }
      ne = normal_without_dense.get();
      info.dense_column_fallback = true;
      if (log)
        *log << "      dense columns moved into the sparse factor (bordered solve inaccurate)\n";
    }
    if (factor_failed) {
      status = SolveStatus::NumericalFailure;
      info.failure_reason = "factorisation failed after all regularisation retries";
      break;
    }

    short_steps = alpha < s.stall_step ? short_steps + 1 : 0;
    if (!(alpha >= s.step_min) || short_steps > s.stall_max_iter) {
      status = SolveStatus::NumericalFailure;  // stalled
      info.failure_reason = "step too short (stalled)";
      break;
    }
    x += alpha * dx;
    y += alpha * dy;
    z += alpha * dz;
    tau += alpha * dtau;
    kappa += alpha * dkappa;
    last_step = alpha;
    last_sigma = sigma;
    last_refine = refine_steps;
    // The embedding is homogeneous: scaling (x, y, z, τ, κ) by a positive factor changes no
    // direction, step or normalised metric. On (nearly) infeasible problems the iterates can
    // shrink together by many orders of magnitude, and then absolute floors (the refinement
    // target) and underflow decide the outcome. Clarabel rescales by max(τ, κ) every iteration
    // (DefaultVariables::rescale); here only when that leaves [1e-4, 1e4], so well-behaved
    // solves keep their path.
    const double scale = std::max(tau, kappa);
    if (scale < 1e-4 || scale > 1e4) {
      x /= scale;
      y /= scale;
      z /= scale;
      tau /= scale;
      kappa /= scale;
    }
  }

  // Reduced-accuracy fallback for runs that stopped without meeting the tolerances.
  if (status == SolveStatus::IterationLimit || status == SolveStatus::TimeLimit ||
      status == SolveStatus::NumericalFailure) {
    if (best_metrics.meets(s.reduced_tol_feas, s.reduced_tol_gap_abs, s.reduced_tol_gap_rel)) {
      status = SolveStatus::SolvedInaccurate;
      metrics = best_metrics;
    } else if (tau < kappa && best_primal_cert.primal_cert <= s.reduced_tol_infeas) {
      status = SolveStatus::PrimalInfeasible;
      metrics = best_primal_cert;
      info.failure_reason = "certificate above tol_infeas (reduced accuracy)";
    } else if (tau < kappa && best_dual_cert.dual_cert <= s.reduced_tol_infeas) {
      status = SolveStatus::DualInfeasible;
      metrics = best_dual_cert;
      info.failure_reason = "certificate above tol_infeas (reduced accuracy)";
    }
  }

  Solution solution;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  switch (status) {
    case SolveStatus::PrimalInfeasible:
      solution.x = Vec::Constant(n, nan);
      solution.y = metrics.y_cert;
      solution.z = metrics.z_cert;
      info.certificate_residual = metrics.primal_cert;
      break;
    case SolveStatus::DualInfeasible:
      solution.x = metrics.x_cert;
      solution.y = Vec::Constant(m, nan);
      solution.z = Vec::Constant(n, nan);
      info.certificate_residual = metrics.dual_cert;
      break;
    case SolveStatus::Solved:
    case SolveStatus::SolvedInaccurate:
    case SolveStatus::IterationLimit:
    case SolveStatus::TimeLimit:
    case SolveStatus::NumericalFailure:
    case SolveStatus::Cancelled:
      solution.x = metrics.x;
      solution.y = metrics.y;
      solution.z = metrics.z;
      break;
  }
  info.status = status;
  info.primal_objective = metrics.primal_objective;
  info.dual_objective = metrics.dual_objective;
  info.gap_abs = metrics.gap_abs;
  info.gap_rel = metrics.gap_rel;
  info.res_primal = metrics.res_primal;
  info.res_dual = metrics.res_dual;
  info.step = last_step;
  info.total_seconds = seconds_since(start);
  if (log) {
    char line[512];
    std::snprintf(line, sizeof line,
                  "status: %s%s%s\niterations %d, primal %.12g, dual %.12g\n"
                  "time [s]: setup %.3f (symbolic %.3f), assembly %.3f, factor %.3f, solve %.3f, "
                  "total %.3f; refactor retries %d\n"
                  "solves with the factor %ld, products with M %ld, centrality correctors %d "
                  "(%d kept)\n",
                  to_string(status), info.failure_reason.empty() ? "" : " - ",
                  info.failure_reason.c_str(), info.iterations, info.primal_objective,
                  info.dual_objective, info.setup_seconds, info.symbolic_seconds,
                  info.assembly_seconds, info.factor_seconds, info.solve_seconds,
                  info.total_seconds, info.num_refactor_retries,
                  normal->num_factor_solves() +
                      (normal_without_dense ? normal_without_dense->num_factor_solves() : 0),
                  normal->num_multiplies() +
                      (normal_without_dense ? normal_without_dense->num_multiplies() : 0),
                  info.num_centrality_correctors, info.num_centrality_correctors_accepted);
    *log << line;
  }
  solution.info = std::move(info);
  solution.snapshot = std::move(snapshot);
  return solution;
}

// ---- Public wrapper ----

ConicSolver::ConicSolver(ConicProblem problem, Settings settings)
    : impl_(std::make_unique<Impl>(std::move(problem), std::move(settings))) {}
ConicSolver::~ConicSolver() = default;
ConicSolver::ConicSolver(ConicSolver&&) noexcept = default;
ConicSolver& ConicSolver::operator=(ConicSolver&&) noexcept = default;

Solution ConicSolver::solve() {
  Solution solution = impl_->solve(true);
  // The least-squares start can sit badly with extreme data (unit weights 1e6 apart: the first
  // step stalled; a random SOCP stalled at iteration 10 and was only "solved inaccurate"). A solve
  // from it that ended in a numerical failure, or was rescued from one by the reduced tolerances,
  // is repeated once from x = z = e, and the better outcome is returned.
  Settings& s = impl_->settings;
  const SolveStatus status = solution.info.status;
  const bool numerical_trouble =
      status == SolveStatus::NumericalFailure ||
      (status == SolveStatus::SolvedInaccurate && !solution.info.failure_reason.empty());
  const double spent = solution.info.total_seconds;
  if (!solution.info.least_squares_start || !numerical_trouble || !(spent < s.time_limit_seconds))
    return solution;
  if (s.verbose)
    *(s.log_stream ? s.log_stream : &std::cout)
        << "      numerical trouble from the least-squares start; solving again from x = z = e\n";
  const double time_limit = s.time_limit_seconds;
  s.time_limit_seconds = time_limit - spent;
  Solution again = impl_->solve(false);
  s.time_limit_seconds = time_limit;
  const bool better = again.info.status == SolveStatus::Solved ||
                      (again.info.status == SolveStatus::SolvedInaccurate &&
                       status == SolveStatus::NumericalFailure);
  Solution& kept = better ? again : solution;
  kept.info.total_seconds = spent + again.info.total_seconds;
  kept.info.restarted = true;
  return std::move(kept);
}

void ConicSolver::update_b(const Eigen::VectorXd& b) {
  if (b.size() != impl_->problem.b.size()) throw ConicSetupError("update_b: wrong length");
  if (!b.allFinite()) throw ConicSetupError("update_b: b is not finite");
  impl_->problem.b = b;
  impl_->rescale();
}

void ConicSolver::update_c(const Eigen::VectorXd& c) {
  if (c.size() != impl_->problem.c.size()) throw ConicSetupError("update_c: wrong length");
  if (!c.allFinite()) throw ConicSetupError("update_c: c is not finite");
  impl_->problem.c = c;
  impl_->rescale();
}

void ConicSolver::update_A_values(const Eigen::VectorXd& values) {
  auto& A = impl_->problem.A;
  if (values.size() != A.nonZeros()) throw ConicSetupError("update_A_values: wrong length");
  if (!values.allFinite()) throw ConicSetupError("update_A_values: values are not finite");
  std::copy(values.data(), values.data() + values.size(), A.valuePtr());
  impl_->rescale();
}

void ConicSolver::set_warm_start(const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                                 const Eigen::VectorXd& z) {
  impl_->warm_x = x;
  impl_->warm_y = y;
  impl_->warm_z = z;
  impl_->has_warm_start = true;
}

void ConicSolver::set_progress_callback(ProgressCallback callback) {
  impl_->callback = std::move(callback);
}
Settings& ConicSolver::settings() { return impl_->settings; }
const ConicProblem& ConicSolver::problem() const { return impl_->problem; }
int ConicSolver::num_symbolic_analyses() const {
  return impl_->normal->num_analyses() +
         (impl_->normal_without_dense ? impl_->normal_without_dense->num_analyses() : 0);
}

Solution solve(const ConicProblem& problem, const Settings& settings) {
  return ConicSolver(problem, settings).solve();
}

}  // namespace rbla::conic
