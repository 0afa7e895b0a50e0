#pragma once
/// @file uic60.hpp
/// The UIC60 (60E1) rail head in closed form: R300, R80 and R13 arcs, internally
/// tangent, then the 1:20 flank (docs/wheel-rail.md §1).

#include <cmath>
#include <type_traits>

#include "fastnorm/error.hpp"
#include "fastnorm/wheelrail/profile_value.hpp"

namespace fastnorm::wheelrail {

/// The uncanted UIC60 head: z_r(y_r), depth below the top (m, positive down), at the
/// lateral coordinate y_r (m) from the rail's symmetry axis; symmetric in y_r.
///
/// Two variants differ only beyond |y_r| = 10.2 mm: `mbench()` (X1 = 10.5 mm, the R13 arc
/// ending at |y_r| = 36 mm; the profile of CONTACT's Manchester benchmark and of every
/// peer case, the default) and `en13674()` (X1 = 10.228 mm, X2 = 26.0265 mm, the EN 13674-1
/// drawing).
template <typename Scalar = double>
class Uic60 {
  static_assert(std::is_floating_point_v<Scalar>, "fastnorm::wheelrail::Uic60 needs a floating-point Scalar");

 public:
  /// The Manchester-benchmark variant (default).
  static Uic60 mbench() {
    // The R13 arc ends at |y_r| = 36 with slope 1:20: its centre is 13 cos b inside that.
    const double b = std::atan(1.0 / 20);
    const double centre3_y = 36 - 13 * std::cos(b);
    const Geometry g = from_x1(10.5);
    return Uic60(g.x1, g.centre2_y, g.centre2_z, std::asin((centre3_y - g.centre2_y) / 67));
  }

  /// The EN 13674-1 variant.
  static Uic60 en13674() {
    const Geometry g = from_x1(10.228);
    return Uic60(g.x1, g.centre2_y, g.centre2_z, std::asin((26.0265 - g.centre2_y) / 80));
  }

  /// Lateral extent of the head's contact surface: the end of the R13 arc, |y_r| (m).
  Scalar flank_start() const { return static_cast<Scalar>(tangent3_y_ / 1000); }

  /// z_r (m, down from the top) and dz_r/dy_r at y_r (m).
  /// @throws fastnorm::invalid_argument for |y_r| beyond the flank (z_r > 37 mm)
  ProfileValue<Scalar> evaluate(Scalar y_r) const {
    FASTNORM_CHECK(std::isfinite(y_r), fastnorm::detail::describe("Uic60: y_r must be finite", y_r));
    const double y = std::abs(static_cast<double>(y_r)) * 1000, sign = y_r < 0 ? -1.0 : 1.0;
    ProfileValue<double> in_mm;
    if (y <= x1_) {
      in_mm = arc_below(0, 300, 300, y);
    } else if (y <= tangent2_y_) {
      in_mm = arc_below(centre2_y_, centre2_z_, 80, y);
    } else if (y <= tangent3_y_) {
      in_mm = arc_below(centre3_y_, centre3_z_, 13, y);
    } else {
      in_mm = {tangent3_z_ + 20 * (y - tangent3_y_), 20.0};  // flank y = t3y + (z − t3z)/20
      FASTNORM_CHECK(in_mm.value <= 37, fastnorm::detail::describe("Uic60: y_r lies below the rail head (m)", y_r));
    }
    return {static_cast<Scalar>(in_mm.value / 1000), static_cast<Scalar>(sign * in_mm.slope)};
  }

 private:
  struct Geometry {
    double x1, centre2_y, centre2_z;
  };
  // R300 centred at (0, 300) up to X1; the R80 arc internally tangent there.
  static Geometry from_x1(double x1) {
    const double a1 = std::asin(x1 / 300);
    return {x1, 220 * std::sin(a1), 300 - 220 * std::cos(a1)};
  }

  // a2: angle of the R80/R13 tangent point seen from the R80 centre.
  Uic60(double x1, double centre2_y, double centre2_z, double a2)
      : x1_(x1), centre2_y_(centre2_y), centre2_z_(centre2_z) {
    tangent2_y_ = centre2_y_ + 80 * std::sin(a2);
    centre3_y_ = centre2_y_ + 67 * std::sin(a2);
    centre3_z_ = centre2_z_ - 67 * std::cos(a2);
    const double b = std::atan(1.0 / 20);
    tangent3_y_ = centre3_y_ + 13 * std::cos(b);
    tangent3_z_ = centre3_z_ - 13 * std::sin(b);
  }

  // z = c_z − sqrt(R² − (y − c_y)²): the upper half of a circle (z down), and its slope.
  static ProfileValue<double> arc_below(double centre_y, double centre_z, double radius, double y) {
    const double root = std::sqrt(radius * radius - (y - centre_y) * (y - centre_y));
    return {centre_z - root, (y - centre_y) / root};
  }

  double x1_, centre2_y_, centre2_z_;
  double tangent2_y_ = 0, centre3_y_ = 0, centre3_z_ = 0, tangent3_y_ = 0, tangent3_z_ = 0;
};

}  // namespace fastnorm::wheelrail
