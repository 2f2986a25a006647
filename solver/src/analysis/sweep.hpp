// Parameter studies: the same model over a grid or a seeded random sample of parameters
// (docs/sweeps.md). This part only defines the points and the model at each; running them (in
// parallel processes, or as the tasks of a Slurm job array) is the command line's job, and each
// point is an ordinary analysis.
#pragma once

#include "model/model.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rbla::analysis {

enum class SweepParameter {
  Friction,           ///< every interface's friction coefficient set to this value (-)
  FrictionFactor,     ///< every interface's friction coefficient times this (-)
  UnitWeightFactor,   ///< every block's unit weight times this (-)
  SeismicAngle,       ///< seismic load along this angle in the horizontal plane (deg, Model::horizontal_axes)
  SettlementTilt,     ///< settlement direction tilted from gravity by this angle (deg)
  SettlementAzimuth,  ///< ... towards this angle in the horizontal plane (deg)
};
const char* to_string(SweepParameter parameter);  ///< the command line's names: friction, ...
std::optional<SweepParameter> parse_sweep_parameter(const std::string& name);

/// One parameter and its range: `count` evenly spaced values from `low` to `high` on a grid; a
/// random sample draws uniformly between them.
struct SweepAxis {
  SweepParameter parameter = SweepParameter::Friction;
  double low = 0.0, high = 0.0;
  int count = 1;
};

struct SweepPoint {
  int index = 0;
  std::vector<double> values;  ///< one per axis, in the axes' order
};

/// Every combination of the axes' values (the last axis varies fastest).
std::vector<SweepPoint> grid_points(const std::vector<SweepAxis>& axes);

/// `samples` points, each value uniform in its axis' range, from a 64-bit seed. The same seed
/// gives the same points on every platform (splitmix64 and 53-bit fractions, not the standard
/// library's distributions, whose output the standard leaves to the implementation).
std::vector<SweepPoint> random_points(const std::vector<SweepAxis>& axes, int samples, std::uint64_t seed);

/// The model at a point. Throws model::ModelError when a parameter does not apply to the model's
/// analysis (a settlement angle in a load-multiplier analysis, a seismic angle under settlement)
/// or a value is out of range (a friction coefficient not in (0, 100], a negative weight factor).
model::Model model_at(const model::Model& model, const std::vector<SweepAxis>& axes, const SweepPoint& point);

/// Checks the axes against the model once, before any point runs (model_at's errors, found at
/// the ranges' ends).
void check_sweep(const model::Model& model, const std::vector<SweepAxis>& axes);

}  // namespace rbla::analysis
