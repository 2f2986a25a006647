#include "analysis/sweep.hpp"

#include "model/errors.hpp"
#include "model/angles.hpp"

#include <cmath>

namespace rbla::analysis {
namespace {

/// The schema's largest friction coefficient.
constexpr double kLargestFriction = 100.0;

struct Named {
  SweepParameter parameter;
  const char* name;
};
constexpr Named kNames[] = {
    {SweepParameter::Friction, "friction"},
    {SweepParameter::FrictionFactor, "friction_factor"},
    {SweepParameter::UnitWeightFactor, "unit_weight_factor"},
    {SweepParameter::SeismicAngle, "seismic_angle"},
    {SweepParameter::SettlementTilt, "settlement_tilt"},
    {SweepParameter::SettlementAzimuth, "settlement_azimuth"},
};

/// splitmix64 (Steele, Lea & Flood, OOPSLA 2014): a fixed, portable sequence.
std::uint64_t next(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

double fraction(std::uint64_t& state) { return static_cast<double>(next(state) >> 11) * 0x1.0p-53; }

double grid_value(const SweepAxis& axis, int k) {
  return axis.count <= 1 ? axis.low : axis.low + (axis.high - axis.low) * k / (axis.count - 1);
}

std::string pointer_of(SweepParameter parameter) { return std::string("sweep parameter ") + to_string(parameter); }

void require(bool ok, SweepParameter parameter, const std::string& message) {
  if (!ok) throw model::ModelError(pointer_of(parameter), message);
}

void set_friction(model::Model& m, SweepParameter parameter, double value) {
  for (auto& contact : m.interfaces) {
    contact.friction = parameter == SweepParameter::Friction ? value : contact.friction * value;
    require(contact.friction > 0.0 && contact.friction <= kLargestFriction, parameter,
            "gives a friction coefficient of " + std::to_string(contact.friction) + ", outside (0, 100]");
  }
}

/// Tilt and azimuth together give the settlement direction: gravity turned by the tilt towards
/// the azimuth.
void set_settlement(model::Model& m, double tilt_degrees, double azimuth_degrees) {
  const auto [x, y] = m.horizontal_axes();
  const double tilt = model::radians(tilt_degrees), azimuth = model::radians(azimuth_degrees);
  const model::Vec3 sideways = std::cos(azimuth) * x + std::sin(azimuth) * y;
  m.analysis.settlement_direction = (std::cos(tilt) * m.gravity.normalized() + std::sin(tilt) * sideways).normalized();
}

}  // namespace

/// The largest unit-weight factor a sweep applies: a factor of 1e300 made unit weights of 1e301,
/// far beyond the schema's 1e12, and no study of masonry needs a thousand times its weight.
constexpr double kLargestWeightFactor = 1000.0;

const char* to_string(SweepParameter parameter) {
  for (const Named& n : kNames) {
    if (n.parameter == parameter) return n.name;
  }
  return "unknown";
}

std::optional<SweepParameter> parse_sweep_parameter(const std::string& name) {
  for (const Named& n : kNames) {
    if (name == n.name) return n.parameter;
  }
  return std::nullopt;
}

std::vector<SweepPoint> grid_points(const std::vector<SweepAxis>& axes) {
  std::size_t total = 1;
  for (const SweepAxis& axis : axes) total *= static_cast<std::size_t>(std::max(axis.count, 1));
  std::vector<SweepPoint> points(total);
  for (std::size_t i = 0; i < total; ++i) {
    points[i].index = static_cast<int>(i);
    points[i].values.resize(axes.size());
    std::size_t rest = i;
    for (std::size_t a = axes.size(); a-- > 0;) {
      const int count = std::max(axes[a].count, 1);
      points[i].values[a] = grid_value(axes[a], static_cast<int>(rest % count));
      rest /= count;
    }
  }
  return points;
}

std::vector<SweepPoint> random_points(const std::vector<SweepAxis>& axes, int samples, std::uint64_t seed) {
  std::uint64_t state = seed;
  std::vector<SweepPoint> points(static_cast<std::size_t>(std::max(samples, 0)));
  for (std::size_t i = 0; i < points.size(); ++i) {
    points[i].index = static_cast<int>(i);
    for (const SweepAxis& axis : axes) points[i].values.push_back(axis.low + (axis.high - axis.low) * fraction(state));
  }
  return points;
}

model::Model model_at(const model::Model& model, const std::vector<SweepAxis>& axes, const SweepPoint& point) {
  model::Model m = model;
  const bool settlement = m.analysis.type == model::AnalysisType::Settlement;
  std::optional<double> tilt, azimuth;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const SweepParameter parameter = axes[a].parameter;
    const double value = point.values[a];
    switch (parameter) {
      case SweepParameter::Friction:
      case SweepParameter::FrictionFactor: set_friction(m, parameter, value); break;
      case SweepParameter::UnitWeightFactor:
        require(value > 0.0 && value <= kLargestWeightFactor, parameter,
                "must be in (0, 1000]: at 0 every block is weightless, and no study needs more");
        for (auto& block : m.blocks) block.unit_weight *= value;
        break;
      case SweepParameter::SeismicAngle: {
        require(!settlement && m.live_loads.empty(), parameter,
                "applies to a load_multiplier analysis whose live load is the seismic load only");
        const auto [x, y] = m.horizontal_axes();
        const double angle = model::radians(value);
        m.analysis.seismic_direction = std::cos(angle) * x + std::sin(angle) * y;
        break;
      }
      case SweepParameter::SettlementTilt:
        require(settlement, parameter, "applies to a settlement analysis");
        require(value >= 0.0 && value < 90.0, parameter, "must be in [0, 90) degrees from gravity");
        tilt = value;
        break;
      case SweepParameter::SettlementAzimuth:
        require(settlement, parameter, "applies to a settlement analysis");
        azimuth = value;
        break;
    }
  }
  if (tilt || azimuth) set_settlement(m, tilt.value_or(0.0), azimuth.value_or(0.0));
  return m;
}

void check_sweep(const model::Model& model, const std::vector<SweepAxis>& axes) {
  for (const SweepAxis& axis : axes) {
    require(std::isfinite(axis.low) && std::isfinite(axis.high), axis.parameter, "needs finite bounds");
    require(axis.count >= 1, axis.parameter, "needs at least one value");
  }
  // A forced planar formulation holds only for loads in its plane; turning them would fail at
  // the first point out of it, after the points before had run.
  for (const SweepAxis& axis : axes) {
    const bool turns_the_load = axis.parameter == SweepParameter::SeismicAngle ||
                                axis.parameter == SweepParameter::SettlementTilt ||
                                axis.parameter == SweepParameter::SettlementAzimuth;
    if (turns_the_load && model.analysis.formulation == model::Formulation::Planar) {
      throw model::ModelError("/analysis/formulation",
                              std::string("is planar, and the sweep's ") + to_string(axis.parameter) +
                                  " turns the load out of the plane: set it to auto (planar where the load is in plane) or 3d");
    }
  }
  for (int end = 0; end < 2; ++end) {
    SweepPoint corner;
    for (const SweepAxis& axis : axes) corner.values.push_back(end == 0 ? axis.low : axis.high);
    model_at(model, axes, corner);
  }
}

}  // namespace rbla::analysis
