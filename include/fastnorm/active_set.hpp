#pragma once
/// @file active_set.hpp
/// The active-set loop shared by every solver (docs/norm.md §1): NORM solves each set
/// exactly, the reduced solvers in a small basis; the loop around them is this one.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "fastnorm/error.hpp"
#include "fastnorm/influence.hpp"
#include "fastnorm/scratch_matrix.hpp"
#include "fastnorm/solution.hpp"

namespace fastnorm {

/// Settings of the active-set loop, shared by all solvers.
template <typename Scalar = double>
struct ActiveSetOptions {
  /// Most linear solves before giving up with Status::iteration_limit.
  int max_iterations = 200;
  /// An element outside the set joins when its deformed gap is below
  /// −gap_tolerance · max|h| (relative; keeps round-off from cycling an element
  /// whose true gap is 0 in and out; docs/norm.md §2).
  Scalar gap_tolerance = 1000 * std::numeric_limits<Scalar>::epsilon();
  /// The starting set is {h − δ₀ ≤ start_depth_fraction · min(h − δ₀)}, δ₀ = 0 in approach
  /// control and a Hertz-like guess in force control. 1 is Kalker's original start, all
  /// interpenetrating elements; the default 0.5 is the Hertz contact area, which needs
  /// fewer and smaller factorisations (docs/norm.md §2). NORM's answer does not depend on it.
  Scalar start_depth_fraction = Scalar(0.5);

  /// @throws fastnorm::invalid_argument naming the offending field
  void validate() const {
    FASTNORM_CHECK(max_iterations >= 1,
                   detail::describe("options: max_iterations must be >= 1", max_iterations));
    FASTNORM_CHECK(std::isfinite(gap_tolerance) && gap_tolerance >= 0,
                   detail::describe("options: gap_tolerance must be finite and >= 0", gap_tolerance));
    FASTNORM_CHECK(start_depth_fraction > 0 && start_depth_fraction <= 1,
                   detail::describe("options: start_depth_fraction must lie in (0, 1]",
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
/// with πa² ≈ A/2 (docs/norm.md Eq. (N3)). Returns δ; `sorted` is workspace.
template <typename Scalar>
Scalar approach_guess(const Eigen::Ref<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>& h0, Scalar element_area,
                      Scalar combined_modulus, Scalar normal_force, std::vector<Scalar>& sorted) {
  sorted.assign(h0.data(), h0.data() + h0.size());
  std::sort(sorted.begin(), sorted.end());
  const Scalar pi = Scalar(3.14159265358979323846L);
  // Force per unit of (δ − min h0) when `overlap_count` elements overlap.
  auto stiffness = [&](std::size_t overlap_count) {
    return Scalar(4) / 3 * combined_modulus *
           std::sqrt(static_cast<Scalar>(overlap_count) * element_area / (2 * pi));
  };
  for (std::size_t m = 1; m < sorted.size(); ++m) {
    if (stiffness(m) * (sorted[m] - sorted.front()) >= normal_force) {
      return sorted.front() + normal_force / stiffness(m);
    }
  }
  return sorted.front() + normal_force / stiffness(sorted.size());
}

/// As above, with its own workspace.
template <typename Scalar>
Scalar approach_guess(const Eigen::Ref<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>& h0, Scalar element_area,
                      Scalar combined_modulus, Scalar normal_force) {
  std::vector<Scalar> sorted;
  return approach_guess(h0, element_area, combined_modulus, normal_force, sorted);
}

/// The sorted element numbers in contact, into `set`: the warm start of the next problem of
/// a sequence (empty, i.e. a cold start, unless the solution is usable).
template <typename Scalar>
void contact_set(const Solution<Scalar>& solution, std::vector<Eigen::Index>& set) {
  set.clear();
  if (!solution.ok()) return;
  for (Eigen::Index k = 0; k < solution.in_contact.size(); ++k) {
    if (solution.in_contact(k)) set.push_back(k);
  }
}

/// Everything the active-set loop touches between iterations. Kept by a solver across the
/// problems of a sequence, it stops allocating once it has grown to the largest set met:
/// the loop itself allocates nothing then (docs/performance.md §3).
template <typename Scalar>
struct ActiveSetWorkspace {
  using Index = Eigen::Index;
  std::vector<Index> active, kept, candidates, joining, admissible_set;
  std::vector<Index> visited_elements;   // every set of this solve, one after the other
  std::vector<std::size_t> visited_ends;  // where each ends in visited_elements
  ScratchMatrix<Scalar> columns;          // right-hand sides in, pressures out (n × 1 or n × 2)
  ScratchMatrix<Scalar> displacement;     // at the candidates
  std::vector<Scalar> admissible_pressure;
  std::vector<Scalar> sorted_distance;    // of the force-control starting guess
  std::vector<char> is_active;            // per element of the grid

  /// True if `set` came up before in this solve; records it otherwise.
  bool seen_before(const std::vector<Index>& set) {
    std::size_t begin = 0;
    for (const std::size_t end : visited_ends) {
      if (end - begin == set.size() &&
          std::equal(set.begin(), set.end(), visited_elements.begin() + static_cast<std::ptrdiff_t>(begin))) {
        return true;
      }
      begin = end;
    }
    visited_elements.insert(visited_elements.end(), set.begin(), set.end());
    visited_ends.push_back(visited_elements.size());
    return false;
  }
};

/// The active-set loop of docs/norm.md §1 around a solver of the problem restricted to a
/// set. `set_solver.solve(active, columns)` receives the sorted element numbers of the set
/// and, in `columns`, right-hand sides over it (n × 1: −h_I; n × 2 in force control: −h0_I
/// and 1), which it overwrites with the pressures on the set for each column; it returns
/// false if its factorisation failed. `set_solver.displacement(targets, active, p, u)` then
/// writes u = C_TI p for pressures p on that set (the join check of step 4; a solver may
/// use what it knows of p, e.g. that it lies in its basis).
///
/// `start_set` (sorted element numbers) replaces the starting set of step 1 when not empty:
/// a warm start from the previous contact set of a sequence of problems.
///
/// Cycles are ended deterministically: when a set comes back, the loop stops with
/// Status::cycled and the last set whose pressures were all positive. (A cycle contains a
/// join, and joins follow only such a set, so one exists; docs/method.md §3.)
template <typename Scalar, typename SetSolver>
Solution<Scalar> solve_active_set(const InfluenceTable<Scalar>& influence,
                                  const Eigen::Ref<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>& h,
                                  const Loading<Scalar>& loading, const ActiveSetOptions<Scalar>& options,
                                  SetSolver& set_solver, ActiveSetWorkspace<Scalar>& work,
                                  const std::vector<Eigen::Index>& start_set = {}) {
  using Index = Eigen::Index;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  const Grid<Scalar>& grid = influence.grid();
  check_undeformed_distance(grid, h);
  const bool force_control = loading.control == Control::force;
  if (force_control) Loading<Scalar>::force(loading.normal_force);  // validates Fn

  const Index n_all = grid.size();
  const Scalar area = grid.element_area();
  const Scalar join_below = -options.gap_tolerance * h.cwiseAbs().maxCoeff();

  Solution<Scalar> solution;
  solution.pressure = Vector::Zero(n_all);
  solution.in_contact = Solution<Scalar>::Mask::Constant(n_all, false);

  // Step 1: the starting set (docs/norm.md §2).
  const Scalar deepest = h.minCoeff();
  Scalar approach = 0;
  if (force_control) {
    approach = approach_guess(h, area, influence.combined_modulus(), loading.normal_force, work.sorted_distance);
  } else if (deepest >= 0) {
    solution.status = Status::no_contact;
    solution.message = "no element has a negative undeformed distance";
    return solution;
  }
  const Scalar start_below = approach + options.start_depth_fraction * (deepest - approach);
  std::vector<Index>& active = work.active;
  active = start_set;
  if (active.empty()) {
    for (Index k = 0; k < n_all; ++k) {
      if (h(k) <= start_below) active.push_back(k);
    }
  }

  auto store = [&](const std::vector<Index>& set, const Scalar* pressure, Scalar delta) {
    solution.pressure.setZero();
    solution.in_contact.setConstant(false);
    for (std::size_t r = 0; r < set.size(); ++r) {
      const Scalar value = std::max(pressure[r], Scalar(0));
      solution.pressure(set[r]) = value;
      solution.in_contact(set[r]) = value > 0;
    }
    solution.approach = delta;
    solution.normal_force = area * solution.pressure.sum();
  };

  work.visited_elements.clear();
  work.visited_ends.clear();
  work.admissible_set.clear();  // last set with all pressures positive
  Scalar admissible_approach = 0;
  work.is_active.assign(static_cast<std::size_t>(n_all), 0);
  const Index column_count = force_control ? 2 : 1;
  while (solution.iterations < options.max_iterations) {
    if (work.seen_before(active)) {
      FASTNORM_ASSERT(!work.admissible_set.empty());
      store(work.admissible_set, work.admissible_pressure.data(), admissible_approach);
      solution.status = Status::cycled;
      solution.message = "active set cycled; returned the last set with positive pressures";
      return solution;
    }
    ++solution.iterations;
    // Step 2: solve on the current set.
    const Index n = static_cast<Index>(active.size());
    auto columns = work.columns.resize(n, column_count);
    for (Index r = 0; r < n; ++r) columns(r, 0) = -h(active[static_cast<std::size_t>(r)]);
    if (force_control) columns.col(1).setOnes();
    if (!set_solver.solve(active, columns)) {
      solution.status = Status::numerical_issue;
      solution.message = "factorisation of the system on the active set failed";
      return solution;
    }
    auto pressure = columns.col(0);
    if (force_control) {
      // p = p_a + δ p_b with δ from dx·dy·Σp = Fn (docs/design.md §3).
      approach = (loading.normal_force / area - columns.col(0).sum()) / columns.col(1).sum();
      pressure += approach * columns.col(1);
    }

    // Step 3: elements with non-positive pressure leave.
    work.kept.clear();
    for (Index r = 0; r < n; ++r) {
      if (pressure(r) > 0) work.kept.push_back(active[static_cast<std::size_t>(r)]);
    }
    if (static_cast<Index>(work.kept.size()) < n) {
      if (solution.iterations == options.max_iterations) break;  // report this iterate
      active.swap(work.kept);
      continue;
    }
    work.admissible_set = active;
    work.admissible_pressure.assign(pressure.data(), pressure.data() + n);
    admissible_approach = approach;

    // Step 4: elements with negative deformed gap join. C p ≥ 0, so only elements with
    // h − δ < 0 can have g < 0: only those are checked.
    for (Index k : active) work.is_active[static_cast<std::size_t>(k)] = 1;
    work.candidates.clear();
    for (Index k = 0; k < n_all; ++k) {
      if (!work.is_active[static_cast<std::size_t>(k)] && h(k) - approach < join_below) work.candidates.push_back(k);
    }
    for (Index k : active) work.is_active[static_cast<std::size_t>(k)] = 0;
    auto displacements = work.displacement.resize(static_cast<Index>(work.candidates.size()), 1);
    auto displacement = displacements.col(0);
    set_solver.displacement(work.candidates, active, pressure, displacement);
    work.joining.clear();
    for (std::size_t t = 0; t < work.candidates.size(); ++t) {
      if (h(work.candidates[t]) - approach + displacement(static_cast<Index>(t)) < join_below) {
        work.joining.push_back(work.candidates[t]);
      }
    }
    if (work.joining.empty()) {
      store(active, pressure.data(), approach);
      solution.status = Status::converged;
      solution.message = "contact set stable";
      return solution;
    }
    if (solution.iterations == options.max_iterations) break;  // report this iterate
    active.insert(active.end(), work.joining.begin(), work.joining.end());
    std::inplace_merge(active.begin(), active.end() - static_cast<std::ptrdiff_t>(work.joining.size()), active.end());
  }
  // The last iterate, its negative pressures clipped, so the caller can inspect it.
  store(active, work.columns.view().data(), approach);
  solution.status = Status::iteration_limit;
  solution.message = "active set still changing after " + std::to_string(solution.iterations) +
                     " iterations";
  return solution;
}

}  // namespace detail
}  // namespace fastnorm
