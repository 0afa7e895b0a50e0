#pragma once
/// @file track.hpp
/// Two rails placed in the track: canted, lifted to the track plane and set to the gauge
/// (docs/wheel-rail.md §3).

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <utility>

#include "fastnorm/detail/object_id.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/wheelrail/profile_curve.hpp"
#include "fastnorm/wheelrail/rail_table.hpp"

namespace fastnorm::wheelrail {

/// Which wheel and rail: left (y_track < 0) or right (y_track > 0).
enum class Side { left, right };

/// +1 for the right side, −1 for the left.
inline double side_sign(Side side) { return side == Side::right ? 1.0 : -1.0; }

inline const char* to_string(Side side) { return side == Side::right ? "right" : "left"; }

/// How the rails sit in the track (m, rad).
struct TrackLayout {
  double gauge = 1.435;                 ///< between the gauge points of the two rails
  double gauge_depth = 0.014;           ///< depth of the gauge points below the top of rail
  double cant = std::atan(1.0 / 40);    ///< rail inclination towards the track centre (0: profile already canted)
};

/// The track: both rail surfaces in the track frame (x forward, y right, z down, origin on
/// the centre line in the plane through the rail tops). The right rail surface is
/// z = Z(y); the left is its mirror image, Z_left(y) = Z(−y).
class Track {
 public:
  /// @param rail the uncanted rail head (depth below the top, y_r positive to the field side
  ///        of the right rail); the default is the MBench UIC60
  /// @throws fastnorm::invalid_argument for a gauge, gauge depth or cant out of range
  explicit Track(ProfileCurve rail = uic60_rail(), TrackLayout layout = {})
      : rail_(std::move(rail)), layout_(layout) {
    FASTNORM_CHECK(std::isfinite(layout.gauge) && layout.gauge > 0,
                   fastnorm::detail::describe("Track: gauge must be positive (m)", layout.gauge));
    FASTNORM_CHECK(std::isfinite(layout.gauge_depth) && layout.gauge_depth > 0,
                   fastnorm::detail::describe("Track: gauge_depth must be positive (m)", layout.gauge_depth));
    FASTNORM_CHECK(std::isfinite(layout.cant) && std::abs(layout.cant) < 0.2,
                   fastnorm::detail::describe("Track: cant must lie in (-0.2, 0.2) rad", layout.cant));
    cos_ = std::cos(layout.cant);
    sin_ = std::sin(layout.cant);
    // Top of the canted head: the lowest z' (dense scan, then golden section).
    const int samples = 2000;
    double best = rail_.y_min(), best_z = canted_z(best);
    for (int k = 1; k <= samples; ++k) {
      const double y_r = rail_.y_min() + (rail_.y_max() - rail_.y_min()) * k / samples;
      if (canted_z(y_r) < best_z) best = y_r, best_z = canted_z(y_r);
    }
    const double step = (rail_.y_max() - rail_.y_min()) / samples;
    const auto top = detail::golden_minimum([&](double y_r) { return canted_z(y_r); },
                                            std::max(rail_.y_min(), best - step), std::min(rail_.y_max(), best + step), 1e-12);
    shift_z_ = -top.second;
    // Gauge point: the innermost point within gauge_depth of the top.
    double inside = top.first, outside = rail_.y_min();
    FASTNORM_CHECK(canted_z(outside) + shift_z_ > layout.gauge_depth,
                   "Track: the rail profile does not reach gauge_depth below its top on the gauge side");
    for (int k = 0; k < 200 && inside - outside > 1e-13; ++k) {
      const double middle = (inside + outside) / 2;
      (canted_z(middle) + shift_z_ <= layout.gauge_depth ? inside : outside) = middle;
    }
    shift_y_ = layout.gauge / 2 - canted_y(inside);
    // Where the right rail profile begins and ends across the track (y increases with y_r).
    first_y_ = canted_y(rail_.y_min()) + shift_y_;
    last_y_ = canted_y(rail_.y_max()) + shift_y_;
    table_ = std::make_shared<const RailTable>(
        [this](double y, double& profile_y) -> std::optional<RailSample> {
          const auto height = rail_height(Side::right, y, profile_y);
          if (!height) return std::nullopt;
          return RailSample{height->value, height->slope, profile_y};
        },
        first_y_, last_y_);
  }

  /// This track's identity: a number no other track of the process has; a copy keeps it (the
  /// data is the same and never changes). What keeps state about a track (a contact search's
  /// tables) knows it by this number, never by its address.
  std::uint64_t id() const { return id_; }
  const TrackLayout& layout() const { return layout_; }

  /// Where the right rail's profile begins and ends across the track (m; the left rail's
  /// span is its mirror image).
  std::pair<double, double> right_rail_span() const { return {first_y_, last_y_}; }

  /// Height Z (m, down) of the rail on `side` at lateral track position y (m), and dZ/dy;
  /// empty where y is beyond the rail profile.
  std::optional<ProfileValue<double>> rail_height(Side side, double y) const {
    double profile_y = std::numeric_limits<double>::quiet_NaN();
    return rail_height(side, y, profile_y);
  }

  /// The same, continuing from a nearby point: `profile_y` holds the right rail's y_r there
  /// (NaN if unknown) and receives this point's (NaN off the rail). From a good guess one
  /// Newton step of at most 50 nm is accepted, as in distance_to_rail (G' ≈ cos θ,
  /// G'' = sin θ·z_r''); the contact search's neighbouring locus samples use it.
  std::optional<ProfileValue<double>> rail_height(Side side, double y, double& profile_y) const {
    const double sign = side_sign(side);
    const auto y_r = right_profile_coordinate(sign * y, profile_y);
    profile_y = y_r ? *y_r : std::numeric_limits<double>::quiet_NaN();
    if (!y_r) return std::nullopt;
    const auto surface = right_rail(*y_r);
    return ProfileValue<double>{surface.z, sign * surface.slope};
  }

  /// The same from the track's RailTable where it vouches for y (within 1e-13 m in height
  /// and 1e-10 in slope), exactly elsewhere: what the contact search's samples take
  /// (docs/wheel-rail.md §4, item 3). `profile_y` receives y_r, interpolated linearly where
  /// the table answered (a start for the next exact evaluation nearby, not a value).
  std::optional<ProfileValue<double>> rail_height_tabulated(Side side, double y, double& profile_y) const {
    const double sign = side_sign(side);
    if (const auto tabulated = table_->at(sign * y)) {
      profile_y = tabulated->profile_y;
      return ProfileValue<double>{tabulated->height, sign * tabulated->slope};
    }
    return rail_height(side, y, profile_y);
  }

  /// The right rail's table (shared by the track's copies; it never changes).
  const RailTable& rail_table() const { return *table_; }

  /// Distance t (m) along the unit direction (dir_y, dir_z) from (y, z) to the rail surface on
  /// `side` (a 2-D intersection: the rail is prismatic); empty if the line misses the profile.
  std::optional<double> distance_to_rail(Side side, double y, double z, double dir_y, double dir_z) const {
    double profile_y = std::numeric_limits<double>::quiet_NaN();
    return distance_to_rail(side, y, z, dir_y, dir_z, profile_y);
  }

  /// The same, continuing from a nearby line: `profile_y` holds y_r where that line met the
  /// right rail's profile (NaN if unknown) and receives this one's. From a good guess one
  /// Newton step of at most 50 nm is accepted: its error ≈ |G''/2G'|·step² stays below
  /// 1e-13 m, since |G''/2G'| reaches about 30 /m on the gauge corner's R13 arc, where the
  /// head is steep (docs/wheel-rail.md §4).
  std::optional<double> distance_to_rail(Side side, double y, double z, double dir_y, double dir_z,
                                         double& profile_y) const {
    const double sign = side_sign(side);
    y *= sign;
    dir_y *= sign;
    // cross((P(y_r) − Q), d) = 0: zero where the rail point lies on the line.
    auto crossing = [&](double y_r) {
      const auto p = right_rail(y_r);
      const double dy_dyr = cos_ + sin_ * p.depth_slope, dz_dyr = -sin_ + cos_ * p.depth_slope;
      return ProfileValue<double>{(p.y - y) * dir_z - (p.z - z) * dir_y, dy_dyr * dir_z - dz_dyr * dir_y};
    };
    const double low = rail_.y_min(), high = rail_.y_max();
    std::optional<double> y_r;
    if (profile_y >= low && profile_y <= high) y_r = detail::newton_root(crossing, profile_y, low, high, 1e-13, 5e-8);
    if (!y_r) {
      const double at_low = crossing(low).value;
      profile_y = std::numeric_limits<double>::quiet_NaN();
      if ((at_low < 0) == (crossing(high).value < 0)) return std::nullopt;
      const auto guess = right_profile_coordinate(y);
      y_r = detail::bracketed_root(crossing, low, at_low, high, guess ? *guess : (low + high) / 2, 1e-13);
    }
    profile_y = *y_r;
    const auto p = right_rail(*y_r);
    return (p.y - y) * dir_y + (p.z - z) * dir_z;
  }

 private:
  struct RailPoint {
    double y, z;           // track coordinates of the right rail point (m)
    double slope;          // dZ/dy in the track
    double depth_slope;    // dz_r/dy_r of the uncanted profile
  };

  double canted_y(double y_r) const { return cos_ * y_r + sin_ * rail_.evaluate(y_r).value; }
  double canted_z(double y_r) const { return -sin_ * y_r + cos_ * rail_.evaluate(y_r).value; }

  // Right rail: y' = cosθ·y_r + sinθ·z_r, z' = −sinθ·y_r + cosθ·z_r (docs/wheel-rail.md §3), shifted.
  RailPoint right_rail(double y_r) const {
    const auto at = rail_.evaluate(y_r);
    const double dy = cos_ + sin_ * at.slope, dz = -sin_ + cos_ * at.slope;
    return {cos_ * y_r + sin_ * at.value + shift_y_, -sin_ * y_r + cos_ * at.value + shift_z_, dz / dy, at.slope};
  }

  // y_r of the right rail point at track position y: y(y_r) increases monotonically
  // (dy/dy_r = cosθ + sinθ·z_r' > 0 on any head with slopes above −cotθ).
  // From `guess` (a nearby point's y_r) by Newton when it converges at once, else bracketed.
  std::optional<double> right_profile_coordinate(double y, double guess = std::numeric_limits<double>::quiet_NaN()) const {
    auto offset = [&](double y_r) {
      const auto at = rail_.evaluate(y_r);
      return ProfileValue<double>{cos_ * y_r + sin_ * at.value + shift_y_ - y, cos_ + sin_ * at.slope};
    };
    if (!(y >= first_y_ && y <= last_y_)) return std::nullopt;
    if (guess >= rail_.y_min() && guess <= rail_.y_max()) {  // false for NaN
      if (const auto root = detail::newton_root(offset, guess, rail_.y_min(), rail_.y_max(), 1e-13, 5e-8)) return root;
    }
    return detail::bracketed_root(offset, rail_.y_min(), first_y_ - y, rail_.y_max(), (y - shift_y_) / cos_, 1e-13);
  }

  ProfileCurve rail_;
  TrackLayout layout_;
  std::uint64_t id_ = fastnorm::detail::new_object_id();
  double cos_ = 1, sin_ = 0;
  double shift_y_ = 0, shift_z_ = 0;
  double first_y_ = 0, last_y_ = 0;  // y of the right rail's first and last profile points
  std::shared_ptr<const RailTable> table_;  // Z and Z' of the right rail, for the contact search
};

}  // namespace fastnorm::wheelrail
