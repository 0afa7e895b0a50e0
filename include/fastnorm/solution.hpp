#pragma once
/// @file solution.hpp
/// How a normal problem is loaded, and what every solver returns.

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include "fastnorm/error.hpp"

namespace fastnorm {

/// How the bodies are pressed together (docs/design.md §1).
enum class Control {
  approach,  ///< h already contains the rigid approach; solve as it stands
  force,     ///< h_k = h0_k − δ with δ unknown and dx·dy·Σp = Fn given
};

/// The loading of one normal problem.
template <typename Scalar = double>
struct Loading {
  Control control = Control::approach;
  /// Total normal force Fn (N); used, and required > 0, in force control only.
  Scalar normal_force = 0;

  static Loading approach() { return Loading{Control::approach, Scalar(0)}; }
  /// @throws fastnorm::invalid_argument if Fn is not positive and finite
  static Loading force(Scalar normal_force) {
    FASTNORM_CHECK(std::isfinite(normal_force) && normal_force > 0,
                   detail::describe("loading: normal_force must be positive and finite (N)",
                                    normal_force));
    return Loading{Control::force, normal_force};
  }
};

/// How a solve ended. Bad input is not a status: it throws fastnorm::invalid_argument.
enum class Status {
  not_solved,       ///< a default-constructed Solution: no solver has filled it
  converged,        ///< the contact set is stable and the Signorini conditions hold
  no_contact,       ///< approach control with every gap positive: zero pressure
  iteration_limit,  ///< the active-set loop reached Options::max_iterations
  cycled,           ///< reduced bases only: no set satisfies both conditions in the basis; the
                    ///< last set whose pressures are all positive is returned (usable)
  numerical_issue,  ///< a factorisation failed (matrix not positive definite)
  budget_reached,   ///< a caller's iteration budget or cap (WarmStart::limit_iterations,
                    ///< cap_iterations) stopped the solve; the answer is its last iterate whose
                    ///< pressures were all positive (CG: its projected iterate), usable, with
                    ///< that iterate's residual, and the next solve from the same workspace
                    ///< goes on where it stopped
};

inline const char* to_string(Status status) {
  switch (status) {
    case Status::not_solved: return "not solved";
    case Status::converged: return "converged";
    case Status::no_contact: return "no contact";
    case Status::iteration_limit: return "iteration limit";
    case Status::cycled: return "cycled";
    case Status::numerical_issue: return "numerical issue";
    case Status::budget_reached: return "budget reached";
  }
  return "unknown";
}

/// The answer of a normal-contact solver on a grid.
template <typename Scalar = double>
struct Solution {
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Mask = Eigen::Array<bool, Eigen::Dynamic, 1>;

  Status status = Status::not_solved;
  /// Pressure on every element of the grid (Pa), ≥ 0; zero outside contact.
  Vector pressure;
  /// Elements in the final contact set.
  Mask in_contact;
  /// dx·dy·Σp (N).
  Scalar normal_force = 0;
  /// Rigid approach δ subtracted from the given h (m): found in force control; 0 in
  /// approach control, where h already contains it.
  Scalar approach = 0;
  /// Active-set iterations (linear solves), or conjugate-gradient iterations.
  int iterations = 0;
  /// How far the answer is from the Signorini conditions as the solver itself measured it,
  /// relative to the deepest interpenetration of the undeformed surfaces, approach − min h
  /// (docs/performance.md Eq. (P1)). CG: its complementarity error, max |g| where p > 0 and
  /// max(−g) where p = 0. Active-set solvers: the largest interpenetration −g of the last
  /// join check outside the set (their equations on the set are solved by a factorisation,
  /// exactly for NORM, in the Galerkin sense for a reduced basis). 0 with no contact.
  Scalar residual = 0;
  /// What happened, in words.
  std::string message;
  /// A contact element lies on the boundary of the grid: the contact may reach beyond the
  /// potential contact area, and then the answer is that of a truncated body (CONTACT
  /// warns alike). Make the grid larger.
  bool at_edge = false;

  Eigen::Index contact_count() const { return in_contact.count(); }
  /// Back to a default Solution on `elements` elements (zero pressures, no contact,
  /// not_solved), keeping the storage: how a solver reuses a recycled answer.
  void clear(Eigen::Index elements) {
    status = Status::not_solved;
    pressure.setZero(elements);
    in_contact.setConstant(elements, false);
    normal_force = approach = residual = 0;
    iterations = 0;
    message.clear();
    message.reserve(message_capacity);
    at_edge = false;
  }
  /// Room a cleared answer's message keeps: every fixed message of the solvers fits (the
  /// longest has 65 characters), so a recycled answer that meets a longer one than before
  /// does not allocate for it in a time step (docs/performance.md §8).
  static constexpr std::size_t message_capacity = 80;
  /// The pressures are a usable answer: converged, no contact, a resolved cycle, or the
  /// admissible iterate at which a caller's budget stopped the loop.
  bool ok() const {
    return status == Status::converged || status == Status::no_contact || status == Status::cycled ||
           status == Status::budget_reached;
  }
  /// The solve was stopped by an iteration limit and the next solve from its workspace
  /// continues it (iteration_limit: the solver's own max_iterations, or a budget that left
  /// no admissible iterate; budget_reached: a caller's budget).
  bool stopped_early() const { return status == Status::iteration_limit || status == Status::budget_reached; }
};

namespace detail {

/// What every solver does to its answer last (docs/validation.md §6): `at_edge` from the
/// contact set on an mx × my grid, and a usable answer checked for what a solver cannot
/// see go wrong — pressures finite and ≥ 0, Fn finite and dx·dy·Σp, δ finite, and in force
/// control the prescribed Fn met to √ε — or else marked `numerical_issue`. A modulus so
/// large (or h so deep) that the elastic displacements vanish below the precision of h
/// gives such an answer.
template <typename Scalar>
void check_answer(Solution<Scalar>& solution, Eigen::Index mx, Eigen::Index my, Scalar element_area,
                  const Loading<Scalar>& loading) {
  solution.at_edge = false;
  if (solution.in_contact.size() != mx * my) return;  // not filled: nothing to check
  for (Eigen::Index i = 0; i < mx && !solution.at_edge; ++i) {
    solution.at_edge = solution.in_contact(i) || solution.in_contact(i + mx * (my - 1));
  }
  for (Eigen::Index j = 0; j < my && !solution.at_edge; ++j) {
    solution.at_edge = solution.in_contact(mx * j) || solution.in_contact(mx - 1 + mx * j);
  }
  if (!solution.ok()) return;
  const Scalar tolerance = std::sqrt(std::numeric_limits<Scalar>::epsilon());
  const Scalar sum = element_area * solution.pressure.sum();
  const char* failed = nullptr;
  // p ≥ 0 fails for NaN too; +Inf makes the sum infinite: one pass besides the sum's.
  if (!(solution.pressure.array() >= Scalar(0)).all() || !std::isfinite(sum)) {
    failed = "pressures not finite or negative";
  } else if (!std::isfinite(solution.normal_force) || !std::isfinite(solution.approach)) {
    failed = "force or approach not finite";
  } else if (std::abs(solution.normal_force - sum) > tolerance * std::abs(sum)) {
    failed = "force is not the sum of the pressures";
  } else if (loading.control == Control::force &&
             !(std::abs(solution.normal_force - loading.normal_force) <= tolerance * loading.normal_force)) {
    failed = "the prescribed force is not met";
  }
  if (!failed) return;
  solution.status = Status::numerical_issue;
  solution.message = std::string("the answer fails its final check: ") + failed +
                     " (Fn " + std::to_string(static_cast<double>(solution.normal_force)) +
                     " N): elastic displacements below the precision of h (modulus too large?)";
}

}  // namespace detail
}  // namespace fastnorm
