#pragma once
/// @file solver_options.hpp
/// The settings of every solver, in one light header (solver_spec.hpp gathers them without
/// pulling in the solvers themselves).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>

#include "fastnorm/constants.hpp"
#include "fastnorm/error.hpp"

namespace fastnorm {

/// Settings of the active-set loop, shared by NORM and the reduced solvers.
template <typename Scalar = double>
struct ActiveSetOptions {
  /// Most linear solves before giving up with Status::iteration_limit.
  int max_iterations = 200;
  /// An element outside the set joins when its deformed gap is below −τ · max|h|, τ this
  /// tolerance (relative). Unset: the solver's own, join_tolerance().
  std::optional<Scalar> gap_tolerance;
  /// The starting set is {h − δ₀ ≤ start_depth_fraction · min(h − δ₀)}, δ₀ = 0 in approach
  /// control and a Hertz-like guess in force control. 1 starts from the deepest element
  /// alone; Kalker's original start, every interpenetrating element, is the limit towards
  /// 0; the default 0.5 is the Hertz contact area, which needs fewer and smaller
  /// factorisations than either (docs/norm.md §2). NORM's answer does not depend on it.
  Scalar start_depth_fraction = Scalar(0.5);
  /// The join check skips a candidate whose gap a bound keeps above zero (docs/method.md
  /// §3, "Pruning the join check"). The answer is the same bit for bit either way; false
  /// evaluates every candidate at every check, for measurement.
  bool bound_join_check = true;

  /// τ of the join check: gap_tolerance if set, else for a solver that solves each set
  /// exactly (NORM) 1000 ε, which keeps round-off from cycling an element whose true gap is
  /// 0 in and out (docs/norm.md §2), and for the reduced solvers reduced_gap_tolerance, or
  /// 1000 ε where that is larger (float): their bases cannot resolve smaller gaps, and
  /// joining what they cannot resolve only spends iterations (docs/method.md §3, "The join
  /// tolerance").
  Scalar join_tolerance(bool exact_on_set) const {
    if (gap_tolerance) return *gap_tolerance;
    const Scalar round_off = 1000 * std::numeric_limits<Scalar>::epsilon();
    return exact_on_set ? round_off : std::max(Scalar(reduced_gap_tolerance), round_off);
  }
  /// The reduced solvers' τ when gap_tolerance is unset (relative to max|h|).
  static constexpr double reduced_gap_tolerance = 3e-5;

  /// @throws fastnorm::invalid_argument naming the offending field
  void validate() const {
    FASTNORM_CHECK(max_iterations >= 1,
                   detail::describe("options: max_iterations must be >= 1", max_iterations));
    FASTNORM_CHECK(!gap_tolerance || (std::isfinite(*gap_tolerance) && *gap_tolerance >= 0),
                   detail::describe("options: gap_tolerance must be finite and >= 0",
                                    gap_tolerance.value_or(Scalar(0))));
    FASTNORM_CHECK(start_depth_fraction > 0 && start_depth_fraction <= 1,
                   detail::describe("options: start_depth_fraction must lie in (0, 1]",
                                    start_depth_fraction));
  }
};

/// Settings of the conjugate-gradient solver.
template <typename Scalar = double>
struct CgOptions {
  /// Stop when the complementarity error (docs/performance.md Eq. (P1)) — the largest
  /// |gap| where p > 0 and the largest interpenetration where p = 0 — is at most
  /// `tolerance` times the largest interpenetration of the undeformed surfaces. The
  /// default is default_tolerance (constants.hpp).
  Scalar tolerance = default_tolerance<Scalar>;
  /// Most iterations (products C t) before Status::iteration_limit.
  int max_iterations = 5000;

  /// @throws fastnorm::invalid_argument naming the offending field
  void validate() const {
    FASTNORM_CHECK(std::isfinite(tolerance) && tolerance > 0,
                   detail::describe("options: tolerance must be positive and finite", tolerance));
    FASTNORM_CHECK(max_iterations >= 1,
                   detail::describe("options: max_iterations must be >= 1", max_iterations));
  }
};

/// Settings of a reduced solver: its active-set loop, and the memory its segment tables
/// may take (docs/method.md §3).
template <typename Scalar = double>
struct ReducedOptions {
  ActiveSetOptions<Scalar> active_set;
  /// Most memory (bytes) for the segment tables (detail/segment_tables.hpp), shared by
  /// copies of the solver. With Scalar = double, the displacement table of one segment
  /// length takes 8·q·(2·mx − n)·my bytes, the correlation table of a pair of lengths (only
  /// where a length's displacement table did not fit) 8·q²·(n_t + n_s − 1) bytes. Past the
  /// budget the solver takes the direct Toeplitz products, slower but the same numbers to
  /// round-off. 0 turns the tables off.
  std::size_t table_budget_bytes = std::size_t(64) << 20;

  /// @throws fastnorm::invalid_argument naming the offending field
  void validate() const { active_set.validate(); }
};

}  // namespace fastnorm
