#pragma once
// The iterate of the homogeneous self-dual embedding (Ye, Todd & Mizuno 1994; conic form as in
// ECOS, Domahidi, Chu & Boyd 2013, and CVXOPT's conelp):
//   A x − b τ = 0,   −Aᵀy + c τ − z = 0,   bᵀy − cᵀx − κ = 0,   x, z ∈ K,  τ, κ ≥ 0,
// in the equilibrated variables (equilibration.hpp), and a search direction in the same shape.

#include "cone.hpp"

namespace rbla::conic::detail {

/// A Newton direction (dx, dy, dz, dτ, dκ).
struct Direction {
  Vec x, y, z;
  double tau = 0, kappa = 0;
  void swap(Direction& other);
};

struct Variables {
  Vec x, y, z;
  double tau = 1, kappa = 1;

  /// x = z = e (the cones' identity), y = 0, τ = κ = 1: the textbook start of the embedding.
  void set_identity(const Vec& e, Eigen::Index rows);
  /// Complementarity μ = (xᵀz + τκ)/(ν + 1), ν the degree of K.
  double mu(double degree) const;
  /// (x, y, z, τ, κ) += α d.
  void take_step(const Direction& d, double alpha);
  /// The embedding is homogeneous: scaling (x, y, z, τ, κ) by a positive factor changes no
  /// direction, step or normalised metric. On (nearly) infeasible problems the iterates can
  /// shrink together by many orders of magnitude, and then absolute floors (the refinement
  /// target) and underflow decide the outcome. Clarabel rescales by max(τ, κ) every iteration
  /// (DefaultVariables::rescale); here only when that leaves [1e-4, 1e4], so well-behaved
  /// solves keep their path. True when it rescaled.
  bool normalise();
};

}  // namespace rbla::conic::detail
