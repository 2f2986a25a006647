#include "linear_solver.hpp"

namespace rbla::conic::detail {

CholmodSolver::CholmodSolver(Ordering ordering, int n, const int* col_ptr, const int* row_ind)
    : cholesky_(ordering) {
  cholesky_.analyze(n, col_ptr, row_ind);
}

bool CholmodSolver::factorize(const double* values, double shift) {
  return cholesky_.factorize(values, shift);
}

void CholmodSolver::solve(double* x, int columns) { cholesky_.solve(x, columns); }

std::unique_ptr<SplitDomainSolver> SplitDomainSolver::create(Ordering ordering,
                                                             ForkJoin& fork_join, int n,
                                                             const int* col_ptr,
                                                             const int* row_ind) {
  std::unique_ptr<SplitDomainSolver> solver(new SplitDomainSolver(ordering, fork_join));
  if (!solver->split_.analyze(n, col_ptr, row_ind)) return nullptr;
  for (auto& share : solver->shares_)
    share.assign(static_cast<std::size_t>(solver->split_.num_separator_slots()), 0.0);
  return solver;
}

bool SplitDomainSolver::factorize(const double* values, double shift) {
  return split_.factorize(values, shares_[0].data(), shares_[1].data(), shift);
}

// In place: SplitCholesky::solve reads all of rhs before it writes.
void SplitDomainSolver::solve(double* x, int columns) { split_.solve(x, columns, x); }

std::unique_ptr<LinearSolver> make_linear_solver(Ordering ordering, ForkJoin* fork_join, int n,
                                                 const int* col_ptr, const int* row_ind) {
  if (fork_join) {
    if (auto split = SplitDomainSolver::create(ordering, *fork_join, n, col_ptr, row_ind))
      return split;
  }
  return std::make_unique<CholmodSolver>(ordering, n, col_ptr, row_ind);
}

}  // namespace rbla::conic::detail
