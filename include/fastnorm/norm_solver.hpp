#pragma once
/// @file norm_solver.hpp
/// Kalker's NORM: the active-set solver for the normal contact problem, approach and
/// force control, with a dense Cholesky factorisation of the active block. This is the
/// reference path every faster solver is tested against (docs/design.md §3, docs/norm.md).

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "fastnorm/error.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/influence.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/solution.hpp"

namespace fastnorm {

/// Settings of the active-set loop.
template <typename Scalar = double>
struct NormOptions {
  /// Most linear solves before giving up with Status::iteration_limit.
  int max_iterations = 200;
  /// An element outside the set joins when its deformed gap is below
  /// −gap_tolerance · max|h| (relative; keeps round-off from cycling an element
  /// whose true gap is 0 in and out; docs/norm.md §2).
  Scalar gap_tolerance = 1000 * std::numeric_limits<Scalar>::epsilon();
  /// The starting set is {h − δ₀ < start_depth_fraction · min(h − δ₀)}, δ₀ = 0 in approach
  /// control and a Hertz-like guess in force control. 1 is Kalker's original start, all
  /// interpenetrating elements; the default 0.5 is the Hertz contact area, which needs
  /// fewer and smaller factorisations (docs/norm.md §2). The solution does not depend on it.
  Scalar start_depth_fraction = Scalar(0.5);

  /// @throws fastnorm::invalid_argument naming the offending field
  void validate() const {
    FASTNORM_CHECK(max_iterations >= 1,
                   detail::describe("NormOptions: max_iterations must be >= 1", max_iterations));
    FASTNORM_CHECK(std::isfinite(gap_tolerance) && gap_tolerance >= 0,
                   detail::describe("NormOptions: gap_tolerance must be finite and >= 0",
                                    gap_tolerance));
    FASTNORM_CHECK(start_depth_fraction > 0 && start_depth_fraction <= 1,
                   detail::describe("NormOptions: start_depth_fraction must lie in (0, 1]",
                                    start_depth_fraction));
  }
};

namespace detail {

/// Rejects h of the wrong size or with NaN/Inf entries.
template <typename Scalar>
void check_undeformed_distance(const Grid<Scalar>& grid,
                               const Eigen::Ref<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>& h) {
  FASTNORM_CHECK(h.size() == grid.size(),
                 detail::describe("undeformed_distance must have grid.size() = " +
                                      std::to_string(grid.size()) + " values",
                                  h.size()));
  for (Eigen::Index k = 0; k < h.size(); ++k) {
    FASTNORM_CHECK(std::isfinite(h(k)), detail::describe("undeformed_distance[" + std::to_string(k) +
                                                             "] must be finite",
                                                         h(k)));
  }
}

/// First guess of the approach δ in force control, used only to pick the starting set.
/// Hertz-like estimate: the overlap {h0 < δ} of area A gives F ≈ (4/3) E* a (δ − min h0)
/// with πa² ≈ A/2 (docs/norm.md Eq. (N3)). Returns δ.
template <typename Scalar>
Scalar approach_guess(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& h0, Scalar element_area,
                      Scalar combined_modulus, Scalar normal_force) {
  std::vector<Scalar> sorted(h0.data(), h0.data() + h0.size());
  std::sort(sorted.begin(), sorted.end());
  const Scalar pi = Scalar(3.14159265358979323846L);
  auto estimated_force = [&](std::size_t overlap_count, Scalar approach) {
    const Scalar radius = std::sqrt(static_cast<Scalar>(overlap_count) * element_area / (2 * pi));
    return Scalar(4) / 3 * combined_modulus * radius * (approach - sorted.front());
  };
  for (std::size_t m = 1; m < sorted.size(); ++m) {
    if (estimated_force(m, sorted[m]) >= normal_force) {
      // Within [sorted[m-1], sorted[m]] the estimate is linear in δ for fixed m.
      const Scalar slope = estimated_force(m, sorted.front() + 1);
      return sorted.front() + normal_force / slope;
    }
  }
  return sorted.front() + normal_force / estimated_force(sorted.size(), sorted.front() + 1);
}

}  // namespace detail

/// Kalker's active-set NORM solver on a fixed grid and material.
///
/// Keeps the influence table, so many problems on the same grid share it.
///
/// **Example**
/// @code
/// fastnorm::Grid<> grid(40, 40, 2.5e-4, 2.5e-4, -4.875e-3, -4.875e-3);
/// fastnorm::NormSolver<> solver(grid, fastnorm::Material<>(2.1e11, 0.3));
/// Eigen::VectorXd h(grid.size());   // undeformed distance (m), + = gap
/// // ... fill h ...
/// auto solution = solver.solve(h, fastnorm::Loading<>::force(5e4));
/// if (solution.status == fastnorm::Status::converged) use(solution.pressure);
/// @endcode
template <typename Scalar = double>
class NormSolver {
 public:
  using Index = Eigen::Index;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Options = NormOptions<Scalar>;

  /// @throws fastnorm::invalid_argument for invalid options
  NormSolver(const Grid<Scalar>& grid, const Material<Scalar>& material, Options options = {})
      : influence_(grid, material), options_(options) {
    options_.validate();
  }

  const Grid<Scalar>& grid() const { return influence_.grid(); }
  const InfluenceTable<Scalar>& influence() const { return influence_; }
  const Options& options() const { return options_; }

  /// Solves the Signorini problem g = h − δ + C p ≥ 0, p ≥ 0, g·p = 0.
  /// @param undeformed_distance h on every element (m, + = gap), grid.size() values
  /// @param loading approach control (δ = 0) or force control (δ found from Fn)
  /// @throws fastnorm::invalid_argument for wrong sizes or non-finite h
  Solution<Scalar> solve(const Eigen::Ref<const Vector>& undeformed_distance,
                         const Loading<Scalar>& loading) const {
    detail::check_undeformed_distance(grid(), undeformed_distance);
    const bool force_control = loading.control == Control::force;
    if (force_control) Loading<Scalar>::force(loading.normal_force);  // validates Fn

    const Vector h = undeformed_distance;
    const Index n_all = grid().size();
    const Scalar area = grid().element_area();
    const Scalar join_below = -options_.gap_tolerance * h.cwiseAbs().maxCoeff();

    Solution<Scalar> solution;
    solution.pressure = Vector::Zero(n_all);
    solution.in_contact = Solution<Scalar>::Mask::Constant(n_all, false);

    // Step 1: the starting set (docs/norm.md §2).
    const Scalar deepest = h.minCoeff();
    Scalar approach = 0;
    if (force_control) {
      approach = detail::approach_guess(h, area, influence_.combined_modulus(), loading.normal_force);
    } else if (deepest >= 0) {
      solution.status = Status::no_contact;
      solution.message = "no element has a negative undeformed distance";
      return solution;
    }
    const Scalar start_below = approach + options_.start_depth_fraction * (deepest - approach);
    std::vector<Index> active;
    for (Index k = 0; k < n_all; ++k) {
      if (h(k) <= start_below) active.push_back(k);
    }

    Vector pressure;
    std::vector<Index> outside;
    while (solution.iterations < options_.max_iterations) {
      ++solution.iterations;
      // Step 2: solve C_II p_I = −(h_I − δ) on the current set.
      Matrix block = influence_.dense_block(active);
      Eigen::LLT<Eigen::Ref<Matrix>> cholesky(block);
      if (cholesky.info() != Eigen::Success) {
        solution.status = Status::numerical_issue;
        solution.message = "Cholesky factorisation of the active block failed";
        return solution;
      }
      const Index n = static_cast<Index>(active.size());
      Vector minus_h(n);
      for (Index r = 0; r < n; ++r) minus_h(r) = -h(active[static_cast<std::size_t>(r)]);
      if (force_control) {
        // p = p_a + δ p_b with C p_a = −h0, C p_b = 1; δ from dx·dy·Σp = Fn (design §3).
        Matrix rhs(n, 2);
        rhs.col(0) = minus_h;
        rhs.col(1).setOnes();
        const Matrix parts = cholesky.solve(rhs);
        approach = (loading.normal_force / area - parts.col(0).sum()) / parts.col(1).sum();
        pressure = parts.col(0) + approach * parts.col(1);
      } else {
        pressure = cholesky.solve(minus_h);
      }

      // Step 3: elements with negative pressure leave.
      std::vector<Index> kept;
      for (Index r = 0; r < n; ++r) {
        if (pressure(r) >= 0) kept.push_back(active[static_cast<std::size_t>(r)]);
      }
      if (static_cast<Index>(kept.size()) < n) {
        active.swap(kept);
        continue;
      }

      // Step 4: elements outside with negative deformed gap join.
      outside.clear();
      std::vector<bool> is_active(static_cast<std::size_t>(n_all), false);
      for (Index k : active) is_active[static_cast<std::size_t>(k)] = true;
      for (Index k = 0; k < n_all; ++k) {
        if (!is_active[static_cast<std::size_t>(k)]) outside.push_back(k);
      }
      const Vector gap = influence_.displacement(outside, active, pressure);
      std::vector<Index> joining;
      for (std::size_t t = 0; t < outside.size(); ++t) {
        if (h(outside[t]) - approach + gap(static_cast<Index>(t)) < join_below) {
          joining.push_back(outside[t]);
        }
      }
      if (joining.empty()) {
        store(active, pressure, approach, solution);
        solution.status = Status::converged;
        solution.message = "contact set stable";
        return solution;
      }
      active.insert(active.end(), joining.begin(), joining.end());
      std::sort(active.begin(), active.end());
    }
    // The last iterate, its negative pressures clipped, so the caller can inspect it.
    pressure = pressure.cwiseMax(Scalar(0));
    store(active, pressure, approach, solution);
    solution.status = Status::iteration_limit;
    solution.message = "active set still changing after " + std::to_string(solution.iterations) +
                       " iterations";
    return solution;
  }

 private:
  /// Scatters the pressures of the set into the solution; fills force and approach.
  void store(const std::vector<Index>& active, const Vector& pressure, Scalar approach,
             Solution<Scalar>& solution) const {
    for (std::size_t r = 0; r < active.size(); ++r) {
      const Scalar value = pressure(static_cast<Index>(r));
      solution.pressure(active[r]) = value;
      solution.in_contact(active[r]) = value > 0;
    }
    solution.approach = approach;
    solution.normal_force = grid().element_area() * solution.pressure.sum();
  }

  InfluenceTable<Scalar> influence_;
  Options options_;
};

}  // namespace fastnorm
