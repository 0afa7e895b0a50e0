#pragma once
/// @file rail_table.hpp
/// A rail's height and slope across the track, tabulated for the contact search: exact at
/// knots a fixed distance apart, the cubic Hermite interpolant between two knots where its
/// error is bounded within stated tolerances, nothing elsewhere (docs/wheel-rail.md §4,
/// item 3).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

namespace fastnorm::wheelrail {

/// A rail point as the contact search needs it.
struct RailSample {
  double height = 0;     ///< Z (m, down) in the track frame
  double slope = 0;      ///< dZ/dy
  double profile_y = 0;  ///< the rail profile coordinate y_r (m): a start for an exact evaluation nearby
};

/// Z(y) and Z'(y) of one rail (the track's right rail), pose-independent, tabulated once.
///
/// Between knots y_k and y_k + Δ the cubic Hermite interpolant p of Z (values and slopes
/// exact at both knots) satisfies |Z − p| ≤ Δ⁴/384 · max|Z⁗| and |Z' − p'| ≤ √3/216 · Δ³ ·
/// max|Z⁗| on the interval. An interval answers (is vouched for) only if
/// (a) both bounds, with Z⁗ estimated from the jumps of the third derivatives of the
///     neighbouring intervals' cubics (each constant; over two intervals on either side)
///     and a safety factor of 4, stay within height_tolerance and slope_tolerance, and
/// (b) at a quarter, half and three quarters of the interval the interpolant agrees with an
///     exact evaluation within half of each tolerance.
/// (a) misses a jump of Z″ (the joint of two arcs) that its neighbours see alike, (b) one
/// that the check points happen to straddle evenly; together they reject every interval
/// near a joint (tests/wheelrail/geometry.test.cpp checks the table against exact
/// evaluations between the check points).
class RailTable {
 public:
  static constexpr double spacing = 50e-6;           ///< Δ between knots (m)
  static constexpr double height_tolerance = 1e-13;  ///< bound on |Z − p| where vouched for (m)
  static constexpr double slope_tolerance = 1e-10;   ///< bound on |Z' − p'| there

  RailTable() = default;

  /// Tabulates `exact(y, profile_y)` → std::optional<RailSample> on [first, last]: the exact
  /// rail point at y (empty beyond the rail), continuing from `profile_y` (y_r nearby, NaN if
  /// unknown), which receives its own.
  template <typename Exact>
  RailTable(const Exact& exact, double first, double last) : first_(first) {
    if (!(last > first)) return;
    const auto knots = static_cast<std::size_t>(std::floor((last - first) / spacing)) + 1;
    if (knots < 2) return;
    std::vector<std::optional<RailSample>> at(knots);
    double profile_y = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t k = 0; k < knots; ++k) at[k] = exact(knot_y(k), profile_y);
    intervals_.resize(knots - 1);
    std::vector<double> third(knots - 1, std::numeric_limits<double>::quiet_NaN());  // Z‴ of each cubic
    for (std::size_t i = 0; i + 1 < knots; ++i) {
      if (!at[i] || !at[i + 1]) continue;
      Interval& interval = intervals_[i];
      const RailSample &a = *at[i], &b = *at[i + 1];
      // p(t) = c0 + c1 t + c2 t² + c3 t³, t = (y − y_i)/Δ ∈ [0, 1].
      interval.c0 = a.height;
      interval.c1 = spacing * a.slope;
      interval.c2 = 3 * (b.height - a.height) - spacing * (2 * a.slope + b.slope);
      interval.c3 = 2 * (a.height - b.height) + spacing * (a.slope + b.slope);
      interval.profile_y0 = a.profile_y;
      interval.profile_y1 = b.profile_y;
      third[i] = 6 * interval.c3 / (spacing * spacing * spacing);
    }
    // |Z⁗| near interval i: the largest jump of Z‴ between consecutive cubics within two
    // intervals of it, over Δ (infinite where a neighbour is missing).
    auto jump = [&](std::size_t left) {  // between cubics left and left + 1
      if (left + 1 >= third.size()) return 0.0;
      const double change = std::abs(third[left + 1] - third[left]) / spacing;
      return std::isnan(change) ? std::numeric_limits<double>::infinity() : change;
    };
    for (std::size_t i = 0; i < intervals_.size(); ++i) {
      if (std::isnan(third[i])) continue;
      double fourth = 0;
      for (std::size_t left = i >= 2 ? i - 2 : 0; left <= i + 1; ++left) fourth = std::max(fourth, jump(left));
      const double height_bound = 4 * fourth * std::pow(spacing, 4) / 384;
      const double slope_bound = 4 * fourth * std::sqrt(3.0) / 216 * std::pow(spacing, 3);
      if (!(height_bound <= height_tolerance && slope_bound <= slope_tolerance)) continue;
      bool agrees = true;
      double check_profile_y = intervals_[i].profile_y0;
      for (double t : {0.25, 0.5, 0.75}) {
        const auto truth = exact(knot_y(i) + t * spacing, check_profile_y);
        const auto tabulated = interpolate(intervals_[i], t);
        agrees = agrees && truth && std::abs(truth->height - tabulated.height) <= height_tolerance / 2 &&
                 std::abs(truth->slope - tabulated.slope) <= slope_tolerance / 2;
      }
      intervals_[i].vouched = agrees;
    }
  }

  /// The interpolated rail point at y where the table vouches for it; empty elsewhere (the
  /// caller evaluates exactly). `profile_y` is interpolated linearly: a start, not a value.
  std::optional<RailSample> at(double y) const {
    const double u = (y - first_) / spacing;
    if (!(u >= 0 && u < static_cast<double>(intervals_.size()))) return std::nullopt;
    const auto i = static_cast<std::size_t>(u);
    const Interval& interval = intervals_[i];
    if (!interval.vouched) return std::nullopt;
    return interpolate(interval, u - static_cast<double>(i));
  }

  /// How many intervals the table has, and how many of them answer.
  std::size_t intervals() const { return intervals_.size(); }
  std::size_t vouched() const {
    return static_cast<std::size_t>(
        std::count_if(intervals_.begin(), intervals_.end(), [](const Interval& interval) { return interval.vouched; }));
  }

 private:
  struct Interval {
    double c0 = 0, c1 = 0, c2 = 0, c3 = 0;  // p in powers of t
    double profile_y0 = 0, profile_y1 = 0;   // y_r at the knots
    bool vouched = false;
  };

  double knot_y(std::size_t k) const { return first_ + static_cast<double>(k) * spacing; }

  static RailSample interpolate(const Interval& interval, double t) {
    return {interval.c0 + t * (interval.c1 + t * (interval.c2 + t * interval.c3)),
            (interval.c1 + t * (2 * interval.c2 + t * 3 * interval.c3)) / spacing,
            interval.profile_y0 + t * (interval.profile_y1 - interval.profile_y0)};
  }

  double first_ = 0;
  std::vector<Interval> intervals_;
};

}  // namespace fastnorm::wheelrail
