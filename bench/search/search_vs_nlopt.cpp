// How many evaluations of alpha(theta) each search needs before its best value is within 1e-3 of
// the true minimum, on radial functions of convex sets whose minimum is known: an ellipse (one
// smooth minimum pair), an off-centre rectangle (four local minima, kinks), and random convex
// polygons. alpha(theta) is a whole analysis in rbla, so evaluations are the cost.
//
// NLopt's global algorithms (DIRECT-L, CRS2, ISRES) are given 200 evaluations; they cannot tell
// when they have the minimum, so the count reported is the first evaluation within 1e-3 of it,
// found with knowledge of the answer they do not have. rbla's search stops by itself when its
// certified bracket is within 1e-3, and is run without the mechanism's supporting lines (chords
// only) and with them.
#include "analysis/radial_search.hpp"

#include <nlopt.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();
using rbla::analysis::RadialSample;

/// A convex polygon { x : n_i . x <= h_i } around the origin, with its supporting lines.
struct Polygon {
  std::vector<std::pair<double, double>> normal_angle_and_distance;
  RadialSample operator()(double t) const {
    RadialSample s;
    s.angle = t;
    s.radius = kInf;
    for (const auto& [angle, h] : normal_angle_and_distance) {
      const double c = std::cos(t - angle);
      if (c > 0.0 && h / c < s.radius) {
        s.radius = h / c;
        s.bound_angle = angle;
        s.bound_radius = h;
      }
    }
    return s;
  }
  double smallest() const {
    double m = kInf;
    for (const auto& [angle, h] : normal_angle_and_distance) m = std::min(m, h);
    return m;
  }
};

struct Case {
  std::string name;
  std::function<RadialSample(double)> f;
  double minimum;
};

/// Evaluations until the best value is within 1e-3 of the minimum (or -1 within the budget).
struct Counter {
  const Case* c;
  int evaluations = 0, first_within = -1;
  double value(double t) {
    const double r = c->f(t).radius;
    ++evaluations;
    if (first_within < 0 && r <= c->minimum * (1.0 + 1e-3)) first_within = evaluations;
    return r;
  }
};

double nlopt_objective(unsigned, const double* x, double*, void* data) {
  return static_cast<Counter*>(data)->value(x[0]);
}

int run_nlopt(const Case& c, nlopt_algorithm algorithm) {
  Counter counter{&c};
  nlopt_opt opt = nlopt_create(algorithm, 1);
  const double lo = 0.0, hi = 2.0 * kPi;
  nlopt_set_lower_bounds(opt, &lo);
  nlopt_set_upper_bounds(opt, &hi);
  nlopt_set_min_objective(opt, nlopt_objective, &counter);
  nlopt_set_maxeval(opt, 200);
  nlopt_srand(7);
  double x = 1.0, f = 0.0;
  nlopt_optimize(opt, &x, &f);
  nlopt_destroy(opt);
  return counter.first_within;
}

struct Ours {
  int first_within = -1;  ///< evaluations until the best is within 1e-3 (as for NLopt)
  int evaluations = 0;    ///< until the search stopped
  bool certified = false;
};

Ours run_ours(const Case& c, bool supporting_lines) {
  rbla::analysis::RadialSearchSettings settings;
  settings.max_samples = 200;
  Counter counter{&c};
  const auto result = rbla::analysis::minimise_radius([&](double t) {
    RadialSample s = c.f(t);
    counter.value(t);
    if (!supporting_lines) {
      s.bound_angle.reset();
      s.bound_radius.reset();
    }
    return s;
  }, settings);
  return {counter.first_within, static_cast<int>(result.samples.size()), result.converged};
}

std::vector<Case> cases() {
  std::vector<Case> all;
  for (double turn : {0.3, 1.1}) {
    all.push_back({"ellipse 2 x 0.5, turned " + std::to_string(turn).substr(0, 3), [turn](double t) {
                     const double c = std::cos(t - turn), s = std::sin(t - turn);
                     RadialSample r;
                     r.angle = t;
                     r.radius = 1.0 / std::sqrt(c * c / 4.0 + s * s / 0.25);
                     return r;
                   }, 0.5});
  }
  const Polygon rectangle{{{0.3, 1.0}, {0.3 + 0.5 * kPi, 0.7}, {0.3 + kPi, 0.4}, {0.3 + 1.5 * kPi, 0.6}}};
  all.push_back({"off-centre rectangle (4 local minima)", rectangle, 0.4});
  // Nearly round, as a dome: 24 faces at distances 1 +- 1 %, and an ellipse 1 x 0.98.
  Polygon round;
  for (int i = 0; i < 24; ++i) round.normal_angle_and_distance.push_back({2.0 * kPi * (i + 0.1) / 24, 1.0 + 0.01 * std::sin(7.0 * i)});
  all.push_back({"24 faces, 1 +- 1 % (dome-like)", round, round.smallest()});
  all.push_back({"ellipse 1 x 0.98", [](double t) {
                   const double c = std::cos(t - 0.2), s = std::sin(t - 0.2);
                   RadialSample r;
                   r.angle = t;
                   r.radius = 1.0 / std::sqrt(c * c + s * s / (0.98 * 0.98));
                   return r;
                 }, 0.98});
  unsigned state = 12345u;
  auto uniform = [&state]() {
    state = state * 1664525u + 1013904223u;
    return (state >> 8) / 16777216.0;
  };
  for (int trial = 0; trial < 20; ++trial) {
    Polygon p;
    const int sides = 3 + static_cast<int>(uniform() * 9);
    for (int i = 0; i < sides; ++i) p.normal_angle_and_distance.push_back({2.0 * kPi * (i + 0.8 * uniform()) / sides, 0.2 + uniform()});
    all.push_back({"random polygon " + std::to_string(trial), p, p.smallest()});
  }
  return all;
}

}  // namespace

int main() {
  const std::vector<std::pair<const char*, nlopt_algorithm>> nlopt_algorithms = {
      {"DIRECT-L", NLOPT_GN_DIRECT_L}, {"CRS2", NLOPT_GN_CRS2_LM}, {"ISRES", NLOPT_GN_ISRES}};
  std::printf("Evaluations until the best value is within 1e-3 of the minimum; for rbla also when its "
              "certified bracket let it stop.\n\n");
  std::printf("| case | rbla, chords | rbla, with mechanisms | DIRECT-L | CRS2 | ISRES |\n|---|---|---|---|---|---|\n");
  std::vector<double> sums(5, 0.0), stops(2, 0.0);
  int misses[5] = {0, 0, 0, 0, 0};
  const auto all = cases();
  for (const Case& c : all) {
    const Ours ours[2] = {run_ours(c, false), run_ours(c, true)};
    std::vector<int> counts = {ours[0].first_within, ours[1].first_within};
    for (const auto& [name, algorithm] : nlopt_algorithms) counts.push_back(run_nlopt(c, algorithm));
    std::printf("| %s |", c.name.c_str());
    for (std::size_t k = 0; k < counts.size(); ++k) {
      if (counts[k] < 0) {
        std::printf(" not within 200 |");
        ++misses[k];
        continue;
      }
      sums[k] += counts[k];
      if (k < 2) {
        stops[k] += ours[k].evaluations;
        std::printf(" %d, stops at %d%s |", counts[k], ours[k].evaluations, ours[k].certified ? "" : " (not certified)");
      } else {
        std::printf(" %d |", counts[k]);
      }
    }
    std::printf("\n");
  }
  const int n = static_cast<int>(all.size());
  std::printf("| mean |");
  for (int k = 0; k < 5; ++k) {
    std::printf(" %.1f", sums[k] / std::max(1, n - misses[k]));
    if (k < 2) std::printf(", stops at %.1f", stops[k] / std::max(1, n - misses[k]));
    std::printf("%s |", misses[k] ? (" (" + std::to_string(misses[k]) + " missed)").c_str() : "");
  }
  std::printf("\n");
  return 0;
}
