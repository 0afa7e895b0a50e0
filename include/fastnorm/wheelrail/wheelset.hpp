#pragma once
/// @file wheelset.hpp
/// A wheelset of two profiled wheels and its pose on the track (docs/wheel-rail.md §3).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

#include "fastnorm/detail/object_id.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/wheelrail/profile_curve.hpp"
#include "fastnorm/wheelrail/track.hpp"

namespace fastnorm::wheelrail {

/// Where the wheelset is (m, rad), in the track frame (x forward, y right, z down).
/// z = 0 puts the taping-line points in the track plane at zero roll; roll > 0 lowers the
/// right wheel; yaw > 0 turns the nose to the right.
struct WheelsetPose {
  double y = 0;     ///< lateral shift
  double z = 0;     ///< vertical position (down)
  double roll = 0;  ///< rotation about x_track
  double yaw = 0;   ///< rotation about the rolled z axis
};

/// The poses the wheel–rail functions accept (m, rad), one set for all of them: beyond
/// these the small-angle contact locus (docs/wheel-rail.md §4, item 1) and the profile ranges no
/// longer hold. A pose outside is rejected by name, never solved.
struct PoseLimits {
  static constexpr double lateral_shift = 0.03;  ///< |y|
  static constexpr double vertical = 0.05;       ///< |z|
  static constexpr double roll = 0.05;           ///< |roll|
  static constexpr double yaw = 0.1;             ///< |yaw|
};

/// @throws fastnorm::invalid_argument naming the coordinate of `pose` that is not finite or
///         outside PoseLimits; `what` names the caller
inline void check_pose(const WheelsetPose& pose, std::string_view what) {
  auto check = [&](double value, double limit, const char* name, const char* unit) {
    FASTNORM_CHECK(std::isfinite(value) && std::abs(value) < limit,
                   fastnorm::detail::describe(std::string(what) + ": " + name + " must lie within ±" + fastnorm::detail::to_text(limit) + " " +
                                                  unit,
                                              value));
  };
  check(pose.y, PoseLimits::lateral_shift, "y", "m");
  check(pose.z, PoseLimits::vertical, "z", "m");
  check(pose.roll, PoseLimits::roll, "roll", "rad");
  check(pose.yaw, PoseLimits::yaw, "yaw", "rad");
}

/// Dimensions of the wheelset (m).
struct WheelsetLayout {
  double nominal_radius = 0.45;            ///< rolling radius at the taping line
  double taping_line_half_distance = 0.75; ///< wheelset centre to each taping-line plane
};

/// Two identical wheels, bodies of revolution about the axle, the right one at
/// y_ws = +(d + y_w), the left at y_ws = −(d + y_w), radius r0 + F(y_w).
class Wheelset {
 public:
  using Vector3 = Eigen::Vector3d;
  using Matrix3 = Eigen::Matrix3d;

  /// A point of the contact locus: where a wheel's surface normal has no x_track component.
  struct LocusPoint {
    double profile_y = 0;    ///< y_w, the wheel profile coordinate (m)
    double radius = 0;       ///< ρ(y_w) (m)
    double radius_slope = 0; ///< dρ/dy_ws
    double angle_sine = 0;   ///< sin θ, θ the wheel angle of the point (0 = lowest)
    Vector3 point = Vector3::Zero();  ///< in the track frame (m)
  };

  /// @throws fastnorm::invalid_argument for non-positive dimensions
  explicit Wheelset(ProfileCurve wheel = s1002_wheel(), WheelsetLayout layout = {})
      : wheel_(std::move(wheel)), layout_(layout) {
    FASTNORM_CHECK(std::isfinite(layout.nominal_radius) && layout.nominal_radius > 0,
                   fastnorm::detail::describe("Wheelset: nominal_radius must be positive (m)", layout.nominal_radius));
    FASTNORM_CHECK(std::isfinite(layout.taping_line_half_distance) && layout.taping_line_half_distance > 0,
                   fastnorm::detail::describe("Wheelset: taping_line_half_distance must be positive (m)",
                                              layout.taping_line_half_distance));
    find_flange_climb_point();
  }

  /// This wheelset's identity: a number no other wheelset of the process has; a copy keeps it (the
  /// data is the same and never changes). What keeps state about a wheelset (a contact search's
  /// tables) knows it by this number, never by its address.
  std::uint64_t id() const { return id_; }
  const WheelsetLayout& layout() const { return layout_; }
  const ProfileCurve& profile() const { return wheel_; }

  /// The steepest angle of the wheel profile, atan|dF/dy_w| (rad): the flange angle.
  double flange_angle() const { return flange_angle_; }
  /// Where the flange reaches its steepest angle, coming from the tread (y_w, m): the first
  /// profile point within flange_angle_tolerance of flange_angle(). A contact on or beyond it
  /// (towards the flange tip) is at flange climb: by Nadal's criterion without friction the
  /// lateral force a wheel can take is Q·tan δ, largest there, so more lateral push lifts
  /// the wheel (docs/wheel-rail.md §5).
  double flange_climb_point() const { return climb_point_; }
  /// Whether profile coordinate y_w lies on the steepest flank or beyond it, to the tip.
  bool at_flange_climb(double profile_y) const { return (profile_y - climb_point_) * tip_direction_ >= 0; }
  /// How close (rad) to the steepest angle the climb point lies.
  static constexpr double flange_angle_tolerance = 1.75e-3;

  /// The wheelset centre C = (0, y, z − r0) in the track frame.
  Vector3 centre(const WheelsetPose& pose) const { return {0, pose.y, pose.z - layout_.nominal_radius}; }

  /// R = Rx(roll)·Rz(yaw): p_track = C + R·p_wheelset.
  static Matrix3 rotation(const WheelsetPose& pose) {
    const double cr = std::cos(pose.roll), sr = std::sin(pose.roll);
    const double cy = std::cos(pose.yaw), sy = std::sin(pose.yaw);
    Matrix3 roll, yaw;
    roll << 1, 0, 0, 0, cr, -sr, 0, sr, cr;
    yaw << cy, -sy, 0, sy, cy, 0, 0, 0, 1;
    return roll * yaw;
  }

  /// y_ws of profile coordinate y_w on `side`.
  double axle_coordinate(Side side, double profile_y) const {
    return side_sign(side) * (layout_.taping_line_half_distance + profile_y);
  }

  /// y_w of axle coordinate y_ws on `side`; empty beyond the wheel profile.
  std::optional<double> profile_coordinate(Side side, double axle_y) const {
    const double profile_y = side_sign(side) * axle_y - layout_.taping_line_half_distance;
    if (!wheel_.contains(profile_y)) return std::nullopt;
    return profile_y;
  }

  /// ρ(y_w) and dρ/dy_ws (the sign of the slope flips on the left wheel).
  ProfileValue<double> radius(Side side, double profile_y) const {
    const auto at = wheel_.evaluate(profile_y);
    return {layout_.nominal_radius + at.value, side_sign(side) * at.slope};
  }

  /// The locus point at y_w: sin θ = −ρ'·tan ψ (docs/wheel-rail.md §4, item 1), then C + R·p_ws.
  LocusPoint locus(Side side, double profile_y, const WheelsetPose& pose, const Matrix3& rotation) const {
    return locus(side, profile_y, pose, rotation, std::tan(pose.yaw));
  }

  /// The same with tan ψ given (a search over many points of one pose computes it once).
  LocusPoint locus(Side side, double profile_y, const WheelsetPose& pose, const Matrix3& rotation,
                   double tan_yaw) const {
    const auto rho = radius(side, profile_y);
    const double sine = std::clamp(-rho.slope * tan_yaw, -1.0, 1.0);
    const Vector3 on_wheel(rho.value * sine, axle_coordinate(side, profile_y), rho.value * std::sqrt(1 - sine * sine));
    return {profile_y, rho.value, rho.slope, sine, centre(pose) + rotation * on_wheel};
  }

 private:
  /// flange_angle_, climb_point_ and tip_direction_ from scans of the profile every 10 µm:
  /// the flange tip is where the radius is largest; the flank is the steepest part between
  /// the tip and the taping line (y_w = 0), and the climb point its end on the tread side.
  void find_flange_climb_point() {
    const double step = 1e-5;
    double tip_y = wheel_.y_min(), largest_radius = -std::numeric_limits<double>::infinity();
    for (double y = wheel_.y_min(); y <= wheel_.y_max(); y += step) {
      const double radius = wheel_.evaluate(y).value;
      if (radius > largest_radius) largest_radius = radius, tip_y = y;
    }
    tip_direction_ = tip_y < 0 ? -1.0 : 1.0;
    auto angle_at = [&](double y) { return std::atan(std::abs(wheel_.evaluate(y).slope)); };
    const double to_tread = -tip_direction_ * step;
    const auto on_face = [&](double y) { return wheel_.contains(y) && (y - tip_y) * to_tread <= std::abs(tip_y); };
    double steepest_y = tip_y;
    flange_angle_ = 0;
    for (double y = tip_y; on_face(y); y += to_tread) {
      if (angle_at(y) > flange_angle_) flange_angle_ = angle_at(y), steepest_y = y;
    }
    climb_point_ = steepest_y;
    for (double y = steepest_y + to_tread; on_face(y) && angle_at(y) >= flange_angle_ - flange_angle_tolerance;
         y += to_tread) {
      climb_point_ = y;
    }
  }

  ProfileCurve wheel_;
  WheelsetLayout layout_;
  std::uint64_t id_ = fastnorm::detail::new_object_id();
  double flange_angle_ = 0, climb_point_ = 0, tip_direction_ = -1;
};

}  // namespace fastnorm::wheelrail
