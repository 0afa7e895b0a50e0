#pragma once
/// @file reduced_solver.hpp
/// Reduced strip-basis solvers (Giner-Navarro, Gómez-Bosch, Alonso, Baeza, Wear 2023;
/// docs/design.md §4, docs/method.md): NORM's active-set loop with the solve on each set
/// replaced by the Galerkin system (Aᵀ C_II A) α = Aᵀ rhs, p_I = A α, where A holds a small
/// basis per segment of each strip.

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <utility>

#include "fastnorm/bases.hpp"
#include "fastnorm/detail/active_set_loop.hpp"
#include "fastnorm/detail/galerkin_set_solver.hpp"
#include "fastnorm/detail/segment_tables.hpp"
#include "fastnorm/detail/solver_base.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/influence.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/solution.hpp"
#include "fastnorm/solver_options.hpp"
#include "fastnorm/warm_start.hpp"

namespace fastnorm {

template <typename Basis, typename Scalar>
class ReducedSolver;

/// What a reduced solver keeps between solves: the starting set, the Galerkin assemblies
/// and factors of the sets of its last solve (the next solve reuses those it meets again),
/// the basis blocks, and the loop's storage. One per thread; it may move between solvers
/// (what belonged to another solver is dropped, its storage kept).
template <typename Scalar = double>
class ReducedWorkspace {
 public:
  /// Where the next solve starts. A reduced solver does not fill it: its answer depends on
  /// the path of the active set, so it starts as a cold solve unless a caller sets a set.
  WarmStart<Scalar>& start() { return start_; }
  const WarmStart<Scalar>& start() const { return start_; }
  /// The next solve is cold: no starting set, no assemblies to reuse (storage kept).
  void forget() {
    start_.clear();
    memory_.forget();
  }
  /// Storage for the next solve's answer: a Solution no longer needed (e.g. the previous
  /// answer of a time loop), handed back so that the next solve fills it instead of
  /// allocating its vectors.
  void recycle(Solution<Scalar>&& used) { loop_.spare_solution = std::move(used); }

 private:
  template <typename Basis, typename S>
  friend class ReducedSolver;
  WarmStart<Scalar> start_;
  std::uint64_t owner_ = 0;  // detail::new_object_id() of the solver the memory belongs to
  detail::GalerkinMemory<Scalar> memory_;
  detail::ActiveSetWorkspace<Scalar> loop_;
};

/// A reduced strip-basis solver: NORM's active-set loop with a Galerkin solve in `Basis`
/// (EllipticBasis, PolynomialBasis, EdgeEnriched<…>, or any type with the interface of
/// bases.hpp) on each set.
///
/// **Example**
/// @code
/// fastnorm::ReducedSolver<fastnorm::PolynomialBasis> solver(grid, steel, fastnorm::PolynomialBasis(4));
/// auto solution = solver.solve(h, fastnorm::Loading<>::approach());
/// @endcode
template <typename Basis, typename Scalar = double>
class ReducedSolver : public detail::SolverBase<ReducedSolver<Basis, Scalar>, ReducedWorkspace<Scalar>, Scalar> {
 public:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Options = ReducedOptions<Scalar>;
  using Workspace = ReducedWorkspace<Scalar>;
  using detail::SolverBase<ReducedSolver, Workspace, Scalar>::solve;

  /// @throws fastnorm::invalid_argument for invalid options
  ReducedSolver(const Grid<Scalar>& grid, const Material<Scalar>& material, Basis basis = Basis(),
                Options options = {})
      : ReducedSolver(grid, material, std::move(basis), options, nullptr) {}

  /// A solver of this one's material, basis and options on `grid`, sharing this one's
  /// segment tables (and their budget) if `grid` has its element sizes and no more elements
  /// either way; else with tables of its own. What a model that meets many grid sizes uses
  /// so that each table is built once (docs/method.md §3): make a solver on the largest
  /// grid, then one for_grid per size met. The answers are those of a solver made anew on
  /// `grid`, to the last digit.
  ReducedSolver for_grid(const Grid<Scalar>& grid) const {
    return ReducedSolver(grid, material_, basis_, options_, tables_);
  }

  const Grid<Scalar>& grid() const { return influence_->grid(); }
  const InfluenceTable<Scalar>& influence() const { return *influence_; }
  const Basis& basis() const { return basis_; }
  const Options& options() const { return options_; }

  /// As NormSolver::solve, with the pressure along each segment in the basis. Every set
  /// that the workspace's previous solve met (in a slowly changing sequence, most of them)
  /// reuses its assembly and factorisation, and new sets copy the blocks of unchanged
  /// segments (docs/performance.md §4); the answer is the cold path's, to round-off.
  /// @throws fastnorm::invalid_argument for wrong sizes, non-finite h, a bad Fn or a bad start
  Solution<Scalar> solve(const Eigen::Ref<const Vector>& undeformed_distance, const Loading<Scalar>& loading,
                         Workspace& workspace) const {
    workspace.start_.check(grid().size());
    if (workspace.owner_ != id_) {  // assemblies of another basis or grid: their storage is kept
      workspace.memory_.forget();
      // Two segments a strip, and 16 sets a solve: an active-set loop's usual iterations.
      workspace.memory_.reserve(2 * static_cast<std::size_t>(grid().my()), 16);
      workspace.loop_.start_on_grid(static_cast<std::size_t>(grid().size()));
      workspace.owner_ = id_;
    }
    workspace.memory_.next_problem();
    detail::GalerkinSetSolver<Basis, Scalar> set_solver(*influence_, basis_, *tables_, workspace.memory_);
    Solution<Scalar> solution = detail::solve_active_set(*influence_, undeformed_distance, loading,
                                                         options_.active_set, set_solver, workspace.loop_,
                                                         workspace.start_);
    // The start is left as it was, but after a solve stopped by the iteration limit: then the
    // set the loop would have solved next (ActiveSetWorkspace::next_set).
    if (solution.stopped_early()) workspace.start_.set_contact_set(workspace.loop_.next_set);
    return solution;
  }

  /// The normal stiffness dFn/dδ (N/m) of the reduced problem at the contact set of
  /// `solution`, the last solve in `workspace`: area · 1ᵀ A (Aᵀ C_II A)⁻¹ Aᵀ 1, by the factor
  /// that solve left (docs/norm.md §4). 0 without contact.
  Scalar normal_stiffness(const Solution<Scalar>& solution, Workspace& workspace) const {
    FASTNORM_CHECK(solution.in_contact.size() == grid().size(), "ReducedSolver::normal_stiffness: solution of another grid");
    FASTNORM_CHECK(workspace.owner_ == id_, "ReducedSolver::normal_stiffness: the workspace holds another solver's solve");
    detail::GalerkinSetSolver<Basis, Scalar> set_solver(*influence_, basis_, *tables_, workspace.memory_);
    return detail::set_stiffness(set_solver, solution, workspace.loop_, grid().element_area());
  }

  /// Builds now every segment table a solve on this solver's grid, or on any for_grid
  /// shares them with, can read, if together they fit options().table_budget_bytes; else
  /// nothing (each is built on first use). Returns whether it built them. What a time loop
  /// does before its first step so that no step builds a table (docs/wheel-rail.md §9).
  bool build_tables() const {
    return tables_->build_all([this](Eigen::Index count) { return Galerkin::segment_block(basis_, count); },
                              basis_.unknowns() + 1);
  }

  /// Memory the segment tables take now (bytes); shared with copies of this solver and
  /// the solvers for_grid made from it that share its tables.
  std::size_t table_bytes() const { return tables_->used_bytes(); }

 private:
  /// With `shared` tables and their extent's influence coefficients if they cover `grid`;
  /// else tables and coefficients of its own.
  ReducedSolver(const Grid<Scalar>& grid, const Material<Scalar>& material, Basis basis, Options options,
                std::shared_ptr<detail::SegmentTables<Scalar>> shared)
      : influence_(influence_for(grid, material, shared.get())),
        material_(material),
        basis_(std::move(basis)),
        options_(options) {
    options_.validate();
    tables_ = shared && shared->covers(*influence_)
                  ? std::move(shared)
                  : std::make_shared<detail::SegmentTables<Scalar>>(influence_, options_.table_budget_bytes);
  }

  using Galerkin = detail::GalerkinSetSolver<Basis, Scalar>;

  /// The influence table of `grid`: the coefficients of `shared`'s extent if it covers the
  /// grid (nothing computed), else its own.
  static std::shared_ptr<const InfluenceTable<Scalar>> influence_for(const Grid<Scalar>& grid,
                                                                      const Material<Scalar>& material,
                                                                      const detail::SegmentTables<Scalar>* shared) {
    if (shared && shared->covers(grid, material.combined_modulus())) {
      return std::make_shared<const InfluenceTable<Scalar>>(shared->extent(), grid);
    }
    return std::make_shared<const InfluenceTable<Scalar>>(grid, material);
  }

  std::shared_ptr<const InfluenceTable<Scalar>> influence_;
  Material<Scalar> material_;
  Basis basis_;
  Options options_;
  // Built on first use; h-independent, so copies and for_grid's solvers share them
  // (thread-safe).
  std::shared_ptr<detail::SegmentTables<Scalar>> tables_;
  std::uint64_t id_ = detail::new_object_id();
};

}  // namespace fastnorm
