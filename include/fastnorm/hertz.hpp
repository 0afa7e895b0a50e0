#pragma once
/// @file hertz.hpp
/// Closed-form Hertz solution for two bodies whose undeformed distance near the first
/// point of contact is h(x, y) = x²/(2 R_x) + y²/(2 R_y) (docs/hertz.md). Independent
/// truth for testing the numerical solvers.

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

#include <Eigen/Core>

#include "fastnorm/constants.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/grid.hpp"

namespace fastnorm {

/// The Hertz contact ellipse and its load.
template <typename Scalar = double>
struct HertzContact {
  Scalar semi_axis_x = 0;   ///< half-length of the contact ellipse along x (m)
  Scalar semi_axis_y = 0;   ///< half-width along y (m)
  Scalar max_pressure = 0;  ///< p0 (Pa)
  Scalar approach = 0;      ///< δ: h − δ + u = 0 in contact (m)
  Scalar normal_force = 0;  ///< N

  /// p0·sqrt(1 − (x/a)² − (y/b)²) inside the ellipse, 0 outside (Pa).
  Scalar pressure(Scalar x, Scalar y) const {
    const Scalar s = 1 - (x / semi_axis_x) * (x / semi_axis_x) - (y / semi_axis_y) * (y / semi_axis_y);
    return s > 0 ? max_pressure * std::sqrt(s) : Scalar(0);
  }
};

namespace detail {

/// What fixes the shape of the contact ellipse: the smaller curvature A = 1/(2 max R),
/// the eccentricity e and the factors K(e) and (K − E)/e² (docs/hertz.md Eq. (H2)).
template <typename Scalar>
struct HertzShape {
  Scalar smaller_curvature;
  Scalar eccentricity;
  Scalar k_integral;
  Scalar k_minus_e_over_e2;
};

/// Rejects radii that are not positive and finite.
template <typename Scalar>
void check_radii(Scalar radius_x, Scalar radius_y) {
  FASTNORM_CHECK(std::isfinite(radius_x) && radius_x > 0,
                 describe("hertz: radius_x must be positive and finite (m)", radius_x));
  FASTNORM_CHECK(std::isfinite(radius_y) && radius_y > 0,
                 describe("hertz: radius_y must be positive and finite (m)", radius_y));
}

/// The complete elliptic integrals K(k) and E(k) of modulus k ∈ [0, 1) (as
/// std::comp_ellint_1/2, which libc++ lacks) by the arithmetic-geometric mean:
/// K = π / (2·AGM(1, √(1 − k²))), E = K·(1 − Σₙ 2ⁿ⁻¹ cₙ²) with c₀ = k, cₙ₊₁ = (aₙ − bₙ)/2
/// (Abramowitz & Stegun 17.6). Quadratic convergence: at most 6 steps in double for
/// k ≤ 1 − 1e-12, checked in tests/core/hertz.test.cpp against closed-form values.
template <typename Scalar>
std::pair<Scalar, Scalar> complete_elliptic_integrals(Scalar k) {
  Scalar a = 1, b = std::sqrt((1 - k) * (1 + k)), c = k, power = Scalar(0.5), sum = power * c * c;
  for (int step = 0; step < 64 && std::abs(c) > std::numeric_limits<Scalar>::epsilon() * a; ++step) {
    c = (a - b) / 2;
    const Scalar next_a = (a + b) / 2;
    b = std::sqrt(a * b);
    a = next_a;
    power *= 2;
    sum += power * c * c;
  }
  const Scalar first = pi<Scalar> / (2 * a);
  return {first, first * (1 - sum)};
}

/// The shape for radii R_x, R_y, which must be positive and finite, like E*.
/// @throws fastnorm::invalid_argument naming the offending argument
template <typename Scalar>
HertzShape<Scalar> hertz_shape(Scalar radius_x, Scalar radius_y, Scalar combined_modulus) {
  check_radii(radius_x, radius_y);
  FASTNORM_CHECK(std::isfinite(combined_modulus) && combined_modulus > 0,
                 describe("hertz: combined_modulus must be positive and finite (Pa)",
                          combined_modulus));
  const Scalar smaller_curvature = 1 / (2 * std::max(radius_x, radius_y));
  const Scalar curvature_ratio = std::max(radius_x, radius_y) / std::min(radius_x, radius_y);
  auto shape = [smaller_curvature](Scalar e) {
    if (e < Scalar(1e-4)) {  // series: K − E = (π/2)(e²/2 + 3e⁴/16 + …)
      return HertzShape<Scalar>{smaller_curvature, e, pi<Scalar> / 2 * (1 + e * e / 4),
                                pi<Scalar> / 4 * (1 + 3 * e * e / 8)};
    }
    const auto [k, E] = detail::complete_elliptic_integrals(e);
    return HertzShape<Scalar>{smaller_curvature, e, k, (k - E) / (e * e)};
  };
  // B/A = ((a/b)² E − K)/(K − E), increasing in e from 1 at e = 0: bisection.
  auto ratio_of = [](Scalar e) {
    const auto [k, E] = detail::complete_elliptic_integrals(e);
    return (E / (1 - e * e) - k) / (k - E);
  };
  if (curvature_ratio <= 1) return shape(Scalar(0));
  Scalar low = 0, high = 1;
  for (int step = 0; step < 200 && high - low > 4 * std::numeric_limits<Scalar>::epsilon(); ++step) {
    const Scalar mid = (low + high) / 2;
    if (mid > 0 && ratio_of(mid) < curvature_ratio) low = mid; else high = mid;
  }
  return shape((low + high) / 2);
}

/// Completes the contact from the long semi-axis `a` (along the smaller curvature A).
template <typename Scalar>
HertzContact<Scalar> hertz_from_long_axis(Scalar radius_x, Scalar radius_y, Scalar combined_modulus,
                                          Scalar a, const HertzShape<Scalar>& shape) {
  const Scalar b = a * std::sqrt(1 - shape.eccentricity * shape.eccentricity);
  HertzContact<Scalar> contact;
  contact.normal_force =
      a * a * a * 2 * pi<Scalar> * combined_modulus * shape.smaller_curvature / (3 * shape.k_minus_e_over_e2);
  contact.max_pressure = 3 * contact.normal_force / (2 * pi<Scalar> * a * b);
  contact.approach = contact.max_pressure * b * shape.k_integral / combined_modulus;
  const bool long_axis_is_x = radius_x >= radius_y;
  contact.semi_axis_x = long_axis_is_x ? a : b;
  contact.semi_axis_y = long_axis_is_x ? b : a;
  return contact;
}

}  // namespace detail

/// Hertz contact for a given normal force.
/// @param radius_x, radius_y relative radii of curvature R_x, R_y (m, > 0)
/// @param combined_modulus E* (Pa)
/// @param normal_force Fn (N, > 0)
/// @throws fastnorm::invalid_argument naming the offending argument
template <typename Scalar>
HertzContact<Scalar> hertz_from_force(Scalar radius_x, Scalar radius_y, Scalar combined_modulus,
                                      Scalar normal_force) {
  static_assert(std::is_floating_point_v<Scalar>);
  const auto shape = detail::hertz_shape(radius_x, radius_y, combined_modulus);
  FASTNORM_CHECK(std::isfinite(normal_force) && normal_force > 0,
                 detail::describe("hertz: normal_force must be positive and finite (N)", normal_force));
  // a³ = 3 F (K − E) / (2π E* e² A)   (docs/hertz.md Eq. (H3))
  const Scalar a = std::cbrt(3 * normal_force * shape.k_minus_e_over_e2 /
                             (2 * pi<Scalar> * combined_modulus * shape.smaller_curvature));
  return detail::hertz_from_long_axis(radius_x, radius_y, combined_modulus, a, shape);
}

/// Hertz contact for a given approach δ (m, > 0).
/// @throws fastnorm::invalid_argument naming the offending argument
template <typename Scalar>
HertzContact<Scalar> hertz_from_approach(Scalar radius_x, Scalar radius_y, Scalar combined_modulus,
                                         Scalar approach) {
  static_assert(std::is_floating_point_v<Scalar>);
  const auto shape = detail::hertz_shape(radius_x, radius_y, combined_modulus);
  FASTNORM_CHECK(std::isfinite(approach) && approach > 0,
                 detail::describe("hertz: approach must be positive and finite (m)", approach));
  // δ = a² A K e²/(K − E)   (docs/hertz.md Eq. (H4))
  const Scalar a =
      std::sqrt(approach * shape.k_minus_e_over_e2 / (shape.smaller_curvature * shape.k_integral));
  return detail::hertz_from_long_axis(radius_x, radius_y, combined_modulus, a, shape);
}

/// The quadratic undeformed distance h = x²/(2 R_x) + y²/(2 R_y) (m) at the element
/// centres of `grid`: the gap of a Hertz problem before any approach.
/// @throws fastnorm::invalid_argument for non-positive radii
template <typename Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, 1> hertz_undeformed_distance(const Grid<Scalar>& grid,
                                                                    Scalar radius_x, Scalar radius_y) {
  detail::check_radii(radius_x, radius_y);
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> h(grid.size());
  for (Eigen::Index k = 0; k < grid.size(); ++k) {
    const Scalar x = grid.x_of(k), y = grid.y_of(k);
    h(k) = x * x / (2 * radius_x) + y * y / (2 * radius_y);
  }
  return h;
}

/// An n × n grid centred on the first point of contact that covers ±coverage semi-axes of
/// `contact` in x and in y (the CONTACT peer cases use coverage 1.2). With n odd an
/// element sits on the first point of contact; with n even the centre is a corner.
/// @throws fastnorm::invalid_argument for n < 1 or coverage ≤ 0
template <typename Scalar>
Grid<Scalar> hertz_grid(const HertzContact<Scalar>& contact, Eigen::Index n, Scalar coverage = Scalar(1.2)) {
  FASTNORM_CHECK(n >= 1, detail::describe("hertz_grid: n must be >= 1", n));
  FASTNORM_CHECK(std::isfinite(coverage) && coverage > 0,
                 detail::describe("hertz_grid: coverage must be positive and finite", coverage));
  const Scalar dx = 2 * coverage * contact.semi_axis_x / static_cast<Scalar>(n);
  const Scalar dy = 2 * coverage * contact.semi_axis_y / static_cast<Scalar>(n);
  const Scalar half = static_cast<Scalar>(n - 1) / 2;
  return Grid<Scalar>(n, n, dx, dy, -half * dx, -half * dy);
}

}  // namespace fastnorm
