#pragma once
/// @file batch.hpp
/// Independent problems on one grid solved in parallel (e.g. the patches of a lookup
/// table): OpenMP threads when compiled with OpenMP (link the CMake target fastnorm::openmp
/// instead of fastnorm::fastnorm; it also defines EIGEN_DONT_PARALLELIZE, so Eigen's own
/// products stay on one thread), one after the other otherwise. Each
/// problem is a cold `solve`, so the answers are the same either way and in any order.

#include <Eigen/Core>
#include <exception>
#include <vector>

#include "fastnorm/error.hpp"
#include "fastnorm/solution.hpp"

namespace fastnorm {

/// Whether solve_batch runs in parallel: compiled with OpenMP.
inline bool batch_is_parallel() {
#ifdef _OPENMP
  return true;
#else
  return false;
#endif
}

/// Solves problem n, (undeformed_distances[n], loadings[n]), for every n with `solver.solve`
/// — any solver of fastnorm (its const solve is safe to call from several threads).
/// @param loadings one per problem, or a single loading for all
/// @throws fastnorm::invalid_argument for mismatched counts; otherwise what the solver throws
///         for the first bad problem (lowest n), after all others have finished
template <typename Solver, typename Vector = typename Solver::Vector>
std::vector<Solution<typename Vector::Scalar>> solve_batch(
    const Solver& solver, const std::vector<Vector>& undeformed_distances,
    const std::vector<Loading<typename Vector::Scalar>>& loadings) {
  const std::size_t count = undeformed_distances.size();
  FASTNORM_CHECK(loadings.size() == count || loadings.size() == 1,
                 detail::describe("solve_batch: loadings must have one entry per problem (" +
                                      std::to_string(count) + ") or a single entry",
                                  loadings.size()));
  std::vector<Solution<typename Vector::Scalar>> solutions(count);
  std::vector<std::exception_ptr> failures(count);
  const long long problems = static_cast<long long>(count);
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic)
#endif
  for (long long n = 0; n < problems; ++n) {
    const std::size_t at = static_cast<std::size_t>(n);
    try {
      solutions[at] = solver.solve(undeformed_distances[at], loadings.size() == 1 ? loadings[0] : loadings[at]);
    } catch (...) {
      failures[at] = std::current_exception();
    }
  }
  for (const auto& failure : failures) {
    if (failure) std::rethrow_exception(failure);
  }
  return solutions;
}

}  // namespace fastnorm
