#pragma once
/// @file norm_solver.hpp
/// Kalker's NORM: the active-set solver for the normal contact problem, approach and
/// force control, with a dense Cholesky factorisation of the active block. This is the
/// reference path every faster solver is tested against (docs/design.md §3, docs/norm.md).

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "fastnorm/detail/active_set_loop.hpp"
#include "fastnorm/detail/in_place_cholesky.hpp"
#include "fastnorm/detail/solver_base.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/influence.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/solution.hpp"
#include "fastnorm/solver_options.hpp"
#include "fastnorm/warm_start.hpp"

namespace fastnorm {

template <typename Scalar>
class NormSolver;

/// What a NormSolver keeps between solves: the starting set, the Cholesky factor of the
/// last set solved, and the loop's storage. One workspace per thread; it may move between
/// solvers (a factor from another solver's table is never used).
template <typename Scalar = double>
class NormWorkspace {
 public:
  /// Where the next solve starts; after a solve, its contact set.
  WarmStart<Scalar>& start() { return start_; }
  const WarmStart<Scalar>& start() const { return start_; }
  /// The next solve is cold (storage kept).
  void forget() {
    start_.clear();
    factorisation_.valid = false;
  }
  /// Storage for the next solve's answer: a Solution no longer needed (e.g. the previous
  /// answer of a time loop), handed back so that the next solve fills it instead of
  /// allocating its vectors.
  void recycle(Solution<Scalar>&& used) { loop_.spare_solution = std::move(used); }

 private:
  friend class NormSolver<Scalar>;
  using Index = Eigen::Index;
  /// The Cholesky factor of C_II for the set I last solved on `table`.
  struct Factorisation {
    std::vector<Index> set;
    std::uint64_t solver = 0;  // detail::new_object_id() of the solver that factorised
    bool valid = false;
    detail::InPlaceCholesky<Scalar> cholesky;
  };
  WarmStart<Scalar> start_;
  Factorisation factorisation_;
  detail::ActiveSetWorkspace<Scalar> loop_;
};

/// Kalker's active-set NORM solver on a fixed grid and material.
///
/// Keeps the influence table (shared by copies); the state of a sequence of problems lives
/// in a NormWorkspace: `solve(h, loading, workspace)` starts from its contact set and reuses
/// its factorisation while the set is unchanged. The answer does not depend on the start.
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
class NormSolver : public detail::SolverBase<NormSolver<Scalar>, NormWorkspace<Scalar>, Scalar> {
 public:
  using Index = Eigen::Index;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Options = ActiveSetOptions<Scalar>;
  using Workspace = NormWorkspace<Scalar>;
  using detail::SolverBase<NormSolver, Workspace, Scalar>::solve;

  /// @throws fastnorm::invalid_argument for invalid options
  NormSolver(const Grid<Scalar>& grid, const Material<Scalar>& material, Options options = {})
      : influence_(std::make_shared<const InfluenceTable<Scalar>>(grid, material)), options_(options) {
    options_.validate();
  }

  const Grid<Scalar>& grid() const { return influence_->grid(); }
  const InfluenceTable<Scalar>& influence() const { return *influence_; }
  const Options& options() const { return options_; }

  /// Solves the Signorini problem g = h − δ + C p ≥ 0, p ≥ 0, g·p = 0 from the workspace's
  /// starting set (Kalker's start if empty) and leaves the contact set there.
  /// @param undeformed_distance h on every element (m, + = gap), grid.size() values
  /// @param loading approach control (δ = 0) or force control (δ found from Fn)
  /// @throws fastnorm::invalid_argument for wrong sizes, non-finite h, a bad Fn or a bad
  ///         starting set
  Solution<Scalar> solve(const Eigen::Ref<const Vector>& undeformed_distance, const Loading<Scalar>& loading,
                         Workspace& workspace) const {
    workspace.start_.check(grid().size());
    if (workspace.factorisation_.solver != id_) {
      workspace.factorisation_.valid = false;
      workspace.factorisation_.solver = id_;
      workspace.loop_.start_on_grid(static_cast<std::size_t>(grid().size()));
    }
    DenseSetSolver set_solver{*influence_, workspace.factorisation_};
    Solution<Scalar> solution = detail::solve_active_set(*influence_, undeformed_distance, loading, options_,
                                                         set_solver, workspace.loop_, workspace.start_);
    // A cut solve goes on from the set its loop would have solved next (docs/wheel-rail.md §9).
    if (solution.stopped_early()) {
      workspace.start_.set_contact_set(workspace.loop_.next_set);
    } else {
      workspace.start_.remember_set(solution);
    }
    return solution;
  }

  /// The normal stiffness dFn/dδ (N/m) of the discrete problem at the contact set of
  /// `solution`, the last solve in `workspace`: area · 1ᵀ C_II⁻¹ 1, by the Cholesky factor
  /// that solve left (docs/norm.md §4). 0 without contact.
  Scalar normal_stiffness(const Solution<Scalar>& solution, Workspace& workspace) const {
    FASTNORM_CHECK(solution.in_contact.size() == grid().size(), "NormSolver::normal_stiffness: solution of another grid");
    DenseSetSolver set_solver{*influence_, workspace.factorisation_};
    return detail::set_stiffness(set_solver, solution, workspace.loop_, grid().element_area());
  }

 private:
  /// Step 2 of NORM: C_II p = rhs with Eigen's Cholesky of the dense block, in storage
  /// reused from one set to the next.
  struct DenseSetSolver {
    static constexpr bool exact_on_set = true;
    const InfluenceTable<Scalar>& influence;
    typename Workspace::Factorisation& factorisation;
    bool solve(const std::vector<Index>& active, Eigen::Ref<Matrix> columns) {
      if (!factorisation.valid || active != factorisation.set) {
        factorisation.set = active;
        factorisation.cholesky.resize(static_cast<Index>(active.size()));
        influence.dense_block(active, active, factorisation.cholesky.matrix());
        factorisation.valid = factorisation.cholesky.factorise();
        if (!factorisation.valid) return false;
      }
      factorisation.cholesky.solve_in_place(columns);
      return true;
    }
    void displacement(const std::vector<Index>& targets, const std::vector<Index>& active,
                      const Eigen::Ref<const Vector>& pressure, Eigen::Ref<Vector> result) const {
      influence.displacement(targets, active, pressure, result);
    }
  };

  std::shared_ptr<const InfluenceTable<Scalar>> influence_;
  Options options_;
  std::uint64_t id_ = detail::new_object_id();
};

}  // namespace fastnorm
