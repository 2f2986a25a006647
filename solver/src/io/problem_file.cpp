#include "io/problem_file.hpp"

#include "io/atomic_file.hpp"
#include "rbla/conic/io.hpp"

namespace rbla::io {

namespace {
bool is_mps(const std::string& path) {
  return path.size() > 4 && path.compare(path.size() - 4, 4, ".mps") == 0;
}
}  // namespace

void check_problem_file(const std::string& path, const conic::ConicProblem& problem) {
  if (is_mps(path) && !problem.cones.soc_dims.empty())
    throw conic::ConicSetupError("write_mps: MPS cannot express second-order cones");
}

void write_problem_file(const std::string& path, const conic::ConicProblem& problem) {
  const bool mps = is_mps(path);
  write_output(path, [&](std::ostream& out) {
    if (mps) conic::write_mps(problem, out);
    else conic::write_cbf(problem, out);
  });
}

}  // namespace rbla::io
