#include "analysis/cone_search.hpp"

#include "analysis/text.hpp"
#include "rbla/conic/solver.hpp"
#include "model/angles.hpp"

#include <Eigen/Geometry>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rbla::analysis {
namespace {

using rbla::model::kPi;

using Vec3 = Eigen::Vector3d;

/// Two unit vectors completing the axis to a right-handed orthonormal frame.
struct Frame {
  Vec3 axis, e1, e2;
};

Frame frame_of(const Vec3& axis) {
  Frame f;
  f.axis = axis.normalized();
  const Vec3 seed = std::abs(f.axis.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  f.e1 = (seed - seed.dot(f.axis) * f.axis).normalized();
  f.e2 = f.axis.cross(f.e1);
  return f;
}

/// The unit direction at `tilt` from the axis and `azimuth` about it (from e1 towards e2).
Vec3 direction_at(const Frame& f, double tilt, double azimuth) {
  return std::cos(tilt) * f.axis + std::sin(tilt) * (std::cos(azimuth) * f.e1 + std::sin(azimuth) * f.e2);
}

/// The master problem: max z subject to z <= g_k . d for every cut, w . d = 1, d in the cone.
/// With q in Q^3 and d = (q0 / tan(beta)) axis + q1 e1 + q2 e2, ||(q1, q2)|| <= q0 is the cone;
/// z = z+ - z- (no free variables in rbla::conic), one slack per cut. Variables in the conic
/// layer's order: z+, z-, slacks (nonnegative), then q.
struct Master {
  conic::ConicProblem problem;
  int q = 0;  ///< index of q0
};

Master master_problem(const std::vector<Vec3>& cuts, const DirectionCone& cone, const Frame& f) {
  const int k = static_cast<int>(cuts.size());
  Master m;
  m.q = 2 + k;
  const double t = std::tan(cone.half_angle);
  auto along = [&](const Vec3& g) { return Vec3(g.dot(f.axis) / t, g.dot(f.e1), g.dot(f.e2)); };
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < k; ++i) {
    const Vec3 a = along(cuts[i]);
    for (int j = 0; j < 3; ++j) entries.emplace_back(i, m.q + j, a[j]);
    entries.emplace_back(i, 0, -1.0);
    entries.emplace_back(i, 1, 1.0);
    entries.emplace_back(i, 2 + i, -1.0);
  }
  const Vec3 a = along(cone.w);
  for (int j = 0; j < 3; ++j) entries.emplace_back(k, m.q + j, a[j]);
  m.problem.A.resize(k + 1, m.q + 3);
  m.problem.A.setFromTriplets(entries.begin(), entries.end());
  m.problem.A.makeCompressed();
  m.problem.b = Eigen::VectorXd::Zero(k + 1);
  m.problem.b[k] = 1.0;
  m.problem.c = Eigen::VectorXd::Zero(m.q + 3);
  m.problem.c[0] = -1.0;
  m.problem.c[1] = 1.0;
  m.problem.cones.num_nonneg = m.q;
  m.problem.cones.soc_dims = {3};
  return m;
}

/// Where the cuts' upper envelope is highest on the slice, and that height (an upper bound of the
/// maximum, from the larger of the master's primal and dual objectives); empty when the master
/// problem did not solve.
struct MasterAnswer {
  Vec3 direction = Vec3::Zero();
  double bound = 0.0;
  bool solved = false;
};

MasterAnswer solve_master(const std::vector<Vec3>& cuts, const DirectionCone& cone, const Frame& f) {
  const Master m = master_problem(cuts, cone, f);
  conic::Settings settings;
  settings.tol_gap_rel = 1e-10;
  MasterAnswer answer;
  conic::Solution s;
  try {
    s = conic::solve(m.problem, settings);
  } catch (const conic::ConicSetupError&) {
    return answer;  // cuts too large to state: the search stops without a bound
  }
  if (!conic::has_solution(s.info.status)) return answer;
  const Vec3 d = (s.x[m.q] / std::tan(cone.half_angle)) * f.axis + s.x[m.q + 1] * f.e1 + s.x[m.q + 2] * f.e2;
  if (!(d.norm() > 0.0) || !d.allFinite()) return answer;
  answer.direction = d.normalized();
  // min -z: its dual objective b.y is below the optimum, so -b.y bounds max z from above.
  answer.bound = std::max(-s.info.primal_objective, -s.info.dual_objective);
  answer.solved = std::isfinite(answer.bound);
  return answer;
}

int largest_ratio(const std::vector<ConeSample>& samples) {
  int best = -1;
  for (int i = 0; i < static_cast<int>(samples.size()); ++i) {
    if (!samples[i].usable || !std::isfinite(samples[i].ratio)) continue;
    if (best < 0 || samples[i].ratio > samples[best].ratio) best = i;
  }
  return best;
}

double nearest_angle(const std::vector<ConeSample>& samples, const Vec3& d) {
  double nearest = kPi;
  for (const ConeSample& s : samples) nearest = std::min(nearest, std::acos(std::clamp(s.direction.dot(d), -1.0, 1.0)));
  return nearest;
}

/// The axis, then `rim_samples` directions evenly around the rim.
std::vector<Vec3> first_directions(const Frame& f, const DirectionCone& cone, const ConeSearchSettings& settings) {
  std::vector<Vec3> directions{f.axis};
  for (int i = 0; i < settings.rim_samples; ++i) {
    directions.push_back(direction_at(f, cone.half_angle, 2.0 * kPi * i / settings.rim_samples));
  }
  return directions;
}

void check_settings(const DirectionCone& cone, const ConeSearchSettings& settings) {
  if (!(cone.half_angle > 0.0 && cone.half_angle < 0.5 * kPi)) {
    throw std::invalid_argument("the cone's half angle must lie strictly between 0 and 90 degrees");
  }
  if (!(cone.axis.norm() > 0.0)) throw std::invalid_argument("the cone's axis is zero");
  if (!(smallest_on_cone(cone) > 0.0)) throw std::invalid_argument("w . d is not positive on the whole cone");
  if (settings.rim_samples < 3 || settings.max_samples < settings.rim_samples + 1) {
    throw std::invalid_argument("at least 3 rim samples, and room for the axis and the rim in max_samples");
  }
}

/// Evaluates one direction; true when the search may go on.
bool take(const std::function<ConeSample(const Vec3&)>& evaluate, const Vec3& d, ConeMaximum& out) {
  ConeSample sample = evaluate(d);
  sample.direction = d;
  out.samples.push_back(sample);
  if (!sample.usable) {
    out.failed = true;
    out.stop = "an evaluation failed: " + sample.why_unusable;
    return false;
  }
  if (!std::isfinite(sample.ratio) || (sample.supergradient && !sample.supergradient->allFinite())) {
    out.failed = true;
    out.stop = "an evaluation returned a value or a supergradient that is not finite";
    return false;
  }
  return true;
}

/// The cuts of every sample; false when a sample lacks one (the envelope would not hold).
bool collect_cuts(const ConeMaximum& out, std::vector<Vec3>& cuts) {
  cuts.clear();
  for (const ConeSample& s : out.samples) {
    if (s.supergradient) cuts.push_back(*s.supergradient);
  }
  return cuts.size() == out.samples.size();
}

}  // namespace

double smallest_on_cone(const DirectionCone& cone) {
  const Vec3 a = cone.axis.normalized();
  const double along = cone.w.dot(a);
  const double across = (cone.w - along * a).norm();
  return along * std::cos(cone.half_angle) - across * std::sin(cone.half_angle);
}

ConeMaximum find_cone_maximum(const std::function<ConeSample(const Vec3& direction)>& evaluate,
                              const DirectionCone& cone, const ConeSearchSettings& settings) {
  check_settings(cone, settings);
  const Frame f = frame_of(cone.axis);
  ConeMaximum out;
  for (const Vec3& d : first_directions(f, cone, settings)) {
    if (!take(evaluate, d, out)) {
      out.best = largest_ratio(out.samples);
      return out;
    }
  }
  std::vector<Vec3> cuts;
  while (true) {
    out.best = largest_ratio(out.samples);
    const double lower = out.samples[out.best].ratio;
    const bool all_cut = collect_cuts(out, cuts);
    const MasterAnswer master = solve_master(cuts, cone, f);
    if (!all_cut || !master.solved) {
      out.stop = all_cut ? "the cutting-plane problem did not solve; the best direction evaluated is reported"
                         : "an evaluation gave no cutting plane; the best direction evaluated is reported";
      return out;
    }
    const double envelope = std::max(master.bound, lower);
    if (settings.concave) out.upper_bound = envelope;
    if (envelope - lower <= settings.tolerance * std::abs(envelope)) {
      // Without concavity the planes only guide: their envelope closing on the best value is
      // where the search has nothing better to try, not a bound.
      out.converged = settings.concave;
      out.stop = settings.concave
                     ? "the bracket [" + format(lower) + ", " + format(envelope) + "] is within the tolerance"
                     : "the cutting planes' envelope closed on the best value (" + format(envelope) +
                           "); not a bound, the function is not known to be concave";
      return out;
    }
    if (static_cast<int>(out.samples.size()) >= settings.max_samples) {
      out.stop = "stopped at " + std::to_string(settings.max_samples) + " evaluations" +
                 (out.upper_bound ? " with the bracket [" + format(lower) + ", " + format(*out.upper_bound) + "]" : "");
      return out;
    }
    if (nearest_angle(out.samples, master.direction) < settings.angle_resolution) {
      out.stop = "the next direction repeats one evaluated (within " + format(settings.angle_resolution) + " rad)";
      return out;
    }
    if (!take(evaluate, master.direction, out)) {
      out.best = largest_ratio(out.samples);
      return out;
    }
  }
}

}  // namespace rbla::analysis
