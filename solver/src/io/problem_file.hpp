// The conic problem of an analysis written for other solvers (`rbla solve --dump-problem`).
#pragma once

#include "rbla/conic/problem.hpp"

#include <string>

namespace rbla::io {

/// Writes `problem` to `path` by the rules of io/atomic_file.hpp: free MPS when the name ends in
/// ".mps" (linear programs only; conic::ConicSetupError otherwise), else CBF (rbla/conic/io.hpp).
void write_problem_file(const std::string& path, const conic::ConicProblem& problem);
/// Throws what write_problem_file would for a problem that `path`'s format cannot express (a
/// conic problem as MPS), before anything is written.
void check_problem_file(const std::string& path, const conic::ConicProblem& problem);

}  // namespace rbla::io
