#include "analysis/solve_steps.hpp"

#include "analysis/mechanism.hpp"
#include "analysis/unloaded_blocks.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rbla::analysis {

std::string quoted_block_ids(const model::Model& m, const std::vector<int>& blocks, std::size_t shown) {
  std::string text;
  for (std::size_t k = 0; k < blocks.size() && k < shown; ++k) {
    text += (k == 0 ? "'" : ", '") + m.blocks[blocks[k]].id + "'";
  }
  if (blocks.size() > shown) text += ", ... (" + std::to_string(blocks.size() - shown) + " more)";
  return text;
}

namespace {

/// Virtual power of the dead and live loads for the block motions (kN m per unit time).
void load_work(const model::Model& m, const std::vector<BlockMotion>& motions, bool settlement, double& dead,
               double& live) {
  dead = live = 0.0;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    const model::Block& block = m.blocks[b];
    if (block.is_support()) continue;
    dead += block.weight() * m.gravity.dot(motions[b].translation);
    if (!settlement && m.analysis.seismic_direction) {
      live += block.weight() * m.analysis.seismic_direction->dot(motions[b].translation);
    }
  }
  auto power = [&](const model::PointLoad& load) {
    return load.force.dot(point_velocity(m, motions, load.block, load.point)) + load.moment.dot(motions[load.block].rotation);
  };
  for (const auto& load : m.dead_loads) dead += power(load);
  if (!settlement) {
    for (const auto& load : m.live_loads) live += power(load);
  }
}

/// Largest force imbalance over the blocks' force rows, in kN, of A x - b.
double equilibrium_residual(const Formulation& f, const Eigen::VectorXd& x) {
  const Eigen::VectorXd r = f.problem.A * x - f.problem.b;
  double worst = 0.0;
  for (std::size_t b = 0; b < f.block_row.size(); ++b) {
    const int row = f.block_row[b];
    if (row < 0) continue;
    const double scale = f.block_scale[b];  // the reference for the moving supports' row
    const int force_rows = f.rows_per_block == 6 ? 3 : 2;
    for (int k = 0; k < force_rows && row + k < f.first_radius_row; ++k) {
      worst = std::max(worst, std::abs(r[row + k]) * scale);
    }
  }
  return worst;
}

}  // namespace

conic::Settings solver_settings(const model::AnalysisRequest& request, const AnalysisOptions& options,
                                double time_left) {
  conic::Settings settings;
  settings.tol_gap_rel = request.tol_relative_gap;
  settings.tol_feas = request.tol_feasibility;
  settings.tol_infeas = std::max(request.tol_feasibility, 1e-10);
  // The caller checks for an exhausted budget first; a positive floor keeps the settings valid
  // when the clock runs out in between (the solver then stops at once with TimeLimit).
  settings.time_limit_seconds = std::max(time_left, 1e-6);
  settings.verbose = options.log != nullptr;
  settings.log_stream = options.log;
  settings.threads = options.threads;
  return settings;
}

double multiplier_value(const Formulation& f, const Eigen::VectorXd& x) {
  const double value = x[f.multiplier_variable];
  return f.settlement ? value * f.force_scale : value;
}

std::vector<double> normal_forces(const model::Model& m, const Formulation& f, const std::vector<Vec3>& forces) {
  std::vector<double> normals(forces.size());
  for (std::size_t p = 0; p < forces.size(); ++p) {
    normals[p] = std::max(0.0, forces[p].dot(m.interfaces[f.points[p].interface_index].normal));
  }
  return normals;
}

void read_solution(const model::Model& m, const Formulation& f, const conic::Solution& solution, bool associative,
                   AnalysisResult& result) {
  const auto start = Clock::now();
  const std::vector<Vec3> forces = f.point_forces(solution.x);
  // A non-associative state's mechanism comes settled from its own problem (non_associative.cpp).
  Eigen::VectorXd y = solution.y;
  if (associative) result.mechanism.arbitrary_blocks = settle_unloaded_blocks(m, f, f.problem.c, y).unsettled;
  result.mechanism.blocks = block_velocities(m, f, y);
  result.mechanism.normalisation = f.settlement ? Normalisation::UnitSettlement : Normalisation::MaxTranslation;
  // One unit of the user's length: displacements read in the user's units come out as 1.
  normalise(m, f, result.mechanism.normalisation, m.units.length_to_m, result.mechanism.blocks);
  fill_interfaces(m, corner_forces(m, f, forces), associative, result.mechanism);

  double dissipation = 0.0;
  if (!associative) {
    // Sliding without dilatancy: the friction force mu N works against the slip.
    for (std::size_t p = 0; p < f.points.size(); ++p) {
      const FormulationPoint& point = f.points[p];
      const auto& interface_result = result.mechanism.interfaces[point.interface_index];
      const double normal = std::max(0.0, forces[p].dot(m.interfaces[point.interface_index].normal));
      double slip = 0.0;
      for (int k : point.corners) {
        const Vec3& dv = interface_result.points[k].relative_velocity;
        slip += std::hypot(dv[1], dv[2]) / static_cast<double>(point.corners.size());
      }
      dissipation += point.friction * normal * slip;
    }
  }
  double dead = 0.0, live = 0.0;
  load_work(m, result.mechanism.blocks, f.settlement, dead, live);
  WorkBalance& work = result.work;
  work.dead_work = dead;
  work.live_work = live;
  work.dissipation = dissipation;
  const double value = multiplier_value(f, solution.x);
  if (f.settlement) {
    // Virtual power: dead + (-R d).(v_s d) = dissipation, with v_s the normalised settlement.
    work.kinematic_value = (dead - dissipation) / m.units.length_to_m;
    work.relative_error = std::abs(value - work.kinematic_value) / std::max(std::abs(value), f.force_scale * 1e-12);
  } else if (live != 0.0) {
    work.kinematic_value = (dissipation - dead) / live;
    work.relative_error = std::abs(value - work.kinematic_value) / std::max(1.0, std::abs(value));
  }
  result.accuracy.relative_gap = solution.info.gap_rel;
  result.accuracy.primal_residual = solution.info.res_primal;
  result.accuracy.dual_residual = solution.info.res_dual;
  result.accuracy.equilibrium_residual = equilibrium_residual(f, solution.x);
  result.mechanism_seconds += seconds_since(start);
}

void read_certificate(const model::Model& m, const Formulation& f, const conic::Solution& solution,
                      AnalysisResult& result) {
  result.mechanism.blocks = block_velocities(m, f, solution.y);
  result.mechanism.normalisation = Normalisation::MaxTranslation;
  normalise(m, f, Normalisation::MaxTranslation, m.units.length_to_m, result.mechanism.blocks);
  fill_interfaces(m, {}, true, result.mechanism, MotionKind::Certificate);
}

void record_size(const Formulation& f, AnalysisResult& result) {
  result.size.num_variables = f.problem.A.cols();
  result.size.num_equality_rows = f.problem.A.rows();
  result.size.num_cones = static_cast<long>(f.problem.cones.num_nonneg + f.problem.cones.soc_dims.size());
  result.size.num_nonzeros = f.problem.A.nonZeros();
}

}  // namespace rbla::analysis
