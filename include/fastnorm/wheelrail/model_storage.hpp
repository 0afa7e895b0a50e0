#pragma once
/// @file model_storage.hpp
/// What the time loop's model keeps so that a step allocates nothing once its sizes have
/// been met (docs/wheel-rail.md §9): the solvers per grid size with their spare
/// workspaces, result storage by length, and vectors resized without freeing storage.

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "fastnorm/error.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/solver_from_spec.hpp"
#include "fastnorm/solver_spec.hpp"
#include "fastnorm/wheelrail/wheelset_contact_result.hpp"

namespace fastnorm::wheelrail::detail {

/// Room a new pool of spares gets when it is made: a few patches' worth, so that handing
/// storage back to it later (a patch that changes grid size) does not allocate in a step.
inline constexpr std::size_t spare_room = 4;

/// `used` resized to `count` elements without freeing any element's storage: those beyond
/// `count` move to `spare`, and a growing `used` takes them back from it before making new
/// ones (so a patch count that drops and rises again allocates nothing).
template <typename T>
void resize_keeping_storage(std::vector<T>& used, std::vector<T>& spare, std::size_t count) {
  while (used.size() > count) {
    spare.push_back(std::move(used.back()));
    used.pop_back();
  }
  while (used.size() < count) {
    if (spare.empty()) {
      used.emplace_back();
    } else {
      used.push_back(std::move(spare.back()));
      spare.pop_back();
    }
  }
}

/// `to` made a copy of `from` element by element, in the storage its elements hold (see
/// resize_keeping_storage for `spare`): copying into kept vectors and workspaces allocates
/// only where they are smaller than what they receive.
template <typename T>
void copy_keeping_storage(const std::vector<T>& from, std::vector<T>& to, std::vector<T>& spare) {
  resize_keeping_storage(to, spare, from.size());
  for (std::size_t k = 0; k < from.size(); ++k) to[k] = from[k];
}

/// One solver per grid size met (element sizes fixed: solvers do not depend on the grid's
/// origin), each with its influence table, and the workspaces with its storage that no
/// patch holds at the moment. The solvers of a reduced kind share one set of segment
/// tables, those of a solver on the largest box (share_tables); when those are all built
/// ahead, so are the solvers of every lattice box size they cover.
template <typename Solver>
class SolverCache {
 public:
  using Workspace = typename Solver::Workspace;

  /// Makes the solver on `largest` whose segment tables the solvers of every grid it covers
  /// share (ReducedSolver::for_grid), and builds them all now if together they fit the
  /// spec's budget (ReducedSolver::build_tables), if `spec` is of a reduced kind and
  /// `Solver` shares tables; else nothing (each solver keeps its own tables). When it builds
  /// them, it also builds the solver of every grid within `largest` whose sides are
  /// multiples of `quantum` (the lattice's box sizes, patch_lattice.hpp), each with room for
  /// its spares, so that a step meeting a box size for the first time builds nothing
  /// (docs/wheel-rail.md §9): (mx/quantum)·(my/quantum) small solvers, 144 for a 96-element
  /// box, each a view of the shared coefficients and tables. Called once, on an empty cache
  /// (the model's constructor): index_for then finds those solvers by their position.
  void share_tables(const Grid<double>& largest, Eigen::Index quantum, const SolverSpec<double>& spec,
                    const Material<double>& material) {
    if constexpr (fastnorm::detail::shares_tables<Solver>) {
      FASTNORM_ASSERT(slots_.empty() && !family_);  // index_for counts on the lattice's solvers coming first
      if (!spec.is_reduced()) return;
      family_.emplace(SolverFromSpec<Solver>::make(spec, largest, material));
      tables_built_ = family_->build_tables();
      if (!tables_built_) return;
      slots_.reserve(static_cast<std::size_t>((largest.mx() / quantum) * (largest.my() / quantum)));
      for (Eigen::Index mx = quantum; mx <= largest.mx(); mx += quantum) {
        for (Eigen::Index my = quantum; my <= largest.my(); my += quantum) {
          index_for(Grid<double>(mx, my, largest.dx(), largest.dy()), spec, material);
        }
      }
      quantum_ = quantum;  // from now on index_for finds them by their sizes alone
    }
  }

  /// Whether share_tables built every table ahead.
  bool tables_built() const { return tables_built_; }

  /// The number of the solver of `grid`'s size, built from `spec` and `material` when it is
  /// met for the first time.
  std::size_t index_for(const Grid<double>& grid, const SolverSpec<double>& spec, const Material<double>& material) {
    if (quantum_ > 0) {  // share_tables' solvers come first, by rows of the lattice's sizes
      const Grid<double>& largest = family_->grid();
      if (grid.mx() % quantum_ == 0 && grid.my() % quantum_ == 0 && grid.mx() <= largest.mx() &&
          grid.my() <= largest.my()) {
        const Eigen::Index row = grid.mx() / quantum_ - 1, column = grid.my() / quantum_ - 1;
        return static_cast<std::size_t>(row * (largest.my() / quantum_) + column);
      }
    }
    for (std::size_t s = 0; s < slots_.size(); ++s) {
      const auto& known = slots_[s].solver.grid();
      if (known.mx() == grid.mx() && known.my() == grid.my()) return s;
    }
    slots_.push_back({make(grid, spec, material), {}});
    slots_.back().spare.reserve(spare_room);
    return slots_.size() - 1;
  }

  const Solver& solver(std::size_t s) const { return slots_[s].solver; }
  std::size_t size() const { return slots_.size(); }

  /// A spare workspace of solver `s`; else, if `across_sizes`, one of the largest grid's
  /// solver that has a spare (a workspace may move between solvers: a reduced solver's
  /// storage keeps its capacity and serves the new one, where NORM's and CG's grid-sized
  /// vectors would be allocated again); else a new one. A spare comes with what it kept of
  /// earlier solves forgotten, so that no answer depends on which spare a patch took (after
  /// trials restored, the spares are not those of a model that never saw them).
  Workspace take_workspace(std::size_t s, bool across_sizes) {
    std::size_t from = s;
    if (slots_[s].spare.empty()) {
      if (!across_sizes) return Workspace();
      for (std::size_t other = 0; other < slots_.size(); ++other) {
        if (!slots_[other].spare.empty() &&
            (from == s || slots_[other].solver.grid().size() > slots_[from].solver.grid().size())) {
          from = other;
        }
      }
      if (from == s) return Workspace();
    }
    Workspace workspace = std::move(slots_[from].spare.back());
    slots_[from].spare.pop_back();
    workspace.forget();
    return workspace;
  }

  /// A workspace of solver `s` that no patch holds any more.
  void give_back(std::size_t s, Workspace&& workspace) { slots_[s].spare.push_back(std::move(workspace)); }

 private:
  Solver make(const Grid<double>& grid, const SolverSpec<double>& spec, const Material<double>& material) const {
    if constexpr (fastnorm::detail::shares_tables<Solver>) {
      if (family_) return family_->for_grid(grid);
    }
    return SolverFromSpec<Solver>::make(spec, grid, material);
  }

  struct Slot {
    Solver solver;
    std::vector<Workspace> spare;
  };
  std::vector<Slot> slots_;
  std::optional<Solver> family_;  // share_tables' solver on the largest box, never solving
  bool tables_built_ = false;
  // The side step of the box sizes share_tables built, up to family_'s grid (0: none built).
  Eigen::Index quantum_ = 0;
};

/// Result storage that no result patch holds at the moment, by length: Eigen's vectors keep
/// no capacity, so a result slot that meets another grid size would otherwise allocate
/// whenever patches appear, merge or vanish.
class StorageByLength {
 public:
  /// Gives the result patch `out` an h, a solution and tractions of `length` elements: its
  /// own, if they have that length; else spares of that length, its own going to the spares
  /// of theirs.
  void fit(PatchContact& out, Eigen::Index length) {
    exchange(out.patch.undeformed_distance, out.patch.undeformed_distance.size(), length, &Spares::distances);
    exchange(out.solution, out.solution.pressure.size(), length, &Spares::solutions);
    exchange(out.traction, out.traction.traction_x.size(), length, &Spares::tractions);
  }

 private:
  struct Spares {
    Eigen::Index length = 0;
    std::vector<Eigen::VectorXd> distances;
    std::vector<Solution<double>> solutions;
    std::vector<TangentialSolution<double>> tractions;
  };

  Spares& spares_of(Eigen::Index length) {
    for (auto& spare : spares_) {
      if (spare.length == length) return spare;
    }
    spares_.push_back({length, {}, {}, {}});
    Spares& made = spares_.back();
    made.distances.reserve(spare_room);
    made.solutions.reserve(spare_room);
    made.tractions.reserve(spare_room);
    return made;
  }

  /// `held`, of `held_length` elements, for one of `length` from the spares (if any: else it
  /// is sized, once, where it is filled).
  template <typename T>
  void exchange(T& held, Eigen::Index held_length, Eigen::Index length, std::vector<T> Spares::*pool) {
    if (held_length == length) return;
    if (held_length > 0) (spares_of(held_length).*pool).push_back(std::move(held));
    auto& spares = spares_of(length).*pool;
    if (spares.empty()) return;
    held = std::move(spares.back());
    spares.pop_back();
  }

  std::vector<Spares> spares_;
};

}  // namespace fastnorm::wheelrail::detail
