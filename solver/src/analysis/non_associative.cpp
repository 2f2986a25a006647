#include "analysis/non_associative.hpp"

#include "analysis/compatible_states.hpp"
#include "analysis/mechanism.hpp"
#include "analysis/unloaded_blocks.hpp"
#include "model/angles.hpp"

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <optional>

namespace rbla::analysis {

namespace {

/// The cost is shifted by (1 + kSelectionShift) s to pick the conservative end of the optimal face
/// (and by 1 - kSelectionShift for the other end): on that face -alpha + sum s N is constant, so
/// the extra eps sum s N selects the state with the least friction at sliding points. For a linear
/// program a small enough eps selects exactly (exact penalty); it is checked (on_face) and retried
/// smaller once.
constexpr double kSelectionShift = 1e-3;
/// Anderson mixing memory (Walker & Ni 2011): two previous shifts were the best of 1 to 3 on the
/// facade and church scenes (docs/benchmark).
constexpr int kAndersonMemory = 2;
/// Intermediate steps are solved to this relative gap; the shifts they feed have a floor of about
/// 1e-4 relative (degenerate mechanisms), so tighter solves buy nothing. The reported states are
/// solved at the requested tolerances.
constexpr double kStepGap = 1e-6;
/// Each step warm-starts from the previous solve's iterate at kNonAssociativeSnapshotGap, blended
/// with the central point by this weight (ConicSolver::set_warm_start). On the six scenes of
/// docs/benchmark/non_associative_states.md, 0.999 took 6 % fewer iterations in all than 0.99,
/// 0.9 and 0.9999 more; the certified values agreed to 8e-5 (docs/benchmark/non_associative.md).
constexpr double kWarmStartWeight = 0.999;
/// A step whose own state dilates by less than this (relative to the value) is tested (two more
/// solves, see ShiftScheme::certify): the first such step, then every TestSchedule::when_close
/// steps; any step TestSchedule::at_most steps after the last test. The state of a step whose
/// mechanism is not unique (a squat wall sliding at mu on any of its bed joints) can keep dilating
/// while the value settles.
constexpr double kCheckDilatancy = 1e-2;
/// The schedules of the trajectories, in the order they run. Where a run tests decides which of
/// several collapse states it certifies. On the six scenes of docs/benchmark/non_associative_states.md
/// the first certified the most conservative state of the six schedules on three, and the first
/// three together on five (within 0.04 % on the sixth).
constexpr TestSchedule kSchedules[] = {{3, 10}, {3, 3}, {5, 20}, {5, 5}, {2, 2}, {15, 15}};
constexpr int kNumSchedules = static_cast<int>(sizeof(kSchedules) / sizeof(kSchedules[0]));

/// s_k = mu_k |d_t,k|: the friction work rate a sliding point would need to dissipate without
/// dilatancy, in the dual's own velocity units (formulation units, unnormalised).
std::vector<double> slip_shift(const model::Model& m, const Formulation& f, const Eigen::VectorXd& y) {
  const std::vector<Vec3> d = formulation_point_velocities(m, f, y);
  std::vector<double> shift(f.points.size(), 0.0);
  for (std::size_t p = 0; p < f.points.size(); ++p) {
    const Vec3& n = m.interfaces[f.points[p].interface_index].normal;
    shift[p] = f.points[p].friction * (d[p] - d[p].dot(n) * n).norm();
  }
  return shift;
}

/// The associative cost plus factor * s_k on each point's normal force, in units of the model's
/// force scale (N_k = sum_j (g_j . n) x_j times the point's own scale over the model's).
Eigen::VectorXd shifted_cost(const model::Model& m, const Formulation& f, const Eigen::VectorXd& cost,
                             const Eigen::VectorXd& shift, double factor) {
  Eigen::VectorXd c = cost;
  for (std::size_t p = 0; p < f.points.size(); ++p) {
    if (shift[p] == 0.0) continue;
    const Vec3& n = m.interfaces[f.points[p].interface_index].normal;
    const double units = f.points[p].force_scale / f.force_scale;
    for (const Generator& g : f.points[p].generators) c[g.variable] += factor * shift[p] * units * g.force.dot(n);
  }
  return c;
}

/// sum_k N_k |d_n,k| over the points: the work of the normal forces on normal motion, zero exactly
/// when the state is compatible with the mechanism without dilatancy (sliding points keep
/// contact, opening points carry nothing). In the problem's value units per unit live work.
double dilatancy_work(const model::Model& m, const Formulation& f, const conic::Solution& forces_from,
                      const Eigen::VectorXd& y) {
  const std::vector<Vec3> d = formulation_point_velocities(m, f, y);
  const std::vector<Vec3> forces = f.point_forces(forces_from.x);
  double work = 0.0;
  for (std::size_t p = 0; p < f.points.size(); ++p) {
    const Vec3& n = m.interfaces[f.points[p].interface_index].normal;
    work += std::max(0.0, forces[p].dot(n)) / f.force_scale * std::abs(d[p].dot(n));
  }
  return f.settlement ? work * f.force_scale : work;
}

/// Anderson mixing, type II (Walker & Ni 2011, SIAM J. Numer. Anal. 49(4)), for the fixed point
/// s = G(s), with a damped plain step (weight `beta`) as the base and the history dropped when
/// the residual grows (the map is only piecewise smooth: an active-set change invalidates it).
class AndersonMixing {
 public:
  AndersonMixing(int memory, double beta) : memory_(memory), beta_(beta) {}

  Eigen::VectorXd next(const Eigen::VectorXd& s, const Eigen::VectorXd& g) {
    const Eigen::VectorXd r = g - s;
    if (last_s_.size() == s.size()) {
      if (r.norm() > 2.0 * last_r_.norm()) {
        ds_.clear();
        dr_.clear();
      } else {
        ds_.push_back(s - last_s_);
        dr_.push_back(r - last_r_);
        if (static_cast<int>(ds_.size()) > memory_) {
          ds_.pop_front();
          dr_.pop_front();
        }
      }
    }
    last_s_ = s;
    last_r_ = r;
    Eigen::VectorXd mixed = s + beta_ * r;
    if (!dr_.empty()) {
      const Eigen::Index k = static_cast<Eigen::Index>(dr_.size());
      Eigen::MatrixXd dR(s.size(), k), dS(s.size(), k);
      for (Eigen::Index j = 0; j < k; ++j) {
        dR.col(j) = dr_[j];
        dS.col(j) = ds_[j];
      }
      const Eigen::VectorXd gamma = dR.colPivHouseholderQr().solve(r);
      if (gamma.allFinite()) mixed -= (dS + beta_ * dR) * gamma;
    }
    return mixed.cwiseMax(0.0);  // a shift is a dissipation rate: never negative
  }

 private:
  int memory_;
  double beta_;
  Eigen::VectorXd last_s_, last_r_;
  std::deque<Eigen::VectorXd> ds_, dr_;
};

Eigen::VectorXd to_vector(const std::vector<double>& v) { return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size())); }

double relative_change(const Eigen::VectorXd& before, const Eigen::VectorXd& after) {
  const double size = std::max(before.lpNorm<Eigen::Infinity>(), after.lpNorm<Eigen::Infinity>());
  return size > 0.0 ? (after - before).lpNorm<Eigen::Infinity>() / size : 0.0;
}

/// One run of the scheme on the associative solver.
class ShiftScheme {
 public:
  ShiftScheme(const model::Model& m, const Formulation& f, conic::ConicSolver& solver, const Deadline& deadline,
              TestSchedule schedule, AnalysisResult& result)
      : m_(m), f_(f), solver_(solver), deadline_(deadline), schedule_(schedule), result_(result),
        request_(m.analysis), cost_(solver.problem().c),
        mixing_(kAndersonMemory, request_.non_associative_damping) {}

  ~ShiftScheme() { solver_.update_c(cost_); }

  /// Interior-point iterations of the run's solves: its steps, and the rest (the selections of
  /// the conservative state, the fixed-point tests and the range).
  struct Iterations {
    int steps = 0;
    int tests = 0;
  };
  Iterations iterations() const { return iterations_; }

  void run(const conic::Solution& associative, double& value) {
    Eigen::VectorXd shift = to_vector(slip_shift(m_, f_, associative.y));
    normals_ = normal_forces(m_, f_, f_.point_forces(associative.x));
    if (request_.non_associative_warm_start) snapshot_ = associative.snapshot;
    result_.non_associative.push_back({0, value, dilatancy_work(m_, f_, associative, associative.y) / scale(value), 0.0,
                                       0.0, associative.info.iterations, associative.info.total_seconds});
    if (shift.lpNorm<Eigen::Infinity>() == 0.0) {
      // No point slides in the associative mechanism: it has no dilatancy to remove.
      result_.non_associative_converged = true;
      result_.non_associative_stop = "no contact point slides in the associative mechanism";
      // Then every state compatible with it has the same value (no friction work in its work
      // equation); the check says whether the associative state is one point by point.
      const PointPattern pattern = point_pattern(m_, f_, associative.y);
      const CompatibleStates states = states_matching(pattern);
      if (states.outcome == CompatibleStates::Outcome::Found) candidate_.pointwise = true;
      if (states.outcome == CompatibleStates::Outcome::None) {
        candidate_.pointwise = false;
        candidate_.violation = pattern_violation(m_, f_, pattern, associative.x);
      }
      record_pointwise();
      return;
    }
    int last_check = 0, last_step_number = 0;
    for (int step = 1; step <= request_.non_associative_max_iterations; ++step) {
      conic::Solution next;
      if (!solve(shifted_cost(m_, f_, cost_, shift, 1.0), kStepGap, next, step)) break;
      const double step_value = multiplier_value(f_, next.x);
      const Eigen::VectorXd rates = to_vector(slip_shift(m_, f_, next.y));
      const double dilatancy = dilatancy_work(m_, f_, next, next.y) / scale(step_value);
      result_.non_associative.push_back({step, step_value, dilatancy, relative_change(shift, rates),
                                         normal_force_change(next), next.info.iterations, next.info.total_seconds});
      // Certify when the step is close, every few steps: the step's own (analytic-centre) state
      // can keep some dilatancy while another state of its optimal face has none, when the
      // mechanism is not unique (a squat wall sliding at mu on any of its bed joints).
      const int wait = dilatancy > kCheckDilatancy        ? schedule_.at_most
                       : result_.non_associative_checks == 0 ? 0
                                                             : schedule_.when_close;
      if (step - last_check >= wait) {
        last_check = step;
        if (certify(next, shift) && accept(step)) break;
      }
      if (work_only_ && step >= retry_until_) {
        keep_work_only("no state certified in the next " + count(schedule_.at_most, "step", "steps") +
                       " matched its mechanism point by point");
        break;
      }
      last_step_ = std::move(next);
      last_shift_ = shift;
      last_step_number = step;
      if (last_check == step && capped_mechanism_.size() > 0) {
        // A failed test: the capped problem's mechanism does not dilate at all, and its slip
        // rates are a better next shift than the step's own (on the 1920-block facade the test's
        // gap fell from 4e-3 to 1.4e-4 with them, and stalled near 4e-3 without).
        shift = to_vector(slip_shift(m_, f_, capped_mechanism_));
        mixing_ = AndersonMixing(kAndersonMemory, request_.non_associative_damping);
      } else {
        shift = mixing_.next(shift, rates);
      }
    }
    if (work_only_ && !result_.non_associative_converged) {
      keep_work_only(result_.non_associative_stop.empty() ? "the step limit was reached before another state passed"
                                                          : "the search for one that does stopped: " +
                                                                result_.non_associative_stop);
    }
    if (!result_.non_associative_converged) {
      if (last_step_.x.size() == 0) return;
      if (result_.non_associative_stop.empty()) {
        result_.non_associative_stop = "the step limit (analysis.non_associative.max_iterations) was reached";
      }
      // The last step, unless the schedule has just tested it (and it failed: the candidate is
      // that test's), is tested now. A pass certifies it like any other state: the test does not
      // depend on how the state was reached.
      if (last_check != last_step_number && certify(last_step_, last_shift_)) {
        result_.non_associative_converged = true;
        result_.non_associative_stop += "; the last step's state passed the fixed-point test";
      }
    }
    report(value);
  }

 private:
  /// After a passed test (certify): whether the run ends with the candidate. A candidate that
  /// matches its mechanism only in work (compatible_states.hpp) is kept while the scheme goes on
  /// for up to TestSchedule::at_most more steps, looking for one that matches point by point.
  /// On the 16 of 48 planar runs whose first certified state matched only in work, this found one
  /// that matches on 4, at 37 to 74 % more interior-point iterations on those 16 runs; going on
  /// to 50 steps found one more (docs/method.md, "How compatible a certified state is").
  bool accept(int step) {
    const std::string passed = "the state passed the fixed-point test (shear capped at mu N)";
    if (candidate_.pointwise == true) {
      result_.non_associative_converged = true;
      result_.non_associative_stop =
          work_only_ ? passed + " and matches its mechanism point by point (an earlier one, " +
                           format(multiplier_value(f_, work_only_->state.x) / value_unit(), 6) +
                           ", matched its own in work only)"
                     : passed;
      work_only_.reset();
      return true;
    }
    if (!candidate_.pointwise) {
      // The check did not finish (the clock, or a solve that failed): the state is certified in
      // work, as far as anyone knows.
      if (work_only_) {
        keep_work_only("the check of the next state that passed did not finish");
        return true;
      }
      result_.non_associative_converged = true;
      result_.non_associative_stop = passed + "; its check point by point did not finish";
      return true;
    }
    if (!work_only_ && request_.non_associative_pointwise_retry) {
      work_only_ = candidate_;
      retry_until_ = step + schedule_.at_most;
      return false;
    }
    if (!work_only_) {
      result_.non_associative_converged = true;
      result_.non_associative_stop = passed + " and matches its mechanism in work only";
      return true;
    }
    keep_work_only("the next state that passed matched its mechanism in work only too");
    return true;
  }

  /// Ends the run with the more conservative of the states certified in work only (the later one
  /// may also be one whose check did not finish).
  void keep_work_only(const std::string& why) {
    const double kept = multiplier_value(f_, work_only_->state.x), later = multiplier_value(f_, candidate_.state.x);
    const bool later_is_certified = candidate_.confirmed && candidate_.pointwise != true;
    if (!later_is_certified || (f_.settlement ? kept >= later : kept <= later)) candidate_ = *work_only_;
    work_only_.reset();
    result_.non_associative_converged = true;
    result_.non_associative_stop = "the state passed the fixed-point test (shear capped at mu N) and matches its "
                                   "mechanism in work only; " + why;
  }

  /// kN per unit of the value in messages: the model's force unit under settlement, 1 for alpha.
  double value_unit() const { return f_.settlement ? m_.units.force_to_kN : 1.0; }

  /// Scale of the value for relative measures: |alpha| (at least 1e-6: a live load a millionth of
  /// its own size), or |R| (at least a millionth of the mean block weight). A floor far below that
  /// made a state at alpha = 0 (a block wedged between walls that slides under its own weight)
  /// impossible to certify: its test gap of 1e-11 was 10 times its value.
  double scale(double v) const {
    return f_.settlement ? std::max(std::abs(v), 1e-6 * f_.force_scale) : std::max(std::abs(v), 1e-6);
  }

  /// Largest change of a point's normal force (kN) since the previous call.
  double normal_force_change(const conic::Solution& solution) {
    const std::vector<double> normals = normal_forces(m_, f_, f_.point_forces(solution.x));
    double change = 0.0;
    for (std::size_t p = 0; p < normals.size(); ++p) change = std::max(change, std::abs(normals[p] - normals_[p]));
    normals_ = normals;
    return change;
  }

  /// Solves with the given cost; false (after a warning) when no solution came back. When the
  /// clock stops a run that holds a certified state (one certified in work only, kept by accept,
  /// one that has just passed the test, or the one whose range is being selected), that state is
  /// reported: the verdict stays.
  bool solve(const Eigen::VectorXd& cost, double gap, conic::Solution& out, int step) {
    const bool holds_certified = work_only_ || result_.non_associative_converged || candidate_.confirmed;
    if (deadline_.left() <= 0.0) {
      if (!holds_certified) result_.verdict = Verdict::TimeLimit;
      if (!result_.non_associative_converged) result_.non_associative_stop = "the time limit ran out";
      return false;
    }
    conic::Settings& s = solver_.settings();
    const conic::Settings saved = s;
    s.tol_gap_rel = std::max(gap, request_.tol_relative_gap);
    s.tol_gap_abs = std::max(gap, saved.tol_gap_abs);
    // A loose step resolves every block's own load as well as an O(1) right-hand side is
    // resolved: a block with its own force scale may have a right-hand side far below 1.
    s.tol_feas = std::max(gap * f_.rhs_resolution, saved.tol_feas);
    s.time_limit_seconds = std::max(deadline_.left(), 1e-6);
    s.snapshot_gap_rel = request_.non_associative_warm_start ? kNonAssociativeSnapshotGap : 0.0;
    s.warm_start_weight = kWarmStartWeight;
    solver_.update_c(cost);
    if (!snapshot_.empty()) solver_.set_warm_start(snapshot_.x, snapshot_.y, snapshot_.z);
    const auto start = Clock::now();
    out = solver_.solve();
    result_.solve_seconds += seconds_since(start);
    (step > 0 ? iterations_.steps : iterations_.tests) += out.info.iterations;
    s = saved;
    if (!out.snapshot.empty()) snapshot_ = out.snapshot;
    if (conic::has_solution(out.info.status)) return true;
    // The result's solver record is of the last solve: this one, which did not finish.
    result_.solver_info = out.info;
    result_.interior_point_history = out.info.history;
    const bool clock = out.info.status == conic::SolveStatus::TimeLimit || out.info.status == conic::SolveStatus::Cancelled;
    if (clock && !holds_certified) {
      result_.verdict = out.info.status == conic::SolveStatus::TimeLimit ? Verdict::TimeLimit : Verdict::Cancelled;
    }
    const std::string what = step > 0 ? "non-associative step " + std::to_string(step)
                                      : std::string("a selection solve of the non-associative scheme");
    const std::string outcome = holds_certified ? "; the state certified before it is reported"
                                : clock         ? "; the analysis stopped and no value is reported"
                                                : "; the last completed step is reported";
    result_.warnings.push_back(
        {"non_associative_step_failed", what + " ended with " + conic::to_string(out.info.status) + outcome, ""});
    // A failed step ends the run; a failed selection only loses that selection (certify keeps the
    // step's own state), unless the clock stopped it.
    if ((step > 0 || clock) && !result_.non_associative_converged) {
      result_.non_associative_stop =
          std::string(step > 0 ? "a step" : "a selection solve") + " ended with " + conic::to_string(out.info.status);
    }
    return false;
  }

  /// Whether x (from a selection solve) lies on the optimal face of the problem shifted by
  /// `shift`: its objective there within ten times a step's gap of that problem's optimum.
  bool on_face(const Eigen::VectorXd& x, const Eigen::VectorXd& shift, double optimum) const {
    const double objective = shifted_cost(m_, f_, cost_, shift, 1.0).dot(x);
    return std::abs(objective - optimum) <= 10.0 * kStepGap * std::max(1.0, std::abs(optimum));
  }

  /// The state at one end of the optimal face of the problem shifted by `shift`, whose optimum is
  /// `optimum`: factor 1 + eps is the conservative end, 1 - eps the other. False when the
  /// selection left the face (or failed).
  bool select(const Eigen::VectorXd& shift, double optimum, double sign, conic::Solution& end) {
    for (const double eps : {kSelectionShift, 0.1 * kSelectionShift}) {
      if (!solve(shifted_cost(m_, f_, cost_, shift, 1.0 + sign * eps), request_.tol_relative_gap, end, 0)) return false;
      if (on_face(end.x, shift, optimum)) return true;
    }
    return false;
  }

  /// After a passed test: the states compatible with the certified mechanism v (no force where it
  /// opens, mu N against the slip where it slides, anything in the cone where it stays closed) are
  /// exactly the optimal states of the problem shifted by v's own slip rates s_v = mu |d_t|. v is
  /// dual feasible there (it does not interpenetrate: d_n + s_v >= mu |d_t|) and complementary to
  /// each of them, and the candidate is one of them. The conservative end of that face is the
  /// state reported and its other end bounds the range. The step's face, with the shift that led
  /// to it, is another set: on a 44-block wall its conservative end was alpha 0.5177 where states
  /// compatible with the same mechanism go down to 0.4868 (an independent review, by its own LP).
  /// Nothing changes when the candidate is not on that face to the test's tolerance; the candidate
  /// stays when the selection is not more conservative than it.
  void move_to_mechanism_face() {
    const Eigen::VectorXd shift = to_vector(slip_shift(m_, f_, candidate_.mechanism_y));
    conic::Solution face, end;
    // Its optimum only places the face for on_face (10 kStepGap): a step's gap is enough.
    if (!solve(shifted_cost(m_, f_, cost_, shift, 1.0), kStepGap, face, 0)) return;
    const double optimum = face.info.primal_objective;
    const double candidate_objective = shifted_cost(m_, f_, cost_, shift, 1.0).dot(candidate_.state.x);
    const double tolerance = request_.non_associative_tolerance * std::max(1.0, std::abs(optimum));
    if (!(std::abs(candidate_objective - optimum) <= tolerance)) return;
    candidate_.shift = shift;
    candidate_.face_optimum = optimum;
    if (!select(shift, optimum, +1.0, end)) return;
    // The candidate lies on the face, so its conservative end is at least as conservative: a
    // selection that is not (by the solves' rounding, where the face is a single state) is not kept.
    const double before = multiplier_value(f_, candidate_.state.x), after = multiplier_value(f_, end.x);
    if (f_.settlement ? after >= before : after <= before) candidate_.state = std::move(end);
  }

  /// After a passed test: the state to report among those compatible with the certified
  /// mechanism. Point by point when the mechanism admits such states (compatible_states.hpp):
  /// their conservative end is reported and their other end bounds the range. Otherwise the
  /// certificate holds in work only: the conservative end of the mechanism's face is reported
  /// (move_to_mechanism_face), and how far it is from pointwise compatible.
  void settle_on_mechanism() {
    if (deadline_.left() <= 0.0) return;
    const PointPattern pattern = point_pattern(m_, f_, candidate_.mechanism_y);
    CompatibleStates states = states_matching(pattern);
    if (states.outcome == CompatibleStates::Outcome::Found) {
      candidate_.pointwise = true;
      candidate_.state = std::move(states.conservative);
      candidate_.other_end = multiplier_value(f_, states.other.x);
      return;
    }
    move_to_mechanism_face();
    if (states.outcome != CompatibleStates::Outcome::None) return;
    candidate_.pointwise = false;
    candidate_.violation = pattern_violation(m_, f_, pattern, candidate_.state.x);
  }

  /// The candidate's pointwise check into the result, with a warning when no state matched its
  /// mechanism point by point.
  void record_pointwise() {
    result_.non_associative_pointwise = candidate_.pointwise;
    if (!candidate_.pointwise) {
      result_.warnings.push_back(
          {"non_associative_pointwise_unchecked",
           "the check of the certified mechanism point by point did not finish (the time limit, or a solve that "
           "failed): the state matches its mechanism in work (to analysis.non_associative.tolerance), and whether "
           "any state matches it point by point is not known",
           "/analysis/non_associative"});
      return;
    }
    if (*candidate_.pointwise) return;
    result_.non_associative_open_force = candidate_.violation.open_force;
    result_.non_associative_friction_shortfall = candidate_.violation.friction_shortfall;
    result_.warnings.push_back(
        {"non_associative_not_pointwise",
         "the certified state matches its mechanism in work (to analysis.non_associative.tolerance), but no "
         "equilibrated state matches the mechanism point by point: in the state reported, points that open carry up "
         "to " + format(100.0 * candidate_.violation.open_force, 3) + " % of the largest normal force and points "
         "that slide fall short of full friction by up to " +
         format(100.0 * candidate_.violation.friction_shortfall, 3) +
         " % of it (other states may come closer; none matches exactly). States that nearly match may lie "
         "further from the value than the tolerance; a smaller "
         "tolerance or more runs (analysis.non_associative.trajectories) may find one that matches",
         "/analysis/non_associative/tolerance"});
  }

  /// The states compatible point by point with a mechanism's pattern (compatible_states.hpp).
  CompatibleStates states_matching(const PointPattern& pattern) {
    conic::Settings settings = solver_.settings();
    settings.time_limit_seconds = std::max(deadline_.left(), 1e-6);
    const auto start = Clock::now();
    CompatibleStates states = compatible_states(m_, f_, pattern, cost_, settings);
    result_.solve_seconds += seconds_since(start);
    iterations_.tests += states.iterations;
    return states;
  }

  /// Keeps the conservative state of `step`'s face (or, when that cannot be selected, the step's
  /// own state) as the candidate to report, and tests it: true when it is optimal for the
  /// cylinder problem built from its own normal forces (cylinder_confirms), whose mechanism is
  /// then the candidate's.
  bool certify(const conic::Solution& step, const Eigen::VectorXd& shift) {
    candidate_.shift = shift;
    candidate_.confirmed = false;
    candidate_.other_end.reset();
    candidate_.pointwise.reset();
    candidate_.face_optimum = step.info.primal_objective;
    candidate_.selected = select(shift, candidate_.face_optimum, +1.0, candidate_.state);
    if (!candidate_.selected) candidate_.state = step;
    candidate_.mechanism_y = step.y;
    candidate_.confirmed = cylinder_confirms(candidate_.state, candidate_.mechanism_y, candidate_.gap);
    if (candidate_.confirmed) candidate_.arbitrary_blocks = capped_arbitrary_blocks_;
    if (candidate_.confirmed) settle_on_mechanism();
    candidate_.dilatancy = dilatancy_work(m_, f_, candidate_.state, candidate_.mechanism_y) /
                           scale(multiplier_value(f_, candidate_.state.x));
    return candidate_.confirmed;
  }

  /// The fixed-point test of Gilbert, Casapulla & Ahmed (2006): with the shear of every point
  /// capped at mu N_k of `state` (a cylinder, no dilatancy), is `state` still optimal? Its forces
  /// satisfy the caps, so the capped problem's value is at least the state's; equal (within the
  /// scheme's tolerance) means the capped problem's mechanism, which cannot dilate, is compatible
  /// with the state: together they are a non-associative collapse state. The mechanism is then
  /// written into `mechanism_y` (rows of the associative formulation).
  bool cylinder_confirms(const conic::Solution& state, Eigen::VectorXd& mechanism_y, double& gap) {
    if (deadline_.left() <= 0.0) return false;
    const std::vector<double> normals = normal_forces(m_, f_, f_.point_forces(state.x));
    // A small floor keeps every cylinder with an interior. It is shear capacity that needs no
    // normal force, so it is relative to the load of the lighter block at the point: one floor for
    // the whole model would be more than a very light block's weight.
    std::vector<double> radii(normals.size());
    for (std::size_t p = 0; p < radii.size(); ++p) {
      radii[p] = std::max(1e-9 * f_.points[p].load, f_.points[p].friction * normals[p]);
    }
    const auto start = Clock::now();
    if (!cylinder_solver_) {
      FormulationOptions options = f_.options;
      options.friction_set = FrictionSet::Cylinder;
      cylinder_ = build_formulation(m_, options);
      result_.assemble_seconds += seconds_since(start);
      conic::ConicProblem problem = cylinder_.problem;
      problem.b = cylinder_.rhs_with_radii(radii);
      cylinder_solver_ = std::make_unique<conic::ConicSolver>(std::move(problem), solver_.settings());
    } else {
      cylinder_solver_->update_b(cylinder_.rhs_with_radii(radii));
    }
    conic::Settings& s = cylinder_solver_->settings();
    s = solver_.settings();
    s.snapshot_gap_rel = 0.0;
    s.time_limit_seconds = std::max(deadline_.left(), 1e-6);
    const auto solve_start = Clock::now();
    const conic::Solution capped = cylinder_solver_->solve();
    result_.solve_seconds += seconds_since(solve_start);
    iterations_.tests += capped.info.iterations;
    ++result_.non_associative_checks;
    if (!conic::has_solution(capped.info.status)) return false;
    const double v_state = multiplier_value(f_, state.x), v_capped = multiplier_value(cylinder_, capped.x);
    // Both values are exact only to the solves' gap (relative to max(1, |value|) in the problem's
    // units): a difference below ten times that is noise, however close to 0 the value is.
    const double noise = 10.0 * request_.tol_relative_gap *
                         (f_.settlement ? std::max(f_.force_scale, std::abs(v_state)) : std::max(1.0, std::abs(v_state)));
    const double slack = request_.non_associative_tolerance * scale(v_state) + noise;
    const bool confirmed = f_.settlement ? v_capped >= v_state - slack : v_capped <= v_state + slack;
    gap = (f_.settlement ? v_state - v_capped : v_capped - v_state) / scale(v_state);
    Eigen::VectorXd capped_y = capped.y;
    capped_arbitrary_blocks_ = settle_unloaded_blocks(m_, cylinder_, cylinder_.problem.c, capped_y).unsettled;
    // The block rows come first in both formulations (radius rows follow them in the capped one).
    capped_mechanism_ = Eigen::VectorXd::Zero(f_.problem.A.rows());
    capped_mechanism_.head(cylinder_.first_radius_row) = capped_y.head(cylinder_.first_radius_row);
    if (confirmed) mechanism_y = capped_mechanism_;
    return confirmed;
  }

  void report(double& value) {
    result_.non_associative_gap = candidate_.gap;
    if (result_.verdict == Verdict::TimeLimit || result_.verdict == Verdict::Cancelled) {
      // Nothing is reported; the run's record keeps the last completed step's value.
      if (last_step_.x.size() > 0) value = multiplier_value(f_, last_step_.x);
      return;
    }
    const Candidate& c = candidate_;
    value = multiplier_value(f_, c.state.x);
    if (result_.non_associative_converged) record_pointwise();
    conic::Solution other;
    if (result_.non_associative_converged && c.other_end) {
      result_.non_associative_range = std::make_pair(std::min(value, *c.other_end), std::max(value, *c.other_end));
    } else if (result_.non_associative_converged && c.selected && select(c.shift, c.face_optimum, -1.0, other)) {
      const double v_other = multiplier_value(f_, other.x);
      result_.non_associative_range = std::make_pair(std::min(value, v_other), std::max(value, v_other));
    } else if (result_.non_associative_converged) {
      result_.warnings.push_back({"non_associative_range_not_computed",
                                  "the range of non-associative states compatible with the mechanism could not be "
                                  "found; the value reported is one such state, not necessarily the most conservative",
                                  "/analysis/friction_model"});
    } else {
      result_.warnings.push_back(
          {"non_associative_not_converged",
           "the non-associative scheme stopped after " + count(result_.non_associative.size() - 1, "step", "steps") +
               " (" + result_.non_associative_stop + ") with a state whose mechanism still dilates (" +
               format(c.dilatancy, 3) +
               " of the value); the state satisfies the friction condition, so its value is never above the "
               "associative one, but it is not an exact non-associative collapse state",
           "/analysis/non_associative/max_iterations"});
    }
    // The candidate's forces with the mechanism of its step: both are optimal for that step's
    // problem, so they are complementary.
    conic::Solution state = c.state;
    state.y = c.mechanism_y;
    const std::vector<int> arbitrary =
        c.confirmed ? c.arbitrary_blocks
                    : settle_unloaded_blocks(m_, f_, shifted_cost(m_, f_, cost_, c.shift, 1.0), state.y).unsettled;
    result_.solver_info = c.state.info;
    result_.interior_point_history = c.state.info.history;
    result_.mechanism = Mechanism{};
    result_.mechanism_seconds = 0.0;
    read_solution(m_, f_, state, false, result_);
    result_.mechanism.arbitrary_blocks = arbitrary;
  }

  /// The state to report: the forces of `state` (the conservative end of the optimal face of the
  /// problem shifted by `shift`, whose optimum is `face_optimum`, or a step's own state) with the
  /// mechanism `mechanism_y` (the capped problem's when confirmed, else the step's). Once
  /// confirmed, the face is that of the mechanism's own slip rates (move_to_mechanism_face).
  struct Candidate {
    conic::Solution state;
    Eigen::VectorXd shift, mechanism_y;
    double face_optimum = 0.0;
    double dilatancy = 0.0;
    std::optional<double> other_end;  ///< the other end of the pointwise compatible states, when found
    std::optional<bool> pointwise;    ///< the pointwise check, when it ran and finished
    PatternViolation violation;       ///< when pointwise is false
    double gap = 0.0;                 ///< of its test (AnalysisResult::non_associative_gap)
    std::vector<int> arbitrary_blocks;  ///< of its test's mechanism, when confirmed
    bool selected = false;
    bool confirmed = false;
  };

  const model::Model& m_;
  const Formulation& f_;
  conic::ConicSolver& solver_;
  const Deadline& deadline_;
  const TestSchedule schedule_;
  AnalysisResult& result_;
  const model::AnalysisRequest& request_;
  const Eigen::VectorXd cost_;
  AndersonMixing mixing_;
  conic::Iterate snapshot_;
  std::vector<double> normals_;
  conic::Solution last_step_;
  Eigen::VectorXd last_shift_;
  Candidate candidate_;
  std::optional<Candidate> work_only_;  ///< a certified candidate that matched only in work (accept)
  int retry_until_ = 0;
  Formulation cylinder_;
  std::unique_ptr<conic::ConicSolver> cylinder_solver_;
  Eigen::VectorXd capped_mechanism_;  ///< of the last test, in the associative formulation's rows
  std::vector<int> capped_arbitrary_blocks_;  ///< of the last test (settle_unloaded_blocks)
  Iterations iterations_;
};

}  // namespace

namespace {

/// Whether run a's state is to be reported rather than run b's: certified beats uncertified, a
/// state that matches its mechanism point by point beats one that matches it in work only (the
/// latter's nearby states are not bounded by the tolerance: docs/method.md), then the
/// conservative value (the lower alpha, the higher R).
bool preferred(bool settlement, const NonAssociativeTrajectory& a, const NonAssociativeTrajectory& b) {
  if (a.converged != b.converged) return a.converged;
  if (!a.converged) return false;  // neither is a collapse state: keep the earlier run's
  const bool a_matches = a.pointwise == true, b_matches = b.pointwise == true;
  if (a_matches != b_matches) return a_matches;
  return settlement ? a.value > b.value : a.value < b.value;
}

bool stopped(const AnalysisResult& r) { return r.verdict == Verdict::TimeLimit || r.verdict == Verdict::Cancelled; }

/// A warning when the certified runs found states further apart than the test's tolerance.
void warn_about_spread(const model::Model& m, const Formulation& f, AnalysisResult& result) {
  double low = std::numeric_limits<double>::infinity(), high = -low;
  int certified = 0;
  for (const NonAssociativeTrajectory& t : result.non_associative_trajectories) {
    if (!t.converged) continue;
    ++certified;
    low = std::min(low, t.value);
    high = std::max(high, t.value);
  }
  const double reported = result.non_associative_trajectories[result.non_associative_reported].value;
  if (certified < 2 || high - low <= m.analysis.non_associative_tolerance * std::abs(reported)) return;
  const double unit = f.settlement ? m.units.force_to_kN : 1.0;
  const bool conservative = reported == (f.settlement ? high : low);
  const std::string which = conservative ? "the conservative one, " + format(reported / unit, 6) + ", is reported"
                                         : format(reported / unit, 6) +
                                               " is reported: it matches its mechanism point by point, the more "
                                               "conservative ones match theirs in work only";
  result.warnings.push_back(
      {"non_associative_states_differ",
       std::to_string(certified) + " runs of the non-associative scheme certified collapse states from " +
           format(low / unit, 6) + " to " + format(high / unit, 6) + " (" + format(100.0 * (high - low) / std::abs(reported), 3) +
           " % of the value apart); " + which +
           ". Non-associative collapse is not unique: a state outside this range may exist",
       "/analysis/non_associative/trajectories"});
}

/// The circumscribed pyramid's edges reach mu N / cos(pi/m): the scheme's states and its test
/// (a prism of the same shape) follow that friction law, so a certified state may carry more shear
/// than Coulomb's cone allows and be on the unsafe side of Coulomb's non-associative states. A
/// planar scene's cone has exactly two edges whatever the setting: nothing to warn about.
void warn_about_circumscribed_pyramid(const model::Model& m, AnalysisResult& result) {
  if (m.analysis.cone != model::ConeKind::PyramidCircumscribed || result.planar) return;
  const double reach = 1.0 / std::cos(model::kPi / m.analysis.pyramid_faces);
  result.warnings.push_back(
      {"non_associative_circumscribed_pyramid",
       "with the circumscribed pyramid a contact point may carry shear up to " + format(reach, 3) +
           " mu N: the non-associative state is one of that friction law, not of Coulomb's cone, and may be on "
           "the unsafe side of it; use cone exact, or pyramid_inscribed for the safe side",
       "/analysis/cone"});
}

}  // namespace

void run_non_associative(const model::Model& m, const Formulation& formulation, conic::ConicSolver& solver,
                         const conic::Solution& associative, const Deadline& deadline, double& value,
                         AnalysisResult& result) {
  const int runs = std::clamp(m.analysis.non_associative_trajectories, 1, kNumSchedules);
  result.non_associative_bound = value;
  const AnalysisResult before = result;
  std::vector<NonAssociativeTrajectory> found;
  double solve_seconds = 0.0, assemble_seconds = 0.0;
  for (int k = 0; k < runs; ++k) {
    AnalysisResult run = before;
    double run_value = value;
    NonAssociativeTrajectory t;
    {
      ShiftScheme scheme(m, formulation, solver, deadline, kSchedules[k], run);
      scheme.run(associative, run_value);
      t.step_iterations = scheme.iterations().steps;
      t.test_iterations = scheme.iterations().tests;
    }
    solve_seconds += run.solve_seconds - before.solve_seconds;
    assemble_seconds += run.assemble_seconds - before.assemble_seconds;
    t.schedule = kSchedules[k];
    t.value = run_value;
    t.converged = run.non_associative_converged;
    t.pointwise = run.non_associative_pointwise;
    t.steps = static_cast<int>(run.non_associative.size()) - 1;
    t.checks = run.non_associative_checks;
    t.seconds = run.solve_seconds - before.solve_seconds;
    // A run the clock stopped is reported only when no earlier one finished.
    if (stopped(run) && k > 0) {
      result.warnings.push_back({"non_associative_trajectories_incomplete",
                                 "the time limit ran out in run " + std::to_string(k + 1) + " of " +
                                     std::to_string(runs) + " of the non-associative scheme; the first " +
                                     std::to_string(k) + " are compared",
                                 "/analysis/non_associative/trajectories"});
      break;
    }
    found.push_back(t);
    if (k == 0 || preferred(formulation.settlement, t, found[result.non_associative_reported])) {
      result = std::move(run);
      result.non_associative_reported = k;
      value = run_value;
    }
    result.non_associative_trajectories = found;
    if (stopped(result)) break;
  }
  result.solve_seconds = before.solve_seconds + solve_seconds;
  result.assemble_seconds = before.assemble_seconds + assemble_seconds;
  warn_about_spread(m, formulation, result);
  warn_about_circumscribed_pyramid(m, result);
}

}  // namespace rbla::analysis
