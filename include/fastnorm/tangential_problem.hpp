#pragma once
/// @file tangential_problem.hpp
/// What every tangential solver of fastnorm takes and gives (docs/tangential.md §5): the
/// creepages, the rolling direction and the solution with its creep forces, and the pieces
/// of a solve they share (the input's checks, the rigid slip's spin shift, the sums).

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <string_view>

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
  /// The last sweep's traction changes by the exact path's stopping rule (TangentialStop):
  /// the largest / (μ·max p_n), or their root mean square / the tractions', times ρ/1.5
  /// once a restart has raised the relaxation ρ (docs/tangential.md §7); 0 for the
  /// simplified theory.
  Scalar residual = 0;
  bool ok() const { return status == Status::converged; }
};

namespace detail {

/// Throws, naming `who`, unless `normal` is a usable answer on `grid`, `friction` positive
/// and finite and the creepages finite.
template <typename Scalar>
void check_tangential_input(const Grid<Scalar>& grid, const Solution<Scalar>& normal, Scalar friction,
                            const Creepage<Scalar>& creepage, std::string_view who) {
  FASTNORM_CHECK(normal.pressure.size() == grid.size() && normal.in_contact.size() == grid.size(),
                 describe(std::string(who) + ": normal must be a solution on this grid (elements)", normal.pressure.size()));
  FASTNORM_CHECK(normal.ok() || normal.status == Status::no_contact,
                 std::string(who) + ": normal has no usable answer (status " + to_string(normal.status) + ")");
  FASTNORM_CHECK(std::isfinite(friction) && friction > 0,
                 describe(std::string(who) + ": friction must be positive and finite", friction));
  FASTNORM_CHECK(std::isfinite(creepage.longitudinal) && std::isfinite(creepage.lateral) && std::isfinite(creepage.spin) &&
                     std::isfinite(creepage.spin_centre_x) && std::isfinite(creepage.spin_centre_y),
                 std::string(who) + ": creepage must be finite (longitudinal, lateral, spin, spin centre)");
}

/// Whether element k carries pressure, so that it takes part in the tangential problem.
template <typename Scalar>
bool carries_pressure(const Solution<Scalar>& normal, Eigen::Index k) {
  return normal.in_contact(k) && normal.pressure(k) > 0;
}

/// `answer` made a solution of n elements, all exterior, every traction, slip, sum and count
/// zero, keeping its vectors' storage if they have n elements.
template <typename Scalar>
void reset_answer(TangentialSolution<Scalar>& answer, Eigen::Index n) {
  answer.traction_x.setZero(n);
  answer.traction_y.setZero(n);
  answer.slip_x.setZero(n);
  answer.slip_y.setZero(n);
  answer.state.setConstant(n, TractionState::exterior);
  answer.force_x = answer.force_y = answer.spin_moment = answer.frictional_power_per_speed = answer.residual = 0;
  answer.adhesion_elements = answer.slip_elements = 0;
  answer.sweeps = 0;
  answer.status = Status::not_solved;
  answer.message.clear();
}

/// A solution of n elements, all exterior, every traction and slip zero.
template <typename Scalar>
TangentialSolution<Scalar> zero_answer(Eigen::Index n) {
  TangentialSolution<Scalar> answer;
  reset_answer(answer, n);
  return answer;
}

/// Marks `answer` as having no element that carries pressure (status no_contact).
template <typename Scalar>
void mark_no_contact(TangentialSolution<Scalar>& answer) {
  answer.status = Status::no_contact;
  answer.message = "no element carries pressure";
}

/// The answer when no element carries pressure: no traction, status no_contact.
template <typename Scalar>
TangentialSolution<Scalar> no_contact_answer(Eigen::Index n) {
  TangentialSolution<Scalar> answer = zero_answer<Scalar>(n);
  mark_no_contact(answer);
  return answer;
}

/// Where the spin term of w_y is evaluated: a sixth of an element from the element's centre
/// towards the leading edge, CONTACT's correction of the rolling step (docs/tangential.md §6).
template <typename Scalar>
Scalar spin_shift(const Grid<Scalar>& grid, RollingDirection direction) {
  return (direction == RollingDirection::positive_x ? Scalar(1) : Scalar(-1)) * grid.dx() / 6;
}

/// Adds an element's traction at (x, y) to the answer's forces, spin moment about the grid's
/// origin and element counts, and, where it slips, `traction_times_slip` = |p||s| times its
/// area to the frictional power.
template <typename Scalar>
void add_element(TangentialSolution<Scalar>& answer, Scalar area, Scalar x, Scalar y, Eigen::Index k,
                 Scalar traction_times_slip) {
  const Scalar px = answer.traction_x(k), py = answer.traction_y(k);
  answer.force_x += area * px;
  answer.force_y += area * py;
  answer.spin_moment += area * (x * py - y * px);
  if (answer.state(k) == TractionState::adhesion) {
    ++answer.adhesion_elements;
  } else {
    ++answer.slip_elements;
    answer.frictional_power_per_speed += area * traction_times_slip;
  }
}

/// The same with |p||s| from the element's traction and slip, as √(|p|²|s|²) rather than
/// std::hypot (whose guard against overflow costs more than the whole sum; tractions and
/// slips are far from double's range).
template <typename Scalar>
void add_element(TangentialSolution<Scalar>& answer, Scalar area, Scalar x, Scalar y, Eigen::Index k) {
  const Scalar px = answer.traction_x(k), py = answer.traction_y(k), sx = answer.slip_x(k), sy = answer.slip_y(k);
  add_element(answer, area, x, y, k,
              answer.state(k) == TractionState::adhesion ? Scalar(0)
                                                          : std::sqrt((px * px + py * py) * (sx * sx + sy * sy)));
}

/// Fills the sums of add_element from every element in contact, row by row.
template <typename Scalar>
void sum_tangential(const Grid<Scalar>& grid, TangentialSolution<Scalar>& answer) {
  for (Eigen::Index j = 0; j < grid.my(); ++j) {
    for (Eigen::Index i = 0; i < grid.mx(); ++i) {
      const Eigen::Index k = grid.index(i, j);
      if (answer.state(k) != TractionState::exterior) add_element(answer, grid.element_area(), grid.x(i), grid.y(j), k);
    }
  }
}

}  // namespace detail
}  // namespace fastnorm
