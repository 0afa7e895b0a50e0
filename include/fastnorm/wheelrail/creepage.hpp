#pragma once
/// @file creepage.hpp
/// The creepages of a wheel–rail patch from the wheelset's velocities by rigid kinematics
/// (docs/wheel-rail.md §10): the rail (body 1) against the wheel (body 2) at the patch's
/// reference point, in the patch frame, CONTACT's definitions.

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <string_view>

#include "fastnorm/error.hpp"
#include "fastnorm/tangential_problem.hpp"
#include "fastnorm/wheelrail/patch.hpp"
#include "fastnorm/wheelrail/wheelset.hpp"

namespace fastnorm::wheelrail {

namespace detail {

/// a × b. By hand: Eigen's cross() lives in <Eigen/Geometry>, which adds about 0.2 s and
/// 19 MB to every file that includes fastnorm.hpp (docs/contributing.md, compile cost).
inline Eigen::Vector3d cross(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return {a.y() * b.z() - a.z() * b.y(), a.z() * b.x() - a.x() * b.z(), a.x() * b.y() - a.y() * b.x()};
}

}  // namespace detail

/// The wheelset's velocities, the rates of its pose (as CONTACT's cntc_setwheelsetvelocity):
/// m/s and rad/s, track frame (x forward, y right, z down).
struct WheelsetVelocity {
  double forward = 0;     ///< V: speed along the track (the track frame moves with it); ≠ 0
  double lateral = 0;     ///< dy/dt
  double vertical = 0;    ///< dz/dt
  double roll_rate = 0;   ///< d(roll)/dt, about x_track
  double yaw_rate = 0;    ///< d(yaw)/dt, about the rolled z axis
  /// The rotation rate about the axle: −V/r for a wheel of rolling radius r rolling
  /// forwards without slip (z is down).
  double pitch_rate = 0;
};

/// @throws fastnorm::invalid_argument, naming `who`, for velocities that are not finite or
///         a forward speed of zero (creepages are velocities over the rolling speed)
inline void check_velocity(const WheelsetVelocity& velocity, std::string_view who) {
  const auto finite = [](double value) { return std::isfinite(value); };
  FASTNORM_CHECK(finite(velocity.lateral) && finite(velocity.vertical) && finite(velocity.roll_rate) &&
                     finite(velocity.yaw_rate) && finite(velocity.pitch_rate),
                 std::string(who) + ": velocity must be finite (lateral, vertical, roll_rate, yaw_rate, pitch_rate)");
  FASTNORM_CHECK(std::isfinite(velocity.forward) && velocity.forward != 0,
                 fastnorm::detail::describe(std::string(who) + ": velocity.forward must be finite and not zero (m/s): creepages "
                                                  "are velocities over the rolling speed",
                                            velocity.forward));
}

/// A patch's creepages and the way it rolls.
struct PatchKinematics {
  Creepage<double> creepage;   ///< about the reference point: spin centre (0, 0) of the grid
  RollingDirection direction = RollingDirection::positive_x;  ///< positive_x when V > 0
  double rolling_speed = 0;    ///< |V| (m/s), by which the creepages are divided
};

/// The angular velocity (rad/s, track frame) of a wheelset oriented R = Rx(roll)·Rz(yaw)
/// and turning about its axle: Ω = roll_rate e_x + yaw_rate Rx e_z + pitch_rate R e_y
/// (docs/wheel-rail.md Eq. (W10)).
inline Eigen::Vector3d wheelset_angular_velocity(const WheelsetPose& pose, const WheelsetVelocity& velocity) {
  const double cr = std::cos(pose.roll), sr = std::sin(pose.roll);
  const Eigen::Vector3d rolled_z(0, -sr, cr);
  const Eigen::Vector3d axle = Wheelset::rotation(pose).col(1);
  return velocity.roll_rate * Eigen::Vector3d::UnitX() + velocity.yaw_rate * rolled_z + velocity.pitch_rate * axle;
}

/// The creepages at the reference point P of `frame` (docs/wheel-rail.md Eq. (W11)): with the
/// track frame moving forwards at V, the rail's material moves at −V e_x and the wheel's
/// at v_C + Ω × (P − C), v_C = (0, dy/dt, dz/dt); their difference (rail − wheel) over |V|
/// along e_x and t_s gives ξ and η, −Ω·n/|V| the spin φ (the rail does not turn).
/// @throws fastnorm::invalid_argument for velocities that are not finite or a forward speed
///         of zero
inline PatchKinematics patch_kinematics(const Wheelset& wheelset, const WheelsetPose& pose,
                                        const WheelsetVelocity& velocity, const PatchFrame& frame) {
  check_velocity(velocity, "patch_kinematics");
  const Eigen::Vector3d omega = wheelset_angular_velocity(pose, velocity);
  const Eigen::Vector3d arm = frame.reference - wheelset.centre(pose);
  const Eigen::Vector3d turning = detail::cross(omega, arm);
  const Eigen::Vector3d wheel = Eigen::Vector3d(0, velocity.lateral, velocity.vertical) + turning;
  const Eigen::Vector3d relative = -velocity.forward * Eigen::Vector3d::UnitX() - wheel;  // rail − wheel
  PatchKinematics kinematics;
  kinematics.rolling_speed = std::abs(velocity.forward);
  kinematics.direction = velocity.forward > 0 ? RollingDirection::positive_x : RollingDirection::negative_x;
  kinematics.creepage.longitudinal = relative.x() / kinematics.rolling_speed;
  kinematics.creepage.lateral = relative.dot(frame.lateral_axis()) / kinematics.rolling_speed;
  kinematics.creepage.spin = -omega.dot(frame.normal()) / kinematics.rolling_speed;
  return kinematics;
}

}  // namespace fastnorm::wheelrail
