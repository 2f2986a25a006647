#pragma once
// Exact problem dumps for bug reports and cross-checks with other solvers.

#include <iosfwd>
#include <limits>
#include <string>

#include "rbla/conic/problem.hpp"

namespace rbla::conic {

/// Conic Benchmark Format, version 3 (https://cblib.zib.de): OBJSENSE MIN, VAR with L+ and Q
/// cones, CON with one L= block. CBF constraints read A x + b ∈ K, so −b is written.
/// Numbers are written with 17 significant digits (round-trips doubles exactly).
void write_cbf(const ConicProblem& problem, std::ostream& out);
void write_cbf(const ConicProblem& problem, const std::string& path);
/// Sizes read_cbf accepts: a file declaring more is refused before anything is allocated for it.
/// The defaults are what Eigen's sparse matrices (int indices) can hold.
struct CbfLimits {
  long long max_variables = std::numeric_limits<int>::max() - 1;
  long long max_constraints = std::numeric_limits<int>::max() - 1;
  long long max_nonzeros = std::numeric_limits<int>::max() - 1;  ///< ACOORD entries, and each of OBJACOORD, BCOORD
};

/// Reads the CBF subset that write_cbf produces: OBJSENSE MIN or MAX (MAX negates c), VAR with
/// at most one leading L+ then Q cones, CON with L= cones only, OBJACOORD, ACOORD, BCOORD, and
/// OBJBCOORD only if 0; VAR and CON before the coordinates, as CBF requires. Anything else, a
/// malformed or out-of-range number, or a size over `limits` throws ConicSetupError naming the
/// line.
ConicProblem read_cbf(std::istream& in, const CbfLimits& limits = {});
ConicProblem read_cbf_file(const std::string& path);

/// Free-format MPS for problems without second-order cones (throws ConicSetupError if any):
/// rows R0..R{m-1} are E rows, columns X0..X{n-1} with default bounds [0, +inf).
void write_mps(const ConicProblem& problem, std::ostream& out);
void write_mps(const ConicProblem& problem, const std::string& path);

}  // namespace rbla::conic
