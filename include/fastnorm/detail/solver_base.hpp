#pragma once
/// @file detail/solver_base.hpp
/// The calls every solver offers on top of the one that does the work (docs/architecture.md
/// §2). A solver `Derived` provides
///
///     Solution<Scalar> solve(h, loading, Workspace& workspace) const;
///
/// which starts from `workspace.start()` and leaves there what the next solve starts from;
/// this base adds, written once for all solvers:
///
/// - `solve(h, loading) const`: a cold solve, safe to call from several threads at once
///   (each call borrows a workspace of its own from a pool, cleared first);
/// - `solve_next(h, loading)`: the next problem of a sequence, in the solver's own workspace;
/// - `reset()`: the next solve_next starts cold;
/// - `workspace()`: that workspace, e.g. to set its starting contact set.
///
/// Copying a solver copies its sequence workspace (the copy goes on from the same point,
/// independently) and shares the h-independent tables, which never change; the pool of
/// the copy starts empty.

#include <Eigen/Core>
#include "fastnorm/detail/object_id.hpp"
#include "fastnorm/detail/workspace_pool.hpp"
#include "fastnorm/solution.hpp"

namespace fastnorm {
namespace detail {

template <typename Derived, typename Workspace, typename Scalar>
class SolverBase {
 public:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  /// A cold solve: the answer does not depend on anything solved before.
  /// @param undeformed_distance h on every element (m, + = gap), grid.size() values
  /// @param loading approach control (δ = 0) or force control (δ found from Fn)
  /// @throws fastnorm::invalid_argument for wrong sizes or non-finite h
  Solution<Scalar> solve(const Eigen::Ref<const Vector>& undeformed_distance, const Loading<Scalar>& loading) const {
    auto workspace = pool_.take();
    workspace->forget();
    return derived().solve(undeformed_distance, loading, *workspace);
  }

  /// The next problem of a sequence: starts from where the previous solve_next (or whatever
  /// was set in workspace()) left off; cold on the first call and after reset().
  Solution<Scalar> solve_next(const Eigen::Ref<const Vector>& undeformed_distance, const Loading<Scalar>& loading) {
    return derived().solve(undeformed_distance, loading, sequence_);
  }

  /// The next solve_next starts cold (storage is kept).
  void reset() { sequence_.forget(); }

  /// The workspace of solve_next.
  Workspace& workspace() { return sequence_; }
  const Workspace& workspace() const { return sequence_; }

 private:
  const Derived& derived() const { return static_cast<const Derived&>(*this); }

  Workspace sequence_;
  mutable WorkspacePool<Workspace> pool_;
};

}  // namespace detail
}  // namespace fastnorm
