#pragma once
/// @file fastsim.hpp
/// Kalker's simplified theory of rolling contact (FASTSIM) on a normal solution: each
/// element's displacement is its traction times a flexibility, so that steady rolling is
/// one sweep along every row from the leading edge, the traction capped at μ p_n element by
/// element (docs/tangential.md §9). The baseline of the fast tangential path: microseconds,
/// against the exact path's SteadyRollingSolver.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>

#include "fastnorm/constants.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/kalker_coefficients.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/solution.hpp"
#include "fastnorm/tangential_problem.hpp"

namespace fastnorm {

/// The flexibilities of the simplified theory (m/Pa): u = L p, with L1 for the longitudinal
/// creepage, L2 for the lateral one and L3 for both terms of the spin (docs/tangential.md
/// Eq. (T11)).
template <typename Scalar = double>
struct Flexibility {
  Scalar longitudinal = 0;  ///< L1
  Scalar lateral = 0;       ///< L2
  Scalar spin = 0;          ///< L3
};

/// The semi-axes (m) of an ellipse: a along the rolling direction x, b lateral.
template <typename Scalar = double>
struct Ellipse {
  Scalar a = 0, b = 0;
};

namespace detail {

/// (T10) for an ellipse, the combined shear modulus and Kalker's coefficients there.
template <typename Scalar>
Flexibility<Scalar> flexibility_of(const Ellipse<Scalar>& ellipse, Scalar shear_modulus,
                                   const KalkerCoefficients<Scalar>& coefficients) {
  const Scalar c = std::sqrt(ellipse.a * ellipse.b);
  return {8 * ellipse.a / (3 * shear_modulus * coefficients.c11), 8 * ellipse.a / (3 * shear_modulus * coefficients.c22),
          pi<Scalar> * ellipse.a * ellipse.a / (4 * shear_modulus * c * coefficients.c23)};
}

/// The ellipse of area `area` whose ratio a/b is `length` (along x) over `width`.
template <typename Scalar>
Ellipse<Scalar> ellipse_of_extent(Scalar area, Scalar length, Scalar width) {
  const Scalar ratio = length / width;
  return {std::sqrt(area * ratio / pi<Scalar>), std::sqrt(area / (pi<Scalar> * ratio))};
}

}  // namespace detail

/// Kalker's flexibilities for an ellipse (docs/tangential.md Eq. (T10)), those with which
/// the simplified theory gives the linear theory's forces (T9) in full adhesion:
/// L1 = 8a/(3 G C11), L2 = 8a/(3 G C22), L3 = π a²/(4 G c C23), c = √(ab), G and ν the
/// combined constants of `material`.
/// @throws fastnorm::invalid_argument for semi-axes that are not positive and finite
template <typename Scalar>
Flexibility<Scalar> kalker_flexibility(const Ellipse<Scalar>& ellipse, const Material<Scalar>& material) {
  check_positive(ellipse.a, "kalker_flexibility: ellipse.a (m)");
  check_positive(ellipse.b, "kalker_flexibility: ellipse.b (m)");
  return detail::flexibility_of(ellipse, material.combined_shear_modulus(),
                                kalker_coefficients(ellipse.a / ellipse.b, material.combined_poisson_ratio()));
}

/// The ellipse equivalent to the contact area of `normal` on `grid`: the same area, and the
/// ratio a/b of the area's length along x to its width (the extents of its elements).
/// @throws fastnorm::invalid_argument for a normal solution of another grid or without an
///         element carrying pressure
template <typename Scalar>
Ellipse<Scalar> equivalent_ellipse(const Grid<Scalar>& grid, const Solution<Scalar>& normal) {
  FASTNORM_CHECK(normal.pressure.size() == grid.size() && normal.in_contact.size() == grid.size(),
                 describe("equivalent_ellipse: normal must be a solution on this grid (elements)", normal.pressure.size()));
  Eigen::Index count = 0, first_i = grid.mx(), last_i = -1, first_j = grid.my(), last_j = -1;
  for (Eigen::Index j = 0; j < grid.my(); ++j) {
    for (Eigen::Index i = 0; i < grid.mx(); ++i) {
      if (!detail::carries_pressure(normal, grid.index(i, j))) continue;
      ++count;
      first_i = std::min(first_i, i), last_i = std::max(last_i, i);
      first_j = std::min(first_j, j), last_j = std::max(last_j, j);
    }
  }
  FASTNORM_CHECK(count > 0, "equivalent_ellipse: no element of normal carries pressure");
  return detail::ellipse_of_extent(static_cast<Scalar>(count) * grid.element_area(),
                                   static_cast<Scalar>(last_i - first_i + 1) * grid.dx(),
                                   static_cast<Scalar>(last_j - first_j + 1) * grid.dy());
}

/// The sensitivities of FASTSIM's creep forces to the creepages: rows Fx, Fy (N) and the
/// spin moment Mz (N·m), columns ξ, η (dimensionless) and φ (rad/m), at fixed pressure and
/// spin centre (docs/tangential.md Eq. (T12)).
template <typename Scalar>
using CreepJacobian = Eigen::Matrix<Scalar, 3, 3>;

/// Steady rolling by Kalker's simplified theory (FASTSIM) on the normal solution `normal` of
/// `grid`, with Coulomb friction `friction` and the creepages `creepage`
/// (docs/tangential.md §9). Along each row from the leading edge, every element carrying
/// pressure takes its upstream neighbour's traction minus dx times the rigid slip over
/// the flexibility,
///
///     p_x = p_x⁺ − dx (ξ/L1 − φ (y − y₀)/L3),   p_y = p_y⁺ − dx (η/L2 + φ (x ± dx/6 − x₀)/L3)   (T11)
///
/// (p⁺ = 0 upstream of the contact; the spin term of w_y a sixth of an element towards the
/// leading edge as in the exact path), scaled back onto μ p_n where it exceeds it (slip,
/// with s = (L1 Δp_x, L2 Δp_y)/dx, Δp the traction minus its unscaled value). This is
/// CONTACT's FASTSIM: with its flexibilities and traction bound it gives CONTACT's forces,
/// areas and frictional power to its printed digits. Forces on body 1, as the exact path's.
/// @throws fastnorm::invalid_argument as SteadyRollingSolver::solve, or for flexibilities
///         that are not positive and finite
template <typename Scalar>
TangentialSolution<Scalar> solve_fastsim(const Grid<Scalar>& grid, const Solution<Scalar>& normal, Scalar friction,
                                         const Creepage<Scalar>& creepage, const Flexibility<Scalar>& flexibility,
                                         RollingDirection direction = RollingDirection::positive_x) {
  TangentialSolution<Scalar> answer;
  solve_fastsim(grid, normal, friction, creepage, flexibility, direction, answer);
  return answer;
}

/// The same into `answer`, whose storage it reuses: no allocation once `answer` has held a
/// solution of the grid's size (the time loop's form); with `jacobian`, the sensitivities
/// of the forces to the creepages as well, differentiated through the sweep (T12).
/// @throws fastnorm::invalid_argument as the other overloads
template <typename Scalar>
void solve_fastsim(const Grid<Scalar>& grid, const Solution<Scalar>& normal, Scalar friction,
                   const Creepage<Scalar>& creepage, const Flexibility<Scalar>& flexibility, RollingDirection direction,
                   TangentialSolution<Scalar>& answer, CreepJacobian<Scalar>* jacobian = nullptr) {
  detail::check_tangential_input(grid, normal, friction, creepage, "solve_fastsim");
  check_positive(flexibility.longitudinal, "solve_fastsim: flexibility.longitudinal (m/Pa)");
  check_positive(flexibility.lateral, "solve_fastsim: flexibility.lateral (m/Pa)");
  check_positive(flexibility.spin, "solve_fastsim: flexibility.spin (m/Pa)");
  const Eigen::Index mx = grid.mx(), my = grid.my();
  detail::reset_answer(answer, grid.size());
  const bool positive = direction == RollingDirection::positive_x;
  const Scalar dx = grid.dx(), area = grid.element_area(), shift = detail::spin_shift(grid, direction);
  // The traction rates along x, −dp/dx in the rolling direction's sense: (T11) without dx.
  const Scalar rate_x0 = creepage.longitudinal / flexibility.longitudinal, rate_y0 = creepage.lateral / flexibility.lateral;
  const Scalar spin_rate = creepage.spin / flexibility.spin;
  using Derivative = Eigen::Matrix<Scalar, 2, 3>;  // d(p_x, p_y)/d(ξ, η, φ)
  if (jacobian) jacobian->setZero();
  bool loaded = false;
  for (Eigen::Index j = 0; j < my; ++j) {
    const Scalar rate_x = rate_x0 - spin_rate * (grid.y(j) - creepage.spin_centre_y);
    Scalar px = 0, py = 0;  // the upstream neighbour's traction
    Derivative dp = Derivative::Zero();  // and its derivative
    for (Eigen::Index step = 0; step < mx; ++step) {
      const Eigen::Index i = positive ? mx - 1 - step : step;
      const Eigen::Index k = grid.index(i, j);
      if (!detail::carries_pressure(normal, k)) {
        px = py = 0;
        dp.setZero();
        continue;
      }
      loaded = true;
      const Scalar rate_y = rate_y0 + spin_rate * (grid.x(i) + shift - creepage.spin_centre_x);
      const Scalar trial_x = px - dx * rate_x, trial_y = py - dx * rate_y;
      // Compared squared, √ only where it slips (std::hypot's overflow guard is not needed).
      const Scalar bound = friction * normal.pressure(k), size_squared = trial_x * trial_x + trial_y * trial_y;
      const bool adheres = size_squared <= bound * bound;
      const Scalar size = adheres ? Scalar(0) : std::sqrt(size_squared);
      if (jacobian) {  // (T12): d(trial) = dp⁺ − dx·d(rate); in slip, projected across the trial
        Derivative d_trial = dp;
        d_trial(0, 0) -= dx / flexibility.longitudinal;
        d_trial(0, 2) += dx * (grid.y(j) - creepage.spin_centre_y) / flexibility.spin;
        d_trial(1, 1) -= dx / flexibility.lateral;
        d_trial(1, 2) -= dx * (grid.x(i) + shift - creepage.spin_centre_x) / flexibility.spin;
        if (adheres) {
          dp = d_trial;
        } else {
          const Eigen::Matrix<Scalar, 2, 1> direction_of_trial(trial_x / size, trial_y / size);
          dp = (bound / size) *
               (Eigen::Matrix<Scalar, 2, 2>::Identity() - direction_of_trial * direction_of_trial.transpose()) * d_trial;
        }
        jacobian->row(0) += area * dp.row(0);
        jacobian->row(1) += area * dp.row(1);
        jacobian->row(2) += area * (grid.x(i) * dp.row(1) - grid.y(j) * dp.row(0));
      }
      if (adheres) {
        px = trial_x, py = trial_y;
        answer.state(k) = TractionState::adhesion;
      } else {
        px = trial_x * bound / size, py = trial_y * bound / size;
        answer.state(k) = TractionState::slip;
        answer.slip_x(k) = flexibility.longitudinal * (px - trial_x) / dx;
        answer.slip_y(k) = flexibility.lateral * (py - trial_y) / dx;
      }
      answer.traction_x(k) = px;
      answer.traction_y(k) = py;
      detail::add_element(answer, area, grid.x(i), grid.y(j), k);
    }
  }
  if (!loaded) return detail::mark_no_contact(answer);
  answer.sweeps = 1;
  answer.status = Status::converged;
  answer.message = "simplified theory (FASTSIM): one sweep";
}

/// FASTSIM with Kalker's flexibilities of the ellipse equivalent to the contact area
/// (equivalent_ellipse, kalker_flexibility).
/// @throws fastnorm::invalid_argument as the other overload
template <typename Scalar>
TangentialSolution<Scalar> solve_fastsim(const Grid<Scalar>& grid, const Material<Scalar>& material,
                                         const Solution<Scalar>& normal, Scalar friction,
                                         const Creepage<Scalar>& creepage,
                                         RollingDirection direction = RollingDirection::positive_x) {
  detail::check_tangential_input(grid, normal, friction, creepage, "solve_fastsim");
  bool loaded = false;
  for (Eigen::Index k = 0; k < grid.size() && !loaded; ++k) loaded = detail::carries_pressure(normal, k);
  if (!loaded) return detail::no_contact_answer<Scalar>(grid.size());
  return solve_fastsim(grid, normal, friction, creepage, kalker_flexibility(equivalent_ellipse(grid, normal), material),
                       direction);
}

}  // namespace fastnorm
