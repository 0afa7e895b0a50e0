#pragma once
// The complementarity error of docs/performance.md Eq. (P1) from an independent product
// C p (the Toeplitz table, not the solver's own): for the tests and the fuzz targets, so
// it includes no test framework.

#include <fastnorm/influence.hpp>
#include <fastnorm/solution.hpp>

#include <algorithm>
#include <cmath>

namespace fastnorm::test {

/// max |g| where p > 0 and max(−g) where p = 0, g = h − δ + C p, relative to the deepest
/// interpenetration of the undeformed surfaces, δ − min h.
inline double complementarity_error(const fastnorm::InfluenceTable<>& table, const Eigen::VectorXd& h,
                                    const fastnorm::Solution<>& solution) {
  const Eigen::VectorXd gap = (h.array() - solution.approach).matrix() + table.displacement(solution.pressure);
  double error = 0;
  for (Eigen::Index k = 0; k < h.size(); ++k) {
    error = std::max(error, solution.pressure(k) > 0 ? std::abs(gap(k)) : -gap(k));
  }
  return error / (solution.approach - h.minCoeff());
}

}  // namespace fastnorm::test
