#pragma once
// The iteration log (Clarabel's info_print.rs layout): a banner with the problem summary, one
// fixed-width row per iteration mirroring IterationRow, and a footer with the verdict and
// timings per phase.

#include <ostream>

#include "normal_equations.hpp"
#include "rbla/conic/info.hpp"
#include "rbla/conic/problem.hpp"

namespace rbla::conic::detail {

void print_banner(std::ostream& out, const ConicProblem& p, const NormalEquations& normal,
                  const Info& info);
void print_row(std::ostream& out, const IterationRow& row);
/// solves, multiplies: counts over every NormalEquations the solve used.
void print_footer(std::ostream& out, const Info& info, long solves, long multiplies);

}  // namespace rbla::conic::detail
