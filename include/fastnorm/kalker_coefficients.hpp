#pragma once
/// @file kalker_coefficients.hpp
/// Kalker's creepage coefficients of the linear theory of rolling contact on a Hertzian
/// ellipse (docs/tangential.md §9): the creep forces at vanishing creepage, and through them
/// the flexibilities of the simplified theory (fastsim.hpp).

#include <array>
#include <cmath>

#include "fastnorm/constants.hpp"
#include "fastnorm/error.hpp"

namespace fastnorm {

/// C11, C22, C23 of Kalker's linear theory: at vanishing creepage, in full adhesion, an
/// ellipse of semi-axes a (rolling direction) and b with c = √(ab) carries on body 1
///
///     Fx = −G c² C11 ξ,   Fy = −G c² (C22 η + c C23 φ)                                  (T9)
///
/// (G the combined shear modulus; CONTACT's signs, docs/tangential.md §5).
template <typename Scalar = double>
struct KalkerCoefficients {
  Scalar c11 = 0, c22 = 0, c23 = 0;
};

namespace detail {

/// Kalker's Table E.3 (Three-dimensional elastic bodies in rolling contact, 1990, p. 293):
/// for g = 0.1, 0.2, …, 1.0 the coefficients C11, C22, C23 at ν = 0, 0.25 and 0.5, first for
/// a/b = g (a ≤ b), then for b/a = g (a ≥ b).
struct KalkerTable {
  using Row = std::array<std::array<double, 3>, 3>;  // [coefficient][ν]
  std::array<std::array<Row, 10>, 2> rows;
};

inline const KalkerTable& kalker_table() {
  static const KalkerTable table{{{
      {{// a/b = g
        {{{2.51, 3.31, 4.85}, {2.51, 2.52, 2.53}, {0.334, 0.473, 0.731}}},
        {{{2.59, 3.37, 4.81}, {2.59, 2.63, 2.66}, {0.483, 0.603, 0.809}}},
        {{{2.68, 3.44, 4.80}, {2.68, 2.75, 2.81}, {0.607, 0.715, 0.889}}},
        {{{2.78, 3.53, 4.82}, {2.78, 2.88, 2.98}, {0.720, 0.823, 0.977}}},
        {{{2.88, 3.62, 4.83}, {2.88, 3.01, 3.14}, {0.827, 0.929, 1.07}}},
        {{{2.98, 3.72, 4.91}, {2.98, 3.14, 3.31}, {0.930, 1.03, 1.18}}},
        {{{3.09, 3.81, 4.97}, {3.09, 3.28, 3.48}, {1.03, 1.14, 1.29}}},
        {{{3.19, 3.91, 5.05}, {3.19, 3.41, 3.65}, {1.13, 1.25, 1.40}}},
        {{{3.29, 4.01, 5.12}, {3.29, 3.54, 3.82}, {1.23, 1.36, 1.51}}},
        {{{3.40, 4.12, 5.20}, {3.40, 3.67, 3.98}, {1.33, 1.47, 1.63}}}}},
      {{// b/a = g
        {{{10.7, 11.7, 12.9}, {10.7, 12.8, 16.0}, {12.2, 14.6, 18.0}}},
        {{{6.96, 7.78, 8.82}, {6.96, 8.14, 9.79}, {5.72, 6.63, 7.89}}},
        {{{5.57, 6.34, 7.34}, {5.57, 6.40, 7.51}, {3.79, 4.32, 5.01}}},
        {{{4.84, 5.57, 6.57}, {4.84, 5.48, 6.31}, {2.88, 3.24, 3.70}}},
        {{{4.37, 5.10, 6.11}, {4.37, 4.90, 5.56}, {2.35, 2.62, 2.96}}},
        {{{4.06, 4.78, 5.80}, {4.06, 4.50, 5.04}, {2.01, 2.23, 2.50}}},
        {{{3.82, 4.54, 5.58}, {3.82, 4.21, 4.67}, {1.76, 1.95, 2.18}}},
        {{{3.65, 4.36, 5.42}, {3.65, 3.99, 4.39}, {1.58, 1.75, 1.94}}},
        {{{3.51, 4.22, 5.30}, {3.51, 3.81, 4.16}, {1.44, 1.59, 1.77}}},
        {{{3.40, 4.12, 5.20}, {3.40, 3.67, 3.98}, {1.33, 1.47, 1.63}}}}},
  }}};
  return table;
}

}  // namespace detail

/// Kalker's coefficients (T9) for an ellipse of axis ratio `a_over_b` = a/b (a along the
/// rolling direction) and Poisson ratio ν ∈ [0, 0.5]. Within the table, g = min(a/b, b/a)
/// ≥ 0.1, linear in g between its rows and quadratic in ν through its three columns (the
/// interpolation of 1/C, which is close to linear in ν); for g < 0.1, Kalker's asymptotes
/// for slender ellipses (docs/tangential.md §9).
/// @throws fastnorm::invalid_argument for a ratio that is not positive and finite or ν
///         outside [0, 0.5]
template <typename Scalar = double>
KalkerCoefficients<Scalar> kalker_coefficients(Scalar a_over_b, Scalar poisson_ratio) {
  FASTNORM_CHECK(std::isfinite(a_over_b) && a_over_b > 0,
                 detail::describe("kalker_coefficients: a_over_b must be positive and finite", a_over_b));
  FASTNORM_CHECK(poisson_ratio >= 0 && poisson_ratio <= Scalar(0.5),
                 detail::describe("kalker_coefficients: poisson_ratio must lie in [0, 0.5]", poisson_ratio));
  const double nu = static_cast<double>(poisson_ratio);
  const bool wide = a_over_b <= 1;  // a ≤ b
  const double g = wide ? static_cast<double>(a_over_b) : 1 / static_cast<double>(a_over_b);
  const double pi_d = pi<double>;
  if (g < 0.1) {
    if (wide) {  // a ≪ b
      return {static_cast<Scalar>(pi_d * pi_d / (4 * (1 - nu))), static_cast<Scalar>(pi_d * pi_d / 4),
              static_cast<Scalar>(pi_d * std::sqrt(g) / (3 * (1 - nu)) * (1 + nu * (std::log(16 / g) - 5)))};
    }
    // a ≫ b
    const double lambda = std::log(16 / (g * g)), shift = 3 - std::log(4.0);
    const double lateral = (1 - nu) * lambda + 2 * nu;
    return {static_cast<Scalar>(2 * pi_d / ((lambda - 2 * nu) * g) * (1 + shift / (lambda - 2 * nu))),
            static_cast<Scalar>(2 * pi_d / g * (1 + (1 - nu) * shift / lateral) / lateral),
            static_cast<Scalar>(2 * pi_d / (3 * std::pow(g, 1.5) * ((1 - nu) * lambda - 2 + 4 * nu)))};
  }
  const auto& rows = detail::kalker_table().rows[wide ? 0 : 1];
  const auto below = static_cast<std::size_t>(std::min(8.0, std::floor(10 * g + 1e-12) - 1));
  const double weight = 10 * g - static_cast<double>(below + 1);  // 0 at row `below`, 1 at the next
  // Lagrange weights of ν = 0, 0.25, 0.5.
  const std::array<double, 3> at_nu = {8 * (nu - 0.25) * (nu - 0.5), -16 * nu * (nu - 0.5), 8 * nu * (nu - 0.25)};
  std::array<double, 3> value{};
  for (std::size_t coefficient = 0; coefficient < 3; ++coefficient) {
    double inverse = 0;
    for (std::size_t column = 0; column < 3; ++column) {
      const double tabulated = (1 - weight) * rows[below][coefficient][column] + weight * rows[below + 1][coefficient][column];
      inverse += at_nu[column] / tabulated;
    }
    value[coefficient] = 1 / inverse;
  }
  return {static_cast<Scalar>(value[0]), static_cast<Scalar>(value[1]), static_cast<Scalar>(value[2])};
}

}  // namespace fastnorm
