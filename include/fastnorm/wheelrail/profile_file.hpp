#pragma once
/// @file profile_file.hpp
/// Measured or worn profiles from files, with a smooth interpolant: SIMPACK profile
/// files (`point.begin … point.end`, header flags mirror.y/mirror.z/inversion/shift/units)
/// and plain two-column `y z` text.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <istream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "fastnorm/error.hpp"
#include "fastnorm/wheelrail/profile_value.hpp"

namespace fastnorm::wheelrail {

/// Profile points (m), in file order after the file's own flags are applied.
struct ProfilePoints {
  std::vector<double> y;
  std::vector<double> z;
};

/// Largest |y| and |z| of a profile point (m): a profile is a few hundred millimetres wide,
/// so a point metres away is a unit mistake (or would overflow the chord lengths).
inline constexpr double max_profile_coordinate = 1.0;

/// Reads a SIMPACK profile (recognised by `point.begin`) or plain two-column text.
/// SIMPACK: lengths in the file's `units.len.f` (user units per metre; 1000 = mm);
/// `shift.y/z` added, then `mirror.y/z` (negate), then `inversion` (reverse order); a
/// non-zero `rotate` is rejected. Plain text: `y z` per line (a third column is ignored),
/// `#` or `!` comments, lengths in `plain_length_unit` metres (default mm). Every point
/// must lie within max_profile_coordinate (1 m) of the origin once in metres.
/// @param source_name used in error messages (a file name)
/// @throws fastnorm::invalid_argument naming the source and line
inline ProfilePoints read_profile(std::istream& in, const std::string& source_name, double plain_length_unit = 1e-3) {
  fastnorm::detail::check_positive(plain_length_unit, "read_profile: plain_length_unit (m)");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  auto fail = [&](std::size_t line, const std::string& what) {
    throw invalid_argument("fastnorm: " + source_name + ":" + std::to_string(line + 1) + ": " + what);
  };
  auto strip = [](std::string line) {
    const auto comment = line.find_first_of("!#");
    if (comment != std::string::npos) line.erase(comment);
    return line;
  };
  const bool simpack = std::any_of(lines.begin(), lines.end(), [&](const std::string& l) {
    return strip(l).find("point.begin") != std::string::npos;
  });
  double unit = plain_length_unit, shift_y = 0, shift_z = 0;
  bool mirror_y = false, mirror_z = false, inversion = false, in_points = !simpack;
  ProfilePoints points;
  for (std::size_t n = 0; n < lines.size(); ++n) {
    const std::string text = strip(lines[n]);
    std::istringstream words(text);
    std::string first;
    if (!(words >> first)) continue;
    if (simpack && !in_points) {
      if (first == "point.begin") {
        in_points = true;
        continue;
      }
      std::string equals;
      double value = 0;
      if (!(words >> equals >> value) || equals != "=") continue;  // text-valued or structural lines
      if (first == "units.len.f") {
        if (!(value > 0)) fail(n, "units.len.f must be positive");
        unit = 1 / value;
      } else if (first == "shift.y") {
        shift_y = value;
      } else if (first == "shift.z") {
        shift_z = value;
      } else if (first == "mirror.y") {
        mirror_y = value != 0;
      } else if (first == "mirror.z") {
        mirror_z = value != 0;
      } else if (first == "inversion") {
        inversion = value != 0;
      } else if (first == "rotate" && value != 0) {
        fail(n, "a non-zero 'rotate' is not supported");
      }
      continue;
    }
    if (simpack && first == "point.end") break;
    std::istringstream numbers(text);
    double y = 0, z = 0;
    if (!(numbers >> y >> z) || !std::isfinite(y) || !std::isfinite(z)) fail(n, "expected two finite numbers 'y z'");
    const double y_metres = (mirror_y ? -1 : 1) * (y + shift_y) * unit;
    const double z_metres = (mirror_z ? -1 : 1) * (z + shift_z) * unit;
    if (!(std::abs(y_metres) <= max_profile_coordinate && std::abs(z_metres) <= max_profile_coordinate)) {
      fail(n, "point (" + fastnorm::detail::to_text(y_metres) + ", " + fastnorm::detail::to_text(z_metres) +
                  ") m lies more than 1 m from the origin (wrong length unit?)");
    }
    points.y.push_back(y_metres);
    points.z.push_back(z_metres);
  }
  if (inversion) {
    std::reverse(points.y.begin(), points.y.end());
    std::reverse(points.z.begin(), points.z.end());
  }
  FASTNORM_CHECK(points.y.size() >= 3, "profile '" + source_name + "' has fewer than 3 points");
  return points;
}

/// read_profile from a file.
/// @throws fastnorm::invalid_argument if the file cannot be opened, or naming its line
inline ProfilePoints read_profile_file(const std::string& path, double plain_length_unit = 1e-3) {
  std::ifstream in(path);
  FASTNORM_CHECK(in.good(), "cannot open profile file '" + path + "'");
  return read_profile(in, path, plain_length_unit);
}

namespace detail {

/// Slope at t[0] of the polynomial through the first `count` points (Newton form).
inline double end_slope(const double* t, const double* v, int count, int step) {
  double differences[4];
  for (int k = 0; k < count; ++k) differences[k] = v[k * step];
  double slope = 0, product = 1;
  for (int order = 1; order < count; ++order) {
    for (int k = count - 1; k >= order; --k) {
      differences[k] = (differences[k] - differences[k - 1]) / (t[k * step] - t[(k - order) * step]);
    }
    // d/dt of Π_{m<order} (t − t_m) at t_0 = Π_{0<m<order} (t_0 − t_m).
    if (order > 1) product *= t[0] - t[(order - 1) * step];
    slope += differences[order] * product;
  }
  return slope;
}

/// A cubic spline v(t) through (t_k, v_k), t strictly increasing, clamped at each end to
/// the slope of the cubic through the four end points (fourth-order accurate, like the
/// spline's interior).
class CubicSpline {
 public:
  CubicSpline(std::vector<double> t, std::vector<double> v) : t_(std::move(t)), v_(std::move(v)) {
    const std::size_t n = t_.size();
    auto width = [&](std::size_t k) { return t_[k + 1] - t_[k]; };
    auto chord = [&](std::size_t k) { return (v_[k + 1] - v_[k]) / width(k); };
    const int end_points = static_cast<int>(std::min<std::size_t>(n, 4));
    const double start_slope = detail::end_slope(t_.data(), v_.data(), end_points, 1);
    const double finish_slope = detail::end_slope(&t_[n - 1], &v_[n - 1], end_points, -1);
    // Second derivatives m_k: row k reads width(k−1) m_{k−1} + diagonal_k m_k + width(k) m_{k+1}
    // = rhs_k, a tridiagonal system solved by the Thomas algorithm in O(n) (Eigen has no
    // banded solver outside its unsupported modules).
    std::vector<double> diagonal(n), rhs(n);
    diagonal[0] = 2 * width(0);
    rhs[0] = 6 * (chord(0) - start_slope);
    for (std::size_t k = 1; k + 1 < n; ++k) {
      diagonal[k] = 2 * (width(k - 1) + width(k));
      rhs[k] = 6 * (chord(k) - chord(k - 1));
    }
    diagonal[n - 1] = 2 * width(n - 2);
    rhs[n - 1] = 6 * (finish_slope - chord(n - 2));
    for (std::size_t k = 1; k < n; ++k) {  // forward elimination
      const double factor = width(k - 1) / diagonal[k - 1];
      diagonal[k] -= factor * width(k - 1);
      rhs[k] -= factor * rhs[k - 1];
    }
    second_.assign(n, 0.0);
    second_[n - 1] = rhs[n - 1] / diagonal[n - 1];
    for (std::size_t k = n - 1; k-- > 0;) second_[k] = (rhs[k] - width(k) * second_[k + 1]) / diagonal[k];
  }

  /// v and dv/dt at t in interval k.
  ProfileValue<double> evaluate(double t, std::size_t k) const {
    const double width = t_[k] - t_[k - 1], a = (t_[k] - t) / width, b = 1 - a;
    return {a * v_[k - 1] + b * v_[k] +
                ((a * a * a - a) * second_[k - 1] + (b * b * b - b) * second_[k]) * width * width / 6,
            (v_[k] - v_[k - 1]) / width +
                (-(3 * a * a - 1) * second_[k - 1] + (3 * b * b - 1) * second_[k]) * width / 6};
  }

  const std::vector<double>& knots() const { return t_; }
  const std::vector<double>& values() const { return v_; }

 private:
  std::vector<double> t_, v_, second_;
};

inline std::vector<double> chord_lengths(const ProfilePoints& points) {
  std::vector<double> length(points.y.size(), 0.0);
  for (std::size_t k = 1; k < length.size(); ++k) {
    length[k] = length[k - 1] + std::hypot(points.y[k] - points.y[k - 1], points.z[k] - points.z[k - 1]);
  }
  return length;
}

}  // namespace detail

/// Smallest distance between consecutive profile points (m) that SplineProfile accepts.
inline constexpr double min_point_spacing = 1e-9;

/// A smooth profile z(y) through measured points: y(s) and z(s) are cubic splines over
/// the chord length s, so steep and vertical stretches (a flange back) are followed as
/// well as flat ones; value and slope are continuous, so contact angles do not jump at
/// the points as a polyline's would.
class SplineProfile {
 public:
  /// @param points at least 3, y strictly monotone along the profile (either direction),
  ///        consecutive points at least min_point_spacing (1 nm) apart
  /// @throws fastnorm::invalid_argument otherwise
  explicit SplineProfile(ProfilePoints points) : SplineProfile(ordered(std::move(points)), true) {}

  double y_min() const { return y_.values().front(); }
  double y_max() const { return y_.values().back(); }

  /// z (m) and dz/dy at y (m).
  /// @throws fastnorm::invalid_argument outside [y_min, y_max]
  ProfileValue<double> evaluate(double y) const {
    FASTNORM_CHECK(std::isfinite(y) && y >= y_min() && y <= y_max(),
                   fastnorm::detail::describe("SplineProfile: y outside the profile's points (m)", y));
    // The point interval holding y, then s with y(s) = y by safeguarded Newton steps.
    const auto& ys = y_.values();
    const std::size_t k = std::min<std::size_t>(
        std::max<std::size_t>(static_cast<std::size_t>(std::upper_bound(ys.begin(), ys.end(), y) - ys.begin()), 1),
        ys.size() - 1);
    double low = y_.knots()[k - 1], high = y_.knots()[k];
    double s = low + (high - low) * (y - ys[k - 1]) / (ys[k] - ys[k - 1]);
    const double tolerance = 8 * std::numeric_limits<double>::epsilon() * (std::abs(ys[k - 1]) + std::abs(ys[k]));
    for (int step = 0; step < 100; ++step) {
      const auto along_y = y_.evaluate(s, k);
      const double residual = along_y.value - y;
      if (std::abs(residual) <= tolerance) break;
      if (residual < 0) low = s; else high = s;
      const double next = s - residual / along_y.slope;
      s = (next >= low && next <= high) ? next : (low + high) / 2;
    }
    const auto along_y = y_.evaluate(s, k), along_z = z_.evaluate(s, k);
    return {along_z.value, along_z.slope / along_y.slope};
  }

 private:
  SplineProfile(const ProfilePoints& ordered_points, bool)
      : y_(detail::chord_lengths(ordered_points), ordered_points.y),
        z_(y_.knots(), ordered_points.z) {}

  // The points by increasing y, checked to be strictly monotone.
  static ProfilePoints ordered(ProfilePoints points) {
    FASTNORM_CHECK(points.y.size() == points.z.size() && points.y.size() >= 3,
                   "SplineProfile: needs at least 3 points y, z");
    if (points.y.front() > points.y.back()) {
      std::reverse(points.y.begin(), points.y.end());
      std::reverse(points.z.begin(), points.z.end());
    }
    for (std::size_t k = 1; k < points.y.size(); ++k) {
      FASTNORM_CHECK(points.y[k] > points.y[k - 1],
                     fastnorm::detail::describe("SplineProfile: y must be strictly monotone at point", k));
      // Knots much closer make the spline's second derivatives overflow (a fuzzed profile
      // with points 5e-77 m apart did); the MBench rail file starts with points 51 nm apart.
      FASTNORM_CHECK(std::hypot(points.y[k] - points.y[k - 1], points.z[k] - points.z[k - 1]) >= min_point_spacing,
                     fastnorm::detail::describe("SplineProfile: points closer than 1 nm, at point", k));
    }
    return points;
  }

  detail::CubicSpline y_;  // y(s)
  detail::CubicSpline z_;  // z(s)
};

}  // namespace fastnorm::wheelrail
