#pragma once
/// @file warm_start.hpp
/// Where the next solve of a workspace starts (docs/architecture.md §2).

#include <Eigen/Core>
#include <algorithm>
#include <string>
#include <vector>

#include "fastnorm/error.hpp"
#include "fastnorm/solution.hpp"

namespace fastnorm {

/// Where an iterative solve stops short of convergence, from its options' max_iterations
/// and its workspace's limits (WarmStart::stop).
struct IterationStop {
  int hard = 0;         ///< no solve takes more iterations
  int soft = 0;         ///< ≤ hard: an active-set solve may stop here at a settled iterate
  bool budget = false;  ///< a stop at an admissible iterate is a caller's (Status::budget_reached)
  /// A settled iterate, where an active-set solve past `soft` stops: all its pressures
  /// positive, and no element outside its set interpenetrating by more than this fraction of
  /// the deepest interpenetration (its join check's residual). Beyond it the answer would
  /// trail a moving contact by whole elements (docs/performance.md §8, "A cap that waits for
  /// a settled iterate").
  static constexpr double settled_residual = 1e-2;
};

/// The starting state a workspace hands to its next solve: a contact set and, where the
/// solver that last used it works with them (CG), the pressures it ended with.
///
/// A solver fills it after each solve with what it uses to start the next one (NORM its
/// contact set, CG its pressures and contact set; the reduced solvers leave it as it was,
/// because their answer depends on the path of the active set: docs/method.md §3). After a
/// solve stopped by its iteration limit, NORM and the reduced solvers leave the set their
/// active-set loop would have solved next, and CG its last iterate, so that the next solve
/// continues the iteration. A
/// caller may set it, e.g. to the previous contact set shifted to a new grid; the next
/// solve checks it against its grid.
template <typename Scalar = double>
class WarmStart {
 public:
  using Index = Eigen::Index;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  /// The contact set the next solve starts from: sorted element numbers k = i + mx·j.
  /// Empty: a cold start.
  const std::vector<Index>& contact_set() const { return contact_set_; }

  /// Starts the next solve from `contact_set` (sorted, each element once, each < grid.size()
  /// of the solver that uses it: checked there). Forgets any pressures. Copied into the
  /// storage the start already has (no allocation once it is large enough).
  void set_contact_set(const std::vector<Index>& contact_set) {
    contact_set_.assign(contact_set.begin(), contact_set.end());
    has_pressure_ = false;
  }

  /// Pressures (Pa, one per element) the last solve ended with, if its solver keeps them.
  bool has_pressure() const { return has_pressure_; }
  const Vector& pressure() const { return pressure_; }

  /// The most iterations each next solve may take, below its options' max_iterations: a
  /// caller's budget (a time step's, WheelsetContact::set_iteration_budget). A solve that
  /// reaches it ends with Status::budget_reached at its last admissible iterate (every
  /// pressure positive; for CG its projected iterate), or with Status::iteration_limit where
  /// there is none, and the next solve goes on where it stopped. 0: the options' alone.
  /// clear() keeps it.
  int iteration_limit() const { return iteration_limit_; }
  /// @throws fastnorm::invalid_argument for a negative limit
  void limit_iterations(int limit) {
    FASTNORM_CHECK(limit >= 0, detail::describe("warm start: iteration limit must be >= 0", limit));
    iteration_limit_ = limit;
  }
  /// A softer bound below the limit (a time loop's cap per solve,
  /// WheelsetContactOptions::warm_solve_iterations): an active-set solve stops after `cap`
  /// iterations at the first settled iterate (IterationStop::settled_residual: its
  /// pressures all positive, its gaps violated by at most a hundredth of the deepest
  /// interpenetration), Status::budget_reached; until one comes it goes on (within the
  /// limit and max_iterations), so that the answer is usable and does not trail a moving
  /// contact. CG, whose every iterate is admissible, stops at the cap. 0: none. clear()
  /// keeps it.
  int iteration_cap() const { return iteration_cap_; }
  /// @throws fastnorm::invalid_argument for a negative cap
  void cap_iterations(int cap) {
    FASTNORM_CHECK(cap >= 0, detail::describe("warm start: iteration cap must be >= 0", cap));
    iteration_cap_ = cap;
  }
  /// The stop of the next solve of options with `max_iterations` (iteration_limit, iteration_cap).
  IterationStop stop(int max_iterations) const {
    IterationStop stop;
    const bool limit_binds = iteration_limit_ > 0 && iteration_limit_ <= max_iterations;
    stop.hard = limit_binds ? iteration_limit_ : max_iterations;
    stop.soft = iteration_cap_ > 0 ? std::min(iteration_cap_, stop.hard) : stop.hard;
    stop.budget = limit_binds || (iteration_cap_ > 0 && iteration_cap_ <= max_iterations);
    return stop;
  }

  /// Storage for a contact set of up to `elements` elements (a grid's size), so that
  /// setting or remembering one never allocates.
  void reserve(std::size_t elements) { contact_set_.reserve(elements); }

  /// Nothing to start from: the next solve is cold. Keeps the storage.
  void clear() {
    contact_set_.clear();
    has_pressure_ = false;
  }

  /// The contact set of a usable solution, or of one cut short by the iteration limit (its
  /// last iterate, from which the next solve goes on); empty otherwise; without pressures.
  void remember_set(const Solution<Scalar>& solution) {
    contact_set_.clear();
    has_pressure_ = false;
    if (!solution.ok() && !solution.stopped_early()) return;
    for (Index k = 0; k < solution.in_contact.size(); ++k) {
      if (solution.in_contact(k)) contact_set_.push_back(k);
    }
  }

  /// The contact set and the pressures of remember_set's solutions (nothing otherwise).
  void remember_pressure(const Solution<Scalar>& solution) {
    remember_set(solution);
    has_pressure_ = !contact_set_.empty();
    if (has_pressure_) pressure_ = solution.pressure;
  }

  /// @throws fastnorm::invalid_argument unless the contact set is sorted, without repeats,
  ///         and within a grid of `element_count` elements
  void check(Index element_count) const {
    for (std::size_t n = 0; n < contact_set_.size(); ++n) {
      const Index k = contact_set_[n];
      FASTNORM_CHECK(k >= 0 && k < element_count,
                     detail::describe("warm start: contact_set[" + std::to_string(n) + "] must lie in [0, " +
                                          std::to_string(element_count) + ")",
                                      k));
      FASTNORM_CHECK(n == 0 || contact_set_[n - 1] < k,
                     detail::describe("warm start: contact_set must be sorted without repeats; contact_set[" +
                                          std::to_string(n) + "]",
                                      k));
    }
    FASTNORM_CHECK(!has_pressure_ || pressure_.size() == element_count,
                   detail::describe("warm start: pressure must have one value per element", pressure_.size()));
  }

 private:
  std::vector<Index> contact_set_;
  Vector pressure_;
  bool has_pressure_ = false;
  int iteration_limit_ = 0;
  int iteration_cap_ = 0;
};

}  // namespace fastnorm
