#include "io/problem_file.hpp"

#include "io/atomic_file.hpp"
#include "rbla/conic/io.hpp"

namespace rbla::io {

void write_problem_file(const std::string& path, const conic::ConicProblem& problem) {
  const bool mps = path.size() > 4 && path.compare(path.size() - 4, 4, ".mps") == 0;
  write_output(path, [&](std::ostream& out) {
    if (mps) conic::write_mps(problem, out);
    else conic::write_cbf(problem, out);
  });
}

}  // namespace rbla::io
