#pragma once
/// @file tangential_problem.hpp
/// What every tangential solver of fastnorm takes and gives (docs/tangential.md §5): the
/// creepages, the rolling direction and the solution with its creep forces, and the pieces
/// of a solve they share (the input's checks, the rigid slip's spin shift, the sums).

#include <Eigen/Core>
#include <cmath>
#include <string>

#include "fastnorm/error.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/solution.hpp"

namespace fastnorm {

/// Creepages of body 1 (the rail) against body 2 (the wheel), CONTACT's definition: the
/// rigid slip at (x, y) is w = (ξ − φ·(y − y₀), η + φ·(x − x₀)) (docs/tangential.md §5).
template <typename Scalar = double>
struct Creepage {
  Scalar longitudinal = 0;    ///< ξ (dimensionless)
  Scalar lateral = 0;         ///< η (dimensionless)
  Scalar spin = 0;            ///< φ (rad/m)
  Scalar spin_centre_x = 0;   ///< x₀ (m), in the grid's coordinates
  Scalar spin_centre_y = 0;   ///< y₀ (m)
};

/// Which way the contact moves over the bodies' surfaces: material enters the contact at
/// its leading edge, on the side the contact moves to (docs/tangential.md §5).
enum class RollingDirection {
  positive_x,  ///< leading edge at +x (CONTACT's χ = 0)
  negative_x,  ///< leading edge at −x (χ = π)
};

/// An element's state in a tangential solution.
enum class TractionState : signed char { exterior = 0, adhesion = 1, slip = 2 };

/// The answer of a tangential solve (the exact path's SteadyRollingSolver or the simplified
/// theory's solve_fastsim). Tractions and forces act on body 1 (the rail), SI.
template <typename Scalar = double>
struct TangentialSolution {
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  Status status = Status::not_solved;
  std::string message;
  Vector traction_x, traction_y;                               ///< Pa, per grid element
  Eigen::Matrix<TractionState, Eigen::Dynamic, 1> state;       ///< per grid element
  Vector slip_x, slip_y;     ///< the slip s = w − ∂u/∂x (dimensionless, per element; 0 in adhesion)
  Scalar force_x = 0, force_y = 0;  ///< N: Σ dA p
  Scalar spin_moment = 0;           ///< N·m: Σ dA (x p_y − y p_x) about the grid's origin
  Eigen::Index adhesion_elements = 0, slip_elements = 0;
  /// The frictional power per unit rolling speed, Σ dA |p||s| over the slip area (N); times
  /// the rolling speed V (m/s) it is the power the friction dissipates (W).
  Scalar frictional_power_per_speed = 0;
  int sweeps = 0;       ///< of the elements from the leading edge (1 for the simplified theory)
  Scalar residual = 0;  ///< the largest traction change of the last sweep / (μ·max p_n)
  bool ok() const { return status == Status::converged; }
};

namespace detail {

/// Throws, naming `who`, unless `normal` is a usable answer on `grid`, `friction` positive
/// and finite and the creepages finite.
template <typename Scalar>
void check_tangential_input(const Grid<Scalar>& grid, const Solution<Scalar>& normal, Scalar friction,
                            const Creepage<Scalar>& creepage, const std::string& who) {
  FASTNORM_CHECK(normal.pressure.size() == grid.size() && normal.in_contact.size() == grid.size(),
                 describe(who + ": normal must be a solution on this grid (elements)", normal.pressure.size()));
  FASTNORM_CHECK(normal.ok() || normal.status == Status::no_contact,
                 who + ": normal has no usable answer (status " + to_string(normal.status) + ")");
  FASTNORM_CHECK(std::isfinite(friction) && friction > 0,
                 describe(who + ": friction must be positive and finite", friction));
  FASTNORM_CHECK(std::isfinite(creepage.longitudinal) && std::isfinite(creepage.lateral) && std::isfinite(creepage.spin) &&
                     std::isfinite(creepage.spin_centre_x) && std::isfinite(creepage.spin_centre_y),
                 who + ": creepage must be finite (longitudinal, lateral, spin, spin centre)");
}

/// Whether element k carries pressure, so that it takes part in the tangential problem.
template <typename Scalar>
bool carries_pressure(const Solution<Scalar>& normal, Eigen::Index k) {
  return normal.in_contact(k) && normal.pressure(k) > 0;
}

/// A solution of n elements, all exterior, every traction and slip zero.
template <typename Scalar>
TangentialSolution<Scalar> zero_answer(Eigen::Index n) {
  using Vector = typename TangentialSolution<Scalar>::Vector;
  TangentialSolution<Scalar> answer;
  answer.traction_x = Vector::Zero(n);
  answer.traction_y = Vector::Zero(n);
  answer.slip_x = Vector::Zero(n);
  answer.slip_y = Vector::Zero(n);
  answer.state = Eigen::Matrix<TractionState, Eigen::Dynamic, 1>::Constant(n, TractionState::exterior);
  return answer;
}

/// The answer when no element carries pressure: no traction, status no_contact.
template <typename Scalar>
TangentialSolution<Scalar> no_contact_answer(Eigen::Index n) {
  TangentialSolution<Scalar> answer = zero_answer<Scalar>(n);
  answer.status = Status::no_contact;
  answer.message = "no element carries pressure";
  return answer;
}

/// Where the spin term of w_y is evaluated: a sixth of an element from the element's centre
/// towards the leading edge, CONTACT's correction of the rolling step (docs/tangential.md §6).
template <typename Scalar>
Scalar spin_shift(const Grid<Scalar>& grid, RollingDirection direction) {
  return (direction == RollingDirection::positive_x ? Scalar(1) : Scalar(-1)) * grid.dx() / 6;
}

/// Fills the forces, the spin moment about the grid's origin, the element counts and the
/// frictional power of `answer` from its tractions, states and slips.
template <typename Scalar>
void sum_tangential(const Grid<Scalar>& grid, TangentialSolution<Scalar>& answer) {
  const Scalar area = grid.element_area();
  for (Eigen::Index k = 0; k < grid.size(); ++k) {
    if (answer.state(k) == TractionState::exterior) continue;
    const Scalar px = answer.traction_x(k), py = answer.traction_y(k);
    answer.force_x += area * px;
    answer.force_y += area * py;
    answer.spin_moment += area * (grid.x(grid.i_of(k)) * py - grid.y(grid.j_of(k)) * px);
    if (answer.state(k) == TractionState::adhesion) {
      ++answer.adhesion_elements;
    } else {
      ++answer.slip_elements;
      answer.frictional_power_per_speed += area * std::hypot(px, py) * std::hypot(answer.slip_x(k), answer.slip_y(k));
    }
  }
}

}  // namespace detail
}  // namespace fastnorm
