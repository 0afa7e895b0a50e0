#pragma once
/// @file detail/active_set_loop.hpp
/// The active-set loop shared by NORM and the reduced solvers (docs/norm.md §1): NORM
/// solves each set exactly, the reduced solvers in a small basis; the loop around them is
/// this one.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "fastnorm/detail/scratch_matrix.hpp"
#include "fastnorm/detail/solver_input.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/influence.hpp"
#include "fastnorm/solution.hpp"
#include "fastnorm/solver_options.hpp"
#include "fastnorm/warm_start.hpp"

namespace fastnorm {
namespace detail {

/// Everything the active-set loop touches between iterations. Kept in a solver's workspace
/// across the problems of a sequence, it stops allocating once it has grown to the largest
/// set met: the loop itself allocates nothing then (docs/performance.md §3).
template <typename Scalar>
struct ActiveSetWorkspace {
  using Index = Eigen::Index;
  std::vector<Index> active, kept, candidates, joining, admissible_set;
  /// After a solve that stopped at its iteration limit: the set its loop would have solved
  /// next (the kept elements after a drop, the set and the joining elements after a join
  /// check), sorted; empty after any other end. A solve started from it continues that loop
  /// (ActiveSetLoop::run).
  std::vector<Index> next_set;
  std::vector<Index> visited_elements;   // every set of this solve, one after the other
  std::vector<std::size_t> visited_ends;  // where each ends in visited_elements
  ScratchMatrix<Scalar> columns;          // right-hand sides in, pressures out (n × 1 or n × 2)
  ScratchMatrix<Scalar> displacement;     // at the candidates
  std::vector<Scalar> admissible_pressure;
  std::vector<Scalar> sorted_distance;    // of the force-control starting guess
  std::vector<std::pair<Eigen::Index, Eigen::Index>> candidate_columns;  // per strip (find_joining)
  Solution<Scalar> spare_solution;        // storage for the next answer (workspace.recycle)
  // The join check's memory (ActiveSetLoop::find_joining): per grid element a lower bound
  // of its displacement u and the check that last bounded it, the pressures of the last
  // check (on `checked_set`), per strip their decrease since and its bound. Within a solve,
  // and from one warm solve to the next on the same solver.
  std::vector<Scalar> displacement_floor, checked_pressure, strip_decrease, strip_drop;
  std::vector<int> bounded_at;
  std::vector<Index> checked_set;
  int checks = 0;  // since the floors were last started afresh; 0: none to carry

  /// The workspace moved to another solver, of a grid of `elements` elements: the floors
  /// belong to another influence table, so the next solve starts them afresh; and the lists
  /// get storage for that grid's sets, so that no set of it grows them (what a time loop's
  /// first steps would otherwise allocate a little at a time). The sets of one solve
  /// together (visited_elements) get two grids' worth and may still grow past it.
  void start_on_grid(std::size_t elements) {
    checks = 0;
    for (auto* set : {&active, &kept, &candidates, &joining, &admissible_set, &checked_set, &next_set}) {
      set->reserve(elements);
    }
    admissible_pressure.reserve(elements);
    candidate_columns.reserve(elements);  // per strip: my ≤ elements
    checked_pressure.reserve(elements);
    visited_elements.reserve(2 * elements);
    visited_ends.reserve(32);  // sets of a solve: a loop's usual iterations, with room
    columns.reserve(2 * elements);
    displacement.reserve(elements);
  }

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

/// One run of the active-set loop of docs/norm.md §1 around a solver of the problem
/// restricted to a set. `set_solver.solve(active, columns)` receives the sorted element
/// numbers of the set and, in `columns`, right-hand sides over it (n × 1: −h_I; n × 2 in
/// force control: −h0_I and 1), which it overwrites with the pressures on the set for each
/// column; it returns false if its factorisation failed. `set_solver.displacement(targets,
/// active, p, u)` then writes u = C_TI p for pressures p on that set (the join check of
/// step 4; a solver may use what it knows of p, e.g. that it lies in its basis).
/// `SetSolver::exact_on_set` says whether it solves the set's problem exactly (NORM) or in
/// a basis, which sets the join tolerance's default (ActiveSetOptions::join_tolerance).
///
/// Cycles are ended deterministically: when a set comes back, the loop stops with
/// Status::cycled and the last set whose pressures were all positive. (A cycle contains a
/// join, and joins follow only such a set, so one exists; docs/method.md §3.)
template <typename Scalar, typename SetSolver>
class ActiveSetLoop {
 public:
  using Index = Eigen::Index;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  ActiveSetLoop(const InfluenceTable<Scalar>& influence, const Eigen::Ref<const Vector>& h,
                const Loading<Scalar>& loading, const ActiveSetOptions<Scalar>& options, SetSolver& set_solver,
                ActiveSetWorkspace<Scalar>& work)
      : influence_(influence), h_(h), loading_(loading), options_(options), set_solver_(set_solver), work_(work) {}

  /// Runs the loop from `start_set` (sorted element numbers), or from step 1's set if empty.
  /// A run stopped by the iteration limit leaves in `work.next_set` the set it would have
  /// solved next; a run started from that set takes the steps the stopped one would have
  /// taken (the sets, not the cycle check's memory of them), so that a solve limited to a
  /// few iterations a time step and continued at the next is the loop continued across
  /// steps, not restarted (docs/wheel-rail.md §9, the iteration budget). `stop`: a run
  /// stops after stop.soft iterations at an iterate whose pressures are all positive and
  /// whose join check's residual is at most IterationStop::settled_residual, and after
  /// stop.hard in any case; with stop.budget a stop once an iterate had all pressures
  /// positive (admissible) answers with the last such iterate, Status::budget_reached, and
  /// any other stop with the clipped last iterate, Status::iteration_limit.
  Solution<Scalar> run(const std::vector<Index>& start_set, const IterationStop& stop) {
    const Index n_all = influence_.grid().size();
    solution_ = std::move(work_.spare_solution);
    solution_.clear(n_all);
    work_.next_set.clear();
    if (!choose_start(start_set)) return finish(Status::no_contact, "no element has a negative undeformed distance");
    work_.visited_elements.clear();
    work_.visited_ends.clear();
    work_.admissible_set.clear();  // last set with all pressures positive
    // A warm solve keeps the floors of the previous solve's checks: the bound holds for any
    // two pressure fields on the same influence table (docs/method.md §3). A cold one, whose
    // first set is far from the last, starts them afresh (cheaper than a bound that fails).
    // (The check counter restarts long before it could overflow.)
    const bool carry = options_.bound_join_check && !start_set.empty() && work_.checks > 0 &&
                       work_.checks < std::numeric_limits<int>::max() / 2;
    if (!carry) {
      work_.checks = 0;
      if (options_.bound_join_check) {
        work_.bounded_at.assign(static_cast<std::size_t>(n_all), 0);
        work_.displacement_floor.resize(static_cast<std::size_t>(n_all));
      }
    }
    while (solution_.iterations < stop.hard) {
      if (work_.seen_before(work_.active)) {
        if (work_.admissible_set.empty()) {  // no set ever had positive pressures: round-off rules
          return finish(Status::numerical_issue,
                        "active set cycled before any set had positive pressures (modulus too large for the "
                        "precision?)");
        }
        store(work_.admissible_set, work_.admissible_pressure.data(), admissible_approach_);
        return finish(Status::cycled, "active set cycled; returned the last set with positive pressures");
      }
      ++solution_.iterations;
      if (!solve_on_set()) return finish(Status::numerical_issue, "factorisation of the system on the active set failed");
      if (drop_non_positive()) {
        if (solution_.iterations >= stop.hard) {
          work_.next_set = work_.kept;
          break;
        }
        work_.active.swap(work_.kept);
        continue;
      }
      remember_admissible();
      find_joining();
      if (work_.joining.empty()) {
        store(work_.active, work_.columns.view().data(), approach_);
        return finish(Status::converged, "contact set stable");
      }
      const bool settled_stop =
          solution_.iterations >= stop.soft && residual_ <= Scalar(IterationStop::settled_residual);
      if (solution_.iterations >= stop.hard || settled_stop) {  // report this iterate
        merge_joining(work_.next_set);
        break;
      }
      merge_joining(work_.kept);
      work_.active.swap(work_.kept);
    }
    // Messages are literals: a cut solve, which a time step's budget makes routine,
    // allocates nothing.
    if (stop.budget && !work_.admissible_set.empty()) {
      // The last admissible iterate: the set just checked for joins, or the one before a
      // drop; residual_ is still its join check's.
      store(work_.admissible_set, work_.admissible_pressure.data(), admissible_approach_);
      return finish(Status::budget_reached, "stopped by the iteration budget; the next solve goes on from here");
    }
    // The last iterate, its negative pressures clipped, so the caller can inspect it.
    store(work_.active, work_.columns.view().data(), approach_);
    return finish(Status::iteration_limit, "active set still changing at the iteration limit");
  }

 private:
  bool force_control() const { return loading_.control == Control::force; }

  /// Step 1 (docs/norm.md §2): the first approach and set; false if nothing touches.
  bool choose_start(const std::vector<Index>& start_set) {
    deepest_ = h_.minCoeff();
    max_abs_h_ = h_.cwiseAbs().maxCoeff();
    join_below_ = -options_.join_tolerance(SetSolver::exact_on_set) * max_abs_h_;
    if (force_control()) {
      approach_ = approach_guess(h_, influence_.grid().element_area(), influence_.combined_modulus(),
                                 loading_.normal_force, work_.sorted_distance);
    } else if (deepest_ >= 0) {
      return false;
    }
    const Scalar start_below = approach_ + options_.start_depth_fraction * (deepest_ - approach_);
    work_.active = start_set;
    if (work_.active.empty()) {
      for (Index k = 0; k < h_.size(); ++k) {
        if (h_(k) <= start_below) work_.active.push_back(k);
      }
    }
    return true;
  }

  /// Step 2: pressures on the set (columns.col(0) afterwards), and δ in force control.
  bool solve_on_set() {
    const auto n = static_cast<Index>(work_.active.size());
    auto columns = work_.columns.resize(n, force_control() ? 2 : 1);
    for (Index r = 0; r < n; ++r) columns(r, 0) = -h_(work_.active[static_cast<std::size_t>(r)]);
    if (force_control()) columns.col(1).setOnes();
    if (!set_solver_.solve(work_.active, columns)) return false;
    if (force_control()) {
      // p = p_a + δ p_b with δ from dx·dy·Σp = Fn (docs/design.md §3).
      approach_ = (loading_.normal_force / influence_.grid().element_area() - columns.col(0).sum()) /
                  columns.col(1).sum();
      columns.col(0) += approach_ * columns.col(1);
    }
    return true;
  }

  /// Step 3: the elements with positive pressure go to `kept`; true if any other left.
  bool drop_non_positive() {
    const auto pressure = work_.columns.view().col(0);
    work_.kept.clear();
    for (Index r = 0; r < pressure.size(); ++r) {
      if (pressure(r) > 0) work_.kept.push_back(work_.active[static_cast<std::size_t>(r)]);
    }
    return static_cast<Index>(work_.kept.size()) < pressure.size();
  }

  void remember_admissible() {
    const auto pressure = work_.columns.view().col(0);
    work_.admissible_set = work_.active;
    work_.admissible_pressure.assign(pressure.data(), pressure.data() + pressure.size());
    admissible_approach_ = approach_;
  }

  /// Step 4: elements outside the set with negative deformed gap, into `joining`. C p ≥ 0,
  /// so only elements with h − δ < 0 can have g < 0: only those are candidates. Records the
  /// deepest interpenetration found as the residual.
  ///
  /// A candidate whose gap is bounded away from zero is not evaluated (docs/method.md §3,
  /// "Pruning the join check"): between two checks of a solve u_t changes by
  /// Σ_k C_tk Δp_k ≥ −Σ_j' max_i C(i, j_t − j') D_j', D_j' the decrease of the pressure
  /// summed over strip j'. So u_t is at least its value at the last check minus that
  /// per-strip bound, accumulated over the checks since it was evaluated; where the gap that
  /// lower bound gives stays above a margin of round-off, the candidate can neither join nor
  /// deepen the residual. The evaluated candidates get the same displacements as without
  /// pruning (each sums its sources in the same order), so the loop takes the same steps,
  /// bit for bit.
  void find_joining() {
    const auto& grid = influence_.grid();
    const auto pressure = work_.columns.view().col(0);
    const bool bounded = options_.bound_join_check && work_.checks > 0;
    ++work_.checks;
    if (bounded) bound_displacement_change(pressure);
    // Round-off of a sum of displacements stays far below this (relative 1000 ε).
    const Scalar margin = 1000 * std::numeric_limits<Scalar>::epsilon() * max_abs_h_;
    find_candidate_columns();
    work_.candidates.clear();
    // The displacements cost per run of candidates along a strip and per source segment,
    // an element of a run far less: a bounded candidate between two evaluated ones of the
    // same run is evaluated too, so that pruning never splits a run. Each strip is scanned
    // over its candidate columns only, and the set's elements there are skipped as the runs
    // of the sorted set they are.
    const auto& active = work_.active;
    const Scalar* h = h_.data();
    const Scalar approach = approach_, join_below = join_below_;
    std::size_t next_active = 0;  // the first element of the set not before the scan
    for (Index j = 0; j < grid.my(); ++j) {
      const auto& columns = work_.candidate_columns[static_cast<std::size_t>(j)];
      Index last_evaluated = -1;  // in the current run of candidates; −1: none yet
      for (Index k = j * grid.mx() + columns.first; k < j * grid.mx() + columns.second; ++k) {
        while (next_active < active.size() && active[next_active] < k) ++next_active;
        const bool in_set = next_active < active.size() && active[next_active] == k;
        if (in_set || !(h[k] - approach < join_below)) {
          last_evaluated = -1;  // the run ends
          continue;
        }
        const auto e = static_cast<std::size_t>(k);
        if (bounded && work_.bounded_at[e] == work_.checks - 1) {
          auto& floor = work_.displacement_floor[e];
          floor -= work_.strip_drop[static_cast<std::size_t>(j)];
          if (h[k] - approach + floor >= margin) {
            work_.bounded_at[e] = work_.checks;  // still a bound; evaluated only if bridged
            continue;
          }
        }
        // The bounded candidates since the last evaluated one of this run, then k.
        if (last_evaluated >= 0) {
          for (Index bridged = last_evaluated + 1; bridged < k; ++bridged) work_.candidates.push_back(bridged);
        }
        work_.candidates.push_back(k);
        last_evaluated = k;
      }
    }
    auto displacement = work_.displacement.resize(static_cast<Index>(work_.candidates.size()), 1).col(0);
    set_solver_.displacement(work_.candidates, work_.active, pressure, displacement);
    work_.joining.clear();
    Scalar deepest_gap = 0;
    for (std::size_t t = 0; t < work_.candidates.size(); ++t) {
      const Index k = work_.candidates[t];
      const Scalar gap = h_(k) - approach_ + displacement(static_cast<Index>(t));
      deepest_gap = std::min(deepest_gap, gap);
      if (gap < join_below_) work_.joining.push_back(k);
    }
    residual_ = std::max(Scalar(0), -deepest_gap) / (approach_ - deepest_);
    if (!options_.bound_join_check) return;
    // What the next check bounds the change from.
    for (std::size_t t = 0; t < work_.candidates.size(); ++t) {
      const auto e = static_cast<std::size_t>(work_.candidates[t]);
      work_.displacement_floor[e] = displacement(static_cast<Index>(t));
      work_.bounded_at[e] = work_.checks;
    }
    work_.checked_set = work_.active;
    work_.checked_pressure.assign(pressure.data(), pressure.data() + pressure.size());
  }

  /// Per strip, the columns [first, last) between the first and the last element that can
  /// join at the current approach (h − δ below the join threshold); the rest of the strip
  /// holds no candidate. Found again only when δ moved (force control), so that a check
  /// scans about the interpenetrating part of the box, not all of it.
  void find_candidate_columns() {
    if (columns_approach_ && *columns_approach_ == approach_) return;
    columns_approach_ = approach_;
    const auto& grid = influence_.grid();
    auto& columns = work_.candidate_columns;
    columns.assign(static_cast<std::size_t>(grid.my()), {Index(0), Index(0)});
    for (Index j = 0; j < grid.my(); ++j) {
      const Scalar* strip = h_.data() + j * grid.mx();
      Index first = 0, last = grid.mx();
      while (first < last && !(strip[first] - approach_ < join_below_)) ++first;
      while (last > first && !(strip[last - 1] - approach_ < join_below_)) --last;
      columns[static_cast<std::size_t>(j)] = {first, last};
    }
  }

  /// strip_drop[j] ≥ −Σ_k C(·, j − j_k) Δp_k over every element of strip j: the largest
  /// fall of u on strip j since the last check, from the pressures' decreases per strip
  /// (only elements of the last checked set can have lost pressure: p ≥ 0 elsewhere then).
  void bound_displacement_change(const Eigen::Ref<const Vector>& pressure) {
    const auto& grid = influence_.grid();
    const auto my = static_cast<std::size_t>(grid.my());
    auto& decrease = work_.strip_decrease;
    decrease.assign(my, Scalar(0));
    // The current pressure of a last-checked element: the sets are sorted, so one merge.
    std::size_t r = 0;
    const auto& now = work_.active;
    for (std::size_t c = 0; c < work_.checked_set.size(); ++c) {
      const Index k = work_.checked_set[c];
      while (r < now.size() && now[r] < k) ++r;
      const Scalar current = r < now.size() && now[r] == k ? pressure(static_cast<Index>(r)) : Scalar(0);
      const Scalar fall = work_.checked_pressure[c] - current;
      if (fall > 0) decrease[static_cast<std::size_t>(grid.j_of(k))] += fall;
    }
    // max_i C(i, dj) = C(0, dj): the displacement of a uniformly loaded rectangle falls off
    // along x on every line parallel to it (tests/core/influence.test.cpp checks the table).
    work_.strip_drop.assign(my, Scalar(0));
    for (std::size_t source = 0; source < my; ++source) {
      if (decrease[source] == 0) continue;
      for (std::size_t j = 0; j < my; ++j) {
        const auto dj = static_cast<Index>(j) - static_cast<Index>(source);
        work_.strip_drop[j] += influence_.at_offset(0, dj) * decrease[source];
      }
    }
  }

  /// The set and the joining elements (both sorted) merged into `merged`: `kept`, whose
  /// storage is free until the next drop, for a join (std::inplace_merge would take a
  /// temporary buffer from the heap at every join), or `next_set` for a cut solve.
  void merge_joining(std::vector<Index>& merged) {
    merged.clear();
    std::merge(work_.active.begin(), work_.active.end(), work_.joining.begin(), work_.joining.end(),
               std::back_inserter(merged));
  }

  /// The pressures `pressure` on `set` (negative ones clipped) as the answer, into the
  /// answer that run() cleared (zero and out of contact everywhere; stored once a run).
  void store(const std::vector<Index>& set, const Scalar* pressure, Scalar approach) {
    for (std::size_t r = 0; r < set.size(); ++r) {
      const Scalar value = std::max(pressure[r], Scalar(0));
      solution_.pressure(set[r]) = value;
      solution_.in_contact(set[r]) = value > 0;
    }
    solution_.approach = approach;
    solution_.normal_force = influence_.grid().element_area() * solution_.pressure.sum();
  }

  /// `message` is copied into the answer's string, which keeps its storage (a recycled
  /// answer's: no allocation).
  Solution<Scalar> finish(Status status, const char* message) {
    solution_.status = status;
    solution_.message = message;
    solution_.residual = residual_;
    const auto& grid = influence_.grid();
    check_answer(solution_, grid.mx(), grid.my(), grid.element_area(), loading_);
    return std::move(solution_);
  }

  const InfluenceTable<Scalar>& influence_;
  const Eigen::Ref<const Vector>& h_;
  const Loading<Scalar>& loading_;
  const ActiveSetOptions<Scalar>& options_;
  SetSolver& set_solver_;
  ActiveSetWorkspace<Scalar>& work_;
  Solution<Scalar> solution_;
  std::optional<Scalar> columns_approach_;  // the approach at which candidate_columns were found
  Scalar deepest_ = 0, max_abs_h_ = 0, join_below_ = 0, approach_ = 0, admissible_approach_ = 0, residual_ = 0;
};

/// Checks the problem and runs the loop (see ActiveSetLoop) from the start's set, or cold
/// if it is empty, within the start's iteration limit and cap.
/// @throws fastnorm::invalid_argument for wrong sizes or non-finite h, or a bad Fn
template <typename Scalar, typename SetSolver>
Solution<Scalar> solve_active_set(const InfluenceTable<Scalar>& influence,
                                  const Eigen::Ref<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>& h,
                                  const Loading<Scalar>& loading, const ActiveSetOptions<Scalar>& options,
                                  SetSolver& set_solver, ActiveSetWorkspace<Scalar>& work,
                                  const WarmStart<Scalar>& start) {
  check_problem(influence.grid(), h, loading);
  return ActiveSetLoop<Scalar, SetSolver>(influence, h, loading, options, set_solver, work)
      .run(start.contact_set(), start.stop(options.max_iterations));
}

/// dFn/dδ at the contact set of `solution` (docs/norm.md §4): on a fixed set I the
/// pressures are p_I = S⁻¹(δ − h_I) with S the set solver's operator (C_II, or its Galerkin
/// projection), so dFn/dδ = area · Σ S⁻¹ 1. One more solve on the set, which reuses the
/// factor the loop left when the set is the last one it solved.
template <typename Scalar, typename SetSolver>
Scalar set_stiffness(SetSolver& set_solver, const Solution<Scalar>& solution, ActiveSetWorkspace<Scalar>& work,
                     Scalar element_area) {
  work.active.clear();
  for (Eigen::Index k = 0; k < solution.in_contact.size(); ++k) {
    if (solution.in_contact(k)) work.active.push_back(k);
  }
  if (work.active.empty()) return Scalar(0);
  auto columns = work.columns.resize(static_cast<Eigen::Index>(work.active.size()), 1);
  columns.setOnes();
  if (!set_solver.solve(work.active, columns)) return std::numeric_limits<Scalar>::quiet_NaN();
  return element_area * columns.sum();
}

}  // namespace detail
}  // namespace fastnorm
