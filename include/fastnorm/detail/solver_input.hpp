#pragma once
/// @file detail/solver_input.hpp
/// What every solver does before it starts: check the problem it was given, and guess the
/// approach that picks its starting set in force control.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "fastnorm/constants.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/solution.hpp"

namespace fastnorm {
namespace detail {

/// Rejects h of the wrong size or with NaN/Inf entries, and a force-control loading whose
/// Fn is not positive and finite.
/// @throws fastnorm::invalid_argument naming the argument
template <typename Scalar>
void check_problem(const Grid<Scalar>& grid, const Eigen::Ref<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>& h,
                   const Loading<Scalar>& loading) {
  FASTNORM_CHECK(h.size() == grid.size(),
                 detail::describe("undeformed_distance must have grid.size() = " + std::to_string(grid.size()) +
                                      " values",
                                  h.size()));
  // One vectorised pass; the element is looked for only when there is one to name.
  if (!h.allFinite()) {
    for (Eigen::Index k = 0; k < h.size(); ++k) {
      FASTNORM_CHECK(std::isfinite(h(k)),
                     detail::describe("undeformed_distance[" + std::to_string(k) + "] must be finite", h(k)));
    }
  }
  if (loading.control == Control::force) Loading<Scalar>::force(loading.normal_force);  // validates Fn
}

/// First guess of the approach δ in force control, used only to pick the starting set.
/// Hertz-like estimate: the overlap {h0 < δ} of area A gives F ≈ (4/3) E* a (δ − min h0)
/// with πa² ≈ A/2 (docs/norm.md Eq. (N3)). Returns δ; `sorted` is workspace.
template <typename Scalar>
Scalar approach_guess(const Eigen::Ref<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>& h0, Scalar element_area,
                      Scalar combined_modulus, Scalar normal_force, std::vector<Scalar>& sorted) {
  sorted.assign(h0.data(), h0.data() + h0.size());
  std::sort(sorted.begin(), sorted.end());
  // Force per unit of (δ − min h0) when `overlap_count` elements overlap.
  auto stiffness = [&](std::size_t overlap_count) {
    return Scalar(4) / 3 * combined_modulus *
           std::sqrt(static_cast<Scalar>(overlap_count) * element_area / (2 * pi<Scalar>));
  };
  for (std::size_t m = 1; m < sorted.size(); ++m) {
    if (stiffness(m) * (sorted[m] - sorted.front()) >= normal_force) {
      return sorted.front() + normal_force / stiffness(m);
    }
  }
  return sorted.front() + normal_force / stiffness(sorted.size());
}

}  // namespace detail
}  // namespace fastnorm
