#pragma once
/// @file detail/workspace_pool.hpp
/// Workspaces lent to the cold `solve(h, loading)` of a solver (solver_base.hpp): a call
/// that may run on several threads at once cannot use one member workspace, and a fresh one
/// per call pays the allocation (and for large systems the page faults) every call. The
/// pool hands each concurrent call its own and keeps them for later calls
/// (docs/performance.md §3). A copy of a pool is empty: workspaces are never shared.

#include <memory>
#include <mutex>
#include <vector>

namespace fastnorm {
namespace detail {

template <typename Workspace>
class WorkspacePool {
 public:
  WorkspacePool() = default;
  WorkspacePool(const WorkspacePool&) noexcept {}
  WorkspacePool& operator=(const WorkspacePool&) noexcept { return *this; }
  ~WorkspacePool() = default;

  /// A workspace for the duration of one call; back to the pool when it goes out of scope.
  class Lease {
   public:
    Lease(WorkspacePool& pool, std::unique_ptr<Workspace> workspace) : pool_(pool), workspace_(std::move(workspace)) {}
    Lease(const Lease&) = delete;
    Lease& operator=(const Lease&) = delete;
    ~Lease() { pool_.give_back(std::move(workspace_)); }
    Workspace& operator*() { return *workspace_; }
    Workspace* operator->() { return workspace_.get(); }

   private:
    WorkspacePool& pool_;
    std::unique_ptr<Workspace> workspace_;
  };

  Lease take() {
    std::unique_ptr<Workspace> workspace;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (!free_.empty()) {
        workspace = std::move(free_.back());
        free_.pop_back();
      }
    }
    if (!workspace) workspace = std::make_unique<Workspace>();
    return Lease(*this, std::move(workspace));
  }

 private:
  void give_back(std::unique_ptr<Workspace> workspace) noexcept {
    try {
      const std::lock_guard<std::mutex> lock(mutex_);
      free_.push_back(std::move(workspace));
    } catch (...) {  // out of memory for the list: the workspace is simply freed
    }
  }

  std::mutex mutex_;
  std::vector<std::unique_ptr<Workspace>> free_;
};

}  // namespace detail
}  // namespace fastnorm
