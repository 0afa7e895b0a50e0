#pragma once
/// @file tangential_solver.hpp
/// Steady rolling with Coulomb friction on a normal solution: the tractions, adhesion and
/// slip areas and creep forces of a patch for given creepages, by Gauss–Seidel sweeps over
/// the elements from the leading edge (docs/tangential.md §5–7). The reference path of the
/// tangential problem, as NORM is of the normal one.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "fastnorm/detail/memory_check.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/solution.hpp"
#include "fastnorm/tangential_influence.hpp"
#include "fastnorm/tangential_problem.hpp"

namespace fastnorm {

template <typename Scalar = double>
struct TangentialOptions {
  /// The sweeps stop when no traction changed by more than tolerance · μ·max p_n in a sweep.
  Scalar tolerance = Scalar(1e-9);
  int max_sweeps = 2000;
  void validate() const {
    FASTNORM_CHECK(tolerance > 0 && tolerance < 1,
                   detail::describe("TangentialOptions: tolerance must lie in (0, 1)", tolerance));
    FASTNORM_CHECK(max_sweeps >= 1, detail::describe("TangentialOptions: max_sweeps must be >= 1", max_sweeps));
  }
};

namespace detail {

/// The steady-rolling operator, D(di, dj) = [C(di, dj) − C(di + e, dj)]/dx with e = +1
/// (leading edge at +x) or −1: the slip's elastic part, the discrete −∂u/∂x
/// = (u_I − u_upstream)/dx, at an element is Σ D(i − i', j − j') p(i', j')
/// (docs/tangential.md Eq. (T6)). Stored for every offset
/// |di| ≤ mx − 1, |dj| ≤ my − 1, column-major in di, so a change of the traction at one
/// element moves a whole row of the grid by a slice of each table column.
template <typename Scalar>
struct RollingOperator {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  Eigen::Index mx = 0, my = 0;
  Matrix xx, xy, yy;  // (2mx − 1) × (2my − 1): row mx − 1 + di, column my − 1 + dj

  RollingOperator(const TangentialInfluenceTable<Scalar>& influence, RollingDirection direction)
      : mx(influence.grid().mx()),
        my(checked_rows(influence.grid())),
        xx(2 * mx - 1, 2 * my - 1),
        xy(2 * mx - 1, 2 * my - 1),
        yy(2 * mx - 1, 2 * my - 1) {
    const Grid<Scalar>& grid = influence.grid();
    const Eigen::Index upstream = direction == RollingDirection::positive_x ? 1 : -1;
    // C from the table; one element past it (|di| = mx, read only by elements on the
    // upstream edge, which the solver refuses) by the closed form.
    auto at = [&](Eigen::Index di, Eigen::Index dj) {
      if (std::abs(di) < mx) return influence.at_offset(di, dj);
      return cerruti_coefficients<Scalar>(static_cast<Scalar>(di) * grid.dx(), static_cast<Scalar>(dj) * grid.dy(),
                                          grid.dx() / 2, grid.dy() / 2, influence.shear_modulus(),
                                          influence.poisson_ratio());
    };
    for (Eigen::Index dj = -(my - 1); dj <= my - 1; ++dj) {
      for (Eigen::Index di = -(mx - 1); di <= mx - 1; ++di) {
        const auto here = at(di, dj), there = at(di + upstream, dj);
        xx(mx - 1 + di, my - 1 + dj) = (here.xx - there.xx) / grid.dx();
        xy(mx - 1 + di, my - 1 + dj) = (here.xy - there.xy) / grid.dx();
        yy(mx - 1 + di, my - 1 + dj) = (here.yy - there.yy) / grid.dx();
      }
    }
  }

 private:
  /// my, once the three tables are known to fit the machine's memory.
  static Eigen::Index checked_rows(const Grid<Scalar>& grid) {
    check_memory(3 * (2 * static_cast<double>(grid.mx()) - 1) * (2 * static_cast<double>(grid.my()) - 1), sizeof(Scalar),
                 "SteadyRollingSolver: grid mx x my");
    return grid.my();
  }
};

/// One element's traction under Coulomb's law when its slip is s = r + (k_x p_x, k_y p_y)
/// (docs/tangential.md §7): adhesion p = −r/k if that is within the bound g (s = 0), else
/// slip p = −g s/|s|, i.e. p_c = −g r_c/(σ + g k_c) with σ = |s| the root of
/// Σ_c r_c²/(σ + g k_c)² = 1, convex and decreasing in σ, so that Newton's method from σ = 0
/// climbs to it monotonically.
template <typename Scalar>
struct ElementTraction {
  Scalar x, y;
  TractionState state;
};

template <typename Scalar>
ElementTraction<Scalar> coulomb_element(Scalar rx, Scalar ry, Scalar bound, Scalar kx, Scalar ky) {
  const Scalar adhesion_x = -rx / kx, adhesion_y = -ry / ky;
  if (adhesion_x * adhesion_x + adhesion_y * adhesion_y <= bound * bound) {
    return {adhesion_x, adhesion_y, TractionState::adhesion};
  }
  Scalar sigma = 0;
  for (int newton = 0; newton < 100; ++newton) {
    const Scalar ex = sigma + bound * kx, ey = sigma + bound * ky;
    const Scalar excess = rx * rx / (ex * ex) + ry * ry / (ey * ey) - 1;
    const Scalar derivative = -2 * (rx * rx / (ex * ex * ex) + ry * ry / (ey * ey * ey));
    const Scalar next = sigma - excess / derivative;
    if (!(next > sigma) || next - sigma <= std::numeric_limits<Scalar>::epsilon() * next) {
      sigma = std::max(sigma, next);
      break;
    }
    sigma = next;
  }
  return {-bound * rx / (sigma + bound * kx), -bound * ry / (sigma + bound * ky), TractionState::slip};
}

}  // namespace detail

/// Steady rolling with Coulomb friction on the patches of one grid: the solver keeps the
/// tangential influence table and the steady-rolling operator D of its grid and rolling
/// direction (both h-independent), and solves for any normal solution on that grid.
///
/// Discretisation (docs/tangential.md §6): in each contact element I the slip is
/// s_I = w_I + Σ_J D_IJ p_J (Eq. (T6)), with the spin term of w_y evaluated a sixth of an
/// element towards the leading edge as CONTACT does; in adhesion s_I = 0 and
/// |p_I| ≤ μ p_n,I, in slip p_I = −μ p_n,I s_I/|s_I|. Each sweep solves every element's
/// 2 × 2 problem with the others fixed, from the leading edge to the trailing one, and
/// updates the slips of the contact rows by the change (Gauss–Seidel with a relaxed local
/// coefficient, docs/tangential.md §7).
///
/// **Example**
/// @code
/// fastnorm::SteadyRollingSolver<> rolling(grid, material);
/// fastnorm::Creepage<> creepage;
/// creepage.longitudinal = 1e-3;
/// auto answer = rolling.solve(normal, 0.3, creepage);   // normal: NormSolver's solution on grid
/// double fx = answer.force_x;                            // N, on body 1
/// @endcode
template <typename Scalar = double>
class SteadyRollingSolver {
 public:
  using Index = Eigen::Index;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  /// @throws fastnorm::invalid_argument for invalid options
  SteadyRollingSolver(const Grid<Scalar>& grid, const Material<Scalar>& material,
                      RollingDirection direction = RollingDirection::positive_x, TangentialOptions<Scalar> options = {})
      : options_(validated(options)),
        direction_(direction),
        influence_(std::make_shared<const TangentialInfluenceTable<Scalar>>(grid, material)),
        rolling_(std::make_shared<const detail::RollingOperator<Scalar>>(*influence_, direction)) {}

  const Grid<Scalar>& grid() const { return influence_->grid(); }
  const TangentialInfluenceTable<Scalar>& influence() const { return *influence_; }
  RollingDirection direction() const { return direction_; }
  const TangentialOptions<Scalar>& options() const { return options_; }

  /// Steady rolling of the patch whose normal solution is `normal` (on this grid), with
  /// Coulomb friction `friction` (μ > 0) and the creepages `creepage`.
  /// @throws fastnorm::invalid_argument for a normal solution of another grid or without an
  ///         answer, a friction coefficient that is not positive and finite, non-finite
  ///         creepages, or a contact area that reaches the grid's upstream edge (the slip
  ///         there needs the displacement one element beyond it)
  TangentialSolution<Scalar> solve(const Solution<Scalar>& normal, Scalar friction,
                                   const Creepage<Scalar>& creepage) const {
    const Grid<Scalar>& grid = influence_->grid();
    const detail::RollingOperator<Scalar>& rolling = *rolling_;
    const Index mx = grid.mx(), my = grid.my(), n = grid.size();
    detail::check_tangential_input(grid, normal, friction, creepage, "SteadyRollingSolver::solve");
    const bool positive = direction_ == RollingDirection::positive_x;
    const Index upstream_column = positive ? mx - 1 : 0;

    TangentialSolution<Scalar> answer = detail::zero_answer<Scalar>(n);
    Vector bound = Vector::Zero(n);  // μ p_n
    for (Index k = 0; k < n; ++k) {
      if (!detail::carries_pressure(normal, k)) continue;
      FASTNORM_CHECK(grid.i_of(k) != upstream_column,
                     "SteadyRollingSolver::solve: the contact area reaches the grid's upstream edge (column " +
                         std::to_string(upstream_column) + "); extend the grid by an element there");
      bound(k) = friction * normal.pressure(k);
      answer.state(k) = TractionState::adhesion;
    }
    const Scalar scale = bound.maxCoeff();
    if (!(scale > 0)) return detail::no_contact_answer<Scalar>(n);

    // The rigid slip (T5), its spin term shifted by a sixth of an element as CONTACT's.
    const Scalar spin_shift = detail::spin_shift(grid, direction_);
    Vector rigid_x(n), rigid_y(n);
    for (Index k = 0; k < n; ++k) {
      const Scalar x = grid.x(grid.i_of(k)), y = grid.y(grid.j_of(k));
      rigid_x(k) = creepage.longitudinal - creepage.spin * (y - creepage.spin_centre_y);
      rigid_y(k) = creepage.lateral + creepage.spin * (x + spin_shift - creepage.spin_centre_x);
    }

    // The rows of the grid that hold contact, and the columns each spans: only there is the
    // slip read (docs/tangential.md §7).
    std::vector<Index> first_column(static_cast<std::size_t>(my), mx), last_column(static_cast<std::size_t>(my), -1);
    for (Index k = 0; k < n; ++k) {
      if (answer.state(k) == TractionState::exterior) continue;
      const auto j = static_cast<std::size_t>(grid.j_of(k));
      first_column[j] = std::min(first_column[j], grid.i_of(k));
      last_column[j] = std::max(last_column[j], grid.i_of(k));
    }
    // elastic = D p over the contact rows, kept up to date as tractions change.
    Vector elastic_x = Vector::Zero(n), elastic_y = Vector::Zero(n);
    auto add_change = [&](Index source, Scalar change_x, Scalar change_y) {
      const Index i = grid.i_of(source), j = grid.j_of(source);
      for (Index row = 0; row < my; ++row) {
        const Index first = first_column[static_cast<std::size_t>(row)], length = last_column[static_cast<std::size_t>(row)] - first + 1;
        if (length <= 0) continue;
        // D(i_t − i, row − j) for i_t = first … last: a slice of one column of each table.
        const Index column = my - 1 + row - j, offset = mx - 1 + first - i;
        elastic_x.segment(row * mx + first, length) += change_x * rolling.xx.col(column).segment(offset, length) +
                                                       change_y * rolling.xy.col(column).segment(offset, length);
        elastic_y.segment(row * mx + first, length) += change_x * rolling.xy.col(column).segment(offset, length) +
                                                       change_y * rolling.yy.col(column).segment(offset, length);
      }
    };
    // The local coefficient of an element's own traction: relaxation · C_II/dx, consistent at
    // the fixed point whatever its value; D's own diagonal, (C(0) − C(e))/dx, makes the
    // sweeps diverge (docs/tangential.md §7, measured), so does a relaxation below 3 on the
    // spin case of peer-tangential. A sweep whose change grows tenfold past the smallest one
    // met restarts the solve from zero tractions with a relaxation 1.5 times larger.
    const auto own = influence_->at_offset(0, 0);
    Scalar relaxation = 3;
    Scalar smallest_change = std::numeric_limits<Scalar>::infinity();
    answer.sweeps = 0;
    bool converged = false;
    while (answer.sweeps < options_.max_sweeps && !converged) {
      ++answer.sweeps;
      const Scalar local_x = relaxation * own.xx / grid.dx(), local_y = relaxation * own.yy / grid.dx();
      Scalar largest_change = 0;
      for (Index step = 0; step < mx; ++step) {
        const Index i = positive ? mx - 1 - step : step;  // from the leading edge
        for (Index j = 0; j < my; ++j) {
          const Index k = i + mx * j;
          if (answer.state(k) == TractionState::exterior) continue;
          // The slip is s = r + local·p, r the rest with this element's traction taken out.
          const Scalar px = answer.traction_x(k), py = answer.traction_y(k);
          const Scalar rx = rigid_x(k) + elastic_x(k) - local_x * px, ry = rigid_y(k) + elastic_y(k) - local_y * py;
          const auto local = detail::coulomb_element(rx, ry, bound(k), local_x, local_y);
          answer.state(k) = local.state;
          const Scalar change_x = local.x - px, change_y = local.y - py;
          if (change_x != 0 || change_y != 0) {
            answer.traction_x(k) = local.x;
            answer.traction_y(k) = local.y;
            add_change(k, change_x, change_y);
            largest_change = std::max(largest_change, std::max(std::abs(change_x), std::abs(change_y)));
          }
        }
      }
      answer.residual = largest_change / scale;
      converged = answer.residual <= options_.tolerance;
      smallest_change = std::min(smallest_change, largest_change);
      if (!converged && largest_change > 10 * smallest_change) {  // diverging: restart, more relaxed
        relaxation *= Scalar(1.5);
        smallest_change = std::numeric_limits<Scalar>::infinity();
        answer.traction_x.setZero();
        answer.traction_y.setZero();
        elastic_x.setZero();
        elastic_y.setZero();
      }
    }

    for (Index k = 0; k < n; ++k) {
      if (answer.state(k) != TractionState::slip) continue;
      answer.slip_x(k) = rigid_x(k) + elastic_x(k);
      answer.slip_y(k) = rigid_y(k) + elastic_y(k);
    }
    detail::sum_tangential(grid, answer);
    if (!converged) {
      answer.status = Status::iteration_limit;
      answer.message = "tractions still changing after " + std::to_string(options_.max_sweeps) + " sweeps";
    } else {
      answer.status = Status::converged;
      answer.message = "tractions stable";
    }
    return answer;
  }

 private:
  static TangentialOptions<Scalar> validated(TangentialOptions<Scalar> options) {
    options.validate();
    return options;
  }

  TangentialOptions<Scalar> options_;
  RollingDirection direction_;
  std::shared_ptr<const TangentialInfluenceTable<Scalar>> influence_;
  std::shared_ptr<const detail::RollingOperator<Scalar>> rolling_;  // shared by copies
};

/// One steady-rolling solve (see SteadyRollingSolver): builds the solver's tables for
/// `grid` and `material`, which a loop over many solves on one grid should keep instead.
/// @throws fastnorm::invalid_argument as SteadyRollingSolver and its solve
template <typename Scalar>
TangentialSolution<Scalar> solve_steady_rolling(const Grid<Scalar>& grid, const Material<Scalar>& material,
                                                const Solution<Scalar>& normal, Scalar friction,
                                                const Creepage<Scalar>& creepage,
                                                RollingDirection direction = RollingDirection::positive_x,
                                                const TangentialOptions<Scalar>& options = {}) {
  return SteadyRollingSolver<Scalar>(grid, material, direction, options).solve(normal, friction, creepage);
}

}  // namespace fastnorm
