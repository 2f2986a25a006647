#include "rbla/conic/settings.hpp"

#include <cmath>

namespace rbla::conic {

const char* to_string(Ordering ordering) {
  switch (ordering) {
    case Ordering::Best:
      return "best of AMD and METIS";
    case Ordering::Amd:
      return "AMD";
    case Ordering::Metis:
      return "METIS";
    case Ordering::CholmodDefault:
      return "CHOLMOD default";
  }
  return "unknown";
}

std::vector<std::string> Settings::validate() const {
  std::vector<std::string> messages;
  auto positive = [&messages](const char* name, double value) {
    if (!(value > 0) || std::isnan(value)) {
      messages.push_back(std::string(name) + " must be > 0 (is " + std::to_string(value) + ")");
    }
  };
  positive("tol_gap_abs", tol_gap_abs);
  positive("tol_gap_rel", tol_gap_rel);
  positive("tol_feas", tol_feas);
  positive("tol_infeas", tol_infeas);
  positive("reduced_tol_gap_abs", reduced_tol_gap_abs);
  positive("reduced_tol_gap_rel", reduced_tol_gap_rel);
  positive("reduced_tol_feas", reduced_tol_feas);
  positive("reduced_tol_infeas", reduced_tol_infeas);
  positive("time_limit_seconds", time_limit_seconds);
  positive("step_min", step_min);
  positive("stall_step", stall_step);
  if (stall_max_iter < 0) messages.push_back("stall_max_iter must be >= 0");
  positive("equilibrate_min_scaling", equilibrate_min_scaling);
  positive("equilibrate_max_scaling", equilibrate_max_scaling);
  positive("reg_static", reg_static);
  positive("refine_tol_rel", refine_tol_rel);
  positive("dense_column_ratio", dense_column_ratio);
  if (max_iter < 0) messages.push_back("max_iter must be >= 0");
  if (!(step_fraction > 0 && step_fraction < 1))
    messages.push_back("step_fraction must be in (0, 1)");
  if (!(warm_start_weight > 0 && warm_start_weight < 1))
    messages.push_back("warm_start_weight must be in (0, 1)");
  if (!(snapshot_gap_rel >= 0) || !std::isfinite(snapshot_gap_rel))
    messages.push_back("snapshot_gap_rel must be finite and >= 0");
  if (!(memory_limit_bytes >= 0) || !std::isfinite(memory_limit_bytes))
    messages.push_back("memory_limit_bytes must be finite and >= 0");
  if (blas_threads < 0 || blas_threads > 256) messages.push_back("blas_threads must be in [0, 256]");
  if (threads < 1 || threads > 2) messages.push_back("threads must be 1 or 2");
  if (split_min_rows < 0) messages.push_back("split_min_rows must be >= 0");
  if (!(sigma_skip_fraction >= 0 && sigma_skip_fraction < 1))
    messages.push_back("sigma_skip_fraction must be in [0, 1)");
  if (max_centrality_correctors < 0 || max_centrality_correctors > 20)
    messages.push_back("max_centrality_correctors must be in [0, 20]");
  if (equilibrate_max_iter < 0) messages.push_back("equilibrate_max_iter must be >= 0");
  if (equilibrate_min_scaling > 1 || equilibrate_max_scaling < 1) {
    messages.push_back("equilibrate_min_scaling <= 1 <= equilibrate_max_scaling is required");
  }
  if (!(reg_retry_factor > 1)) messages.push_back("reg_retry_factor must be > 1");
  if (reg_max_retries < 0) messages.push_back("reg_max_retries must be >= 0");
  if (refine_max_iter < 0) messages.push_back("refine_max_iter must be >= 0");
  if (dense_column_min_nnz < 1) messages.push_back("dense_column_min_nnz must be >= 1");
  if (dense_column_max < 0) messages.push_back("dense_column_max must be >= 0");
  return messages;
}

}  // namespace rbla::conic
