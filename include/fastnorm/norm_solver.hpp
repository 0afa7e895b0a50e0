#pragma once
/// @file norm_solver.hpp
/// Kalker's NORM: the active-set solver for the normal contact problem, approach and
/// force control, with a dense Cholesky factorisation of the active block. This is the
/// reference path every faster solver is tested against (docs/design.md §3, docs/norm.md).

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "fastnorm/active_set.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/in_place_cholesky.hpp"
#include "fastnorm/influence.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/solution.hpp"
#include "fastnorm/workspace_pool.hpp"

namespace fastnorm {

/// Kalker's active-set NORM solver on a fixed grid and material.
///
/// Keeps the influence table, so many problems on the same grid share it; `solve_next`
/// also keeps the last contact set and its factorisation for a sequence of problems.
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
  using Options = ActiveSetOptions<Scalar>;

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
    auto workspace = cold_workspaces_->take();  // its storage, not its factorisation
    workspace->factorisation.valid = false;
    DenseSetSolver set_solver{influence_, workspace->factorisation};
    return detail::solve_active_set(influence_, undeformed_distance, loading, options_, set_solver,
                                    workspace->loop);
  }

  /// As solve, for the next problem of a sequence on this grid: starts from the contact set
  /// of the previous solve_next (cold on the first call and after reset()) and reuses its
  /// factorisation while the set is unchanged. The answer is solve's (docs/performance.md §4).
  Solution<Scalar> solve_next(const Eigen::Ref<const Vector>& undeformed_distance, const Loading<Scalar>& loading) {
    DenseSetSolver set_solver{influence_, memory_};
    Solution<Scalar> solution = detail::solve_active_set(influence_, undeformed_distance, loading, options_,
                                                         set_solver, workspace_, last_set_);
    detail::contact_set(solution, last_set_);
    return solution;
  }

  /// Forgets the previous contact set and factorisation: the next solve_next starts cold.
  void reset() {
    last_set_.clear();
    memory_.valid = false;
  }

 private:
  /// The Cholesky factor of C_II for the set I last solved (valid after a solve).
  struct Factorisation {
    std::vector<Index> set;
    bool valid = false;
    detail::InPlaceCholesky<Scalar> cholesky;
  };

  /// Step 2 of NORM: C_II p = rhs with Eigen's Cholesky of the dense block, in storage
  /// reused from one set to the next.
  struct DenseSetSolver {
    const InfluenceTable<Scalar>& influence;
    Factorisation& factorisation;
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

  struct ColdWorkspace {
    Factorisation factorisation;
    detail::ActiveSetWorkspace<Scalar> loop;
  };

  InfluenceTable<Scalar> influence_;
  Options options_;
  // Workspaces of solve (one per concurrent call), shared by copies of the solver.
  std::shared_ptr<detail::WorkspacePool<ColdWorkspace>> cold_workspaces_ =
      std::make_shared<detail::WorkspacePool<ColdWorkspace>>();
  // The sequence of solve_next.
  std::vector<Index> last_set_;
  Factorisation memory_;
  detail::ActiveSetWorkspace<Scalar> workspace_;
};

}  // namespace fastnorm
