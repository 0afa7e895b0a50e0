#pragma once
/// @file s1002.hpp
/// The S1002 wheel profile (EN 13715 / UIC 510-2) in closed form (docs/wheel-rail.md §1): eight sections, polynomials and arcs.

#include <cmath>
#include <type_traits>

#include "fastnorm/error.hpp"
#include "fastnorm/wheelrail/profile_value.hpp"

namespace fastnorm::wheelrail {

/// S1002: F(y), the radial height above the taping-line radius (m, positive = larger
/// radius), at the lateral profile coordinate y (m) measured from the taping line,
/// positive towards the field side; the flange is at negative y and its back at
/// y = −0.070 m. The wheel radius is r0 + F(y).
///
/// Valid for y in [−0.0699, 0.060] (at −0.070 the flange back is vertical).
template <typename Scalar = double>
class S1002 {
  static_assert(std::is_floating_point_v<Scalar>, "fastnorm::wheelrail::S1002 needs a floating-point Scalar");

 public:
  /// Lowest and highest valid y (m).
  static constexpr double y_min = -0.0699;
  static constexpr double y_max = 0.060;

  /// F(y) (m) and dF/dy.
  /// @throws fastnorm::invalid_argument for y outside [y_min, y_max]
  ProfileValue<Scalar> evaluate(Scalar y) const {
    FASTNORM_CHECK(std::isfinite(y) && y >= Scalar(y_min) - Scalar(1e-12) && y <= Scalar(y_max) + Scalar(1e-12),
                   fastnorm::detail::describe("S1002: y must lie in [-0.0699, 0.060] m", y));
    const auto in_mm = evaluate_mm(static_cast<double>(y) * 1000);
    return {static_cast<Scalar>(in_mm.value / 1000), static_cast<Scalar>(in_mm.slope)};
  }

 private:
  // The published coefficients are for mm; evaluated in double.
  static ProfileValue<double> evaluate_mm(double y) {
    if (y >= 32.15796) return {1.364323640 - 0.066666667 * y, -0.066666667};  // A: 1:15 cone
    if (y >= -26) {                                                            // B: tread
      // Signs alternate as published: F = −BB y + CB y² − DB y³ + EB y⁴ − FB y⁵ + GB y⁶ − HB y⁷ + IB y⁸.
      const double c[9] = {0.0,          -3.358537058e-02, 1.565681624e-03, -2.810427944e-05, 5.844240864e-08,
                           -1.562379023e-08, 5.309217349e-15, -5.957839843e-12, 2.646656573e-13};
      return polynomial(c, y);
    }
    if (y >= -35) {  // C: flange root
      const double c[9] = {-4.320221063e+03, -1.038384026e+03, -1.065501873e+02, -6.051367875,
                           -2.054332446e-01, -4.169739389e-03, -4.687195829e-05, -2.252755540e-07, 0.0};
      return polynomial(c, y);
    }
    if (y >= -38.426669071) {  // D: arc R13, centre (−26.210665, 16.446), below it
      const double root = std::sqrt(13.0 * 13.0 - (y + 26.210665) * (y + 26.210665));
      return {16.446 - root, (y + 26.210665) / root};
    }
    if (y >= -39.764473993) return {-93.576667419 - 2.747477419 * y, -2.747477419};  // E: 70° flank
    if (y >= -49.662510381) return arc_above(8.834924130, 20, 58.558326413, y);      // F
    if (y >= -62.764705882) return arc_above(16, 12, 55, y);                         // G: flange tip
    return arc_above(9.519259302, 20.5, 49.5, y);                                     // H: flange back
  }

  // Σ c_n yⁿ (n ≤ 8) and its derivative by Estrin's scheme: pairs of terms combined with y²,
  // then y⁴, y⁸, so that the chain of dependent multiply-adds is four long instead of
  // Horner's eight. The wheel is evaluated in chains of Newton steps (h along a row, the
  // locus samples), where that chain's latency is the cost (8 ns against 27 ns a call,
  // docs/performance.md §8).
  static ProfileValue<double> polynomial(const double (&c)[9], double y) {
    const double y2 = y * y, y4 = y2 * y2, y8 = y4 * y4;
    const double value = ((c[0] + c[1] * y) + (c[2] + c[3] * y) * y2) +
                         ((c[4] + c[5] * y) + (c[6] + c[7] * y) * y2) * y4 + c[8] * y8;
    const double slope = ((c[1] + 2 * c[2] * y) + (3 * c[3] + 4 * c[4] * y) * y2) +
                         ((5 * c[5] + 6 * c[6] * y) + (7 * c[7] + 8 * c[8] * y) * y2) * y4;
    return {value, slope};
  }

  // A + sqrt(B² − (y + C)²): an arc of radius B centred at (−C, A), above its centre.
  static ProfileValue<double> arc_above(double a, double b, double c, double y) {
    const double root = std::sqrt(b * b - (y + c) * (y + c));
    return {a + root, -(y + c) / root};
  }
};

}  // namespace fastnorm::wheelrail
