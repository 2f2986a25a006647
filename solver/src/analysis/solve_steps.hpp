// Steps shared by the analysis pipeline (limit_analysis.cpp) and the iterative strategies that
// wrap its solve (non_associative.cpp): solver settings from the request, the time budget, and
// reading a conic solution back as a value, forces and a mechanism.
#pragma once

#include "analysis/analysis_result.hpp"
#include "analysis/formulation.hpp"
#include "analysis/limit_analysis.hpp"
#include "analysis/text.hpp"
#include "model/model.hpp"
#include "rbla/conic/solver.hpp"

#include <chrono>
#include <limits>
#include <string>
#include <vector>

namespace rbla::analysis {

/// The analysis's time budget (model.analysis.time_limit; 0 or less is no limit).
struct Deadline {
  Clock::time_point start = Clock::now();
  double limit_seconds = 0.0;
  double left() const {
    if (limit_seconds <= 0.0) return std::numeric_limits<double>::infinity();
    return std::max(0.0, limit_seconds - seconds_since(start));
  }
};

/// Block ids for messages: the first `shown` of `blocks` (indices into model.blocks), quoted,
/// then how many more there are.
std::string quoted_block_ids(const model::Model& m, const std::vector<int>& blocks, std::size_t shown);

/// Conic settings for one solve of the request, with `time_left` seconds.
conic::Settings solver_settings(const model::AnalysisRequest& request, const AnalysisOptions& options,
                                double time_left);

/// The value the problem optimises: alpha, or the base reaction in kN under settlement.
double multiplier_value(const Formulation& f, const Eigen::VectorXd& x);

/// Normal force (kN, compression positive) at every formulation point.
std::vector<double> normal_forces(const model::Model& m, const Formulation& f, const std::vector<Vec3>& forces);

/// Fills the mechanism, work balance and accuracy of a solved problem. Associative: the motion of
/// blocks with no load is settled first (unloaded_blocks.hpp); a non-associative state's
/// mechanism comes settled from its own problem. Non-associative: sliding points dissipate
/// mu N |slip| (associative sliding dissipates nothing: its dilatancy work cancels the friction
/// work).
void read_solution(const model::Model& m, const Formulation& f, const conic::Solution& solution, bool associative,
                   AnalysisResult& result);

/// Which blocks fall, from a primal infeasibility certificate y (b^T y > 0, -A^T y in K*): a
/// kinematically admissible motion on which the dead loads do positive work.
void read_certificate(const model::Model& m, const Formulation& f, const conic::Solution& solution,
                      AnalysisResult& result);

void record_size(const Formulation& f, AnalysisResult& result);

}  // namespace rbla::analysis
