// Creepages from the wheelset's velocities and creep forces in the time loop
// (creepage.hpp, wheelset_contact.hpp, docs/wheel-rail.md §10): the kinematics against hand
// calculations on hand-made frames, the model's creep forces against FASTSIM on its
// patches, full sliding, and bad input.
#include <catch2/catch.hpp>
#include <fastnorm/fastnorm.hpp>

#include <Eigen/Geometry>  // cross
#include <cmath>
#include <string>

namespace wr = fastnorm::wheelrail;
using Catch::Matchers::Contains;

namespace {

/// A patch frame on the `side` rail at (x, y, z) with inclination δ.
wr::PatchFrame frame_at(wr::Side side, double x, double y, double z, double inclination) {
  wr::PatchFrame frame;
  frame.side = side;
  frame.reference = Eigen::Vector3d(x, y, z);
  frame.inclination = inclination;
  return frame;
}

/// The model of the creep tests: the elliptic basis on 30 elements, Coulomb's `friction`.
wr::WheelsetContactOptions creep_options(double friction) {
  wr::WheelsetContactOptions options;
  options.solver = fastnorm::SolverSpec<double>::parse("elliptic");
  options.grid.elements = 30;
  options.creep.friction = friction;
  return options;
}

/// The rigid two-wheel contact at (y, yaw), lowered by 0.1 mm.
wr::WheelsetPose lowered_pose(const wr::Track& track, const wr::Wheelset& wheelset, double y, double yaw,
                              const wr::WheelsetContactOptions& options) {
  auto pose = wr::rigid_contact_pose(track, wheelset, y, yaw, options.search);
  pose.z += 0.1e-3;
  return pose;
}

/// Forwards at 30 m/s, rolling on r0 = 0.45 m.
wr::WheelsetVelocity rolling_at_30() {
  wr::WheelsetVelocity velocity;
  velocity.forward = 30;
  velocity.pitch_rate = -30 / 0.45;
  return velocity;
}

}  // namespace

TEST_CASE("Creepages follow the rigid kinematics of hand calculations", "[wheelrail][creep]") {
  const wr::Wheelset wheelset;  // r0 = 0.45 m
  const double speed = 30, r0 = 0.45;
  for (const wr::Side side : {wr::Side::left, wr::Side::right}) {
    const double sign = side == wr::Side::right ? 1 : -1, delta = -sign * 0.05;
    SECTION(std::string(wr::to_string(side)) + ": rolling, yaw, lateral, vertical, yaw and roll rates at zero roll") {
      wr::WheelsetPose pose;
      pose.y = 2e-3, pose.z = 1e-4, pose.yaw = 4e-3;
      const wr::PatchFrame frame = frame_at(side, 2e-3, pose.y + sign * 0.752, pose.z + 3e-4, delta);
      // The arm P − C; with roll 0 the axle is (−sin ψ, cos ψ, 0).
      const Eigen::Vector3d arm = frame.reference - wheelset.centre(pose);
      const double s = std::sin(pose.yaw), c = std::cos(pose.yaw), cd = std::cos(delta), sd = std::sin(delta);
      wr::WheelsetVelocity velocity;
      velocity.forward = speed;
      velocity.pitch_rate = -speed / r0;
      velocity.lateral = 0.2, velocity.vertical = -0.05, velocity.yaw_rate = 0.3, velocity.roll_rate = 0.1;
      const double w = velocity.pitch_rate, yr = velocity.yaw_rate, rr = velocity.roll_rate;
      // The wheel's velocity at P: v_C + Ω × arm, Ω = rr e_x + yr e_z + w (−s, c, 0), by hand.
      const double ox = rr - w * s, oy = w * c, oz = yr;
      const double vx = oy * arm.z() - oz * arm.y();
      const double vy = velocity.lateral + oz * arm.x() - ox * arm.z();
      const double vz = velocity.vertical + ox * arm.y() - oy * arm.x();
      // Rail (−V e_x) minus wheel, over V, along e_x and t_s = (0, cos δ, sin δ); spin −Ω·n/V.
      const double xi = (-speed - vx) / speed, eta = (-vy * cd - vz * sd) / speed, phi = -(-oy * sd + oz * cd) / speed;
      const auto kinematics = wr::patch_kinematics(wheelset, pose, velocity, frame);
      CHECK(kinematics.creepage.longitudinal == Approx(xi).margin(1e-12));
      CHECK(kinematics.creepage.lateral == Approx(eta).margin(1e-12));
      CHECK(kinematics.creepage.spin == Approx(phi).margin(1e-12));
      CHECK(kinematics.direction == fastnorm::RollingDirection::positive_x);
      CHECK(kinematics.rolling_speed == speed);
    }
    SECTION(std::string(wr::to_string(side)) + ": pure rolling of a rolled wheelset, spin sin(roll − δ)/r0") {
      // At yaw 0, whatever the roll, a point P in the plane x = 0 has Ω × arm = −(V/r0) ρ e_x,
      // ρ its distance from the axle: ξ = ρ/r0 − 1, η = 0, φ = sin(roll − δ)/r0.
      wr::WheelsetPose pose;
      pose.roll = 0.02;
      const wr::PatchFrame frame = frame_at(side, 0, sign * 0.75, 1e-4, delta);
      const Eigen::Vector3d arm = frame.reference - wheelset.centre(pose);
      const Eigen::Vector3d axle(0, std::cos(pose.roll), std::sin(pose.roll));
      const double rho = (arm - arm.dot(axle) * axle).norm();
      wr::WheelsetVelocity velocity;
      velocity.forward = speed;
      velocity.pitch_rate = -speed / r0;
      const auto kinematics = wr::patch_kinematics(wheelset, pose, velocity, frame);
      CHECK(kinematics.creepage.longitudinal == Approx(rho / r0 - 1).margin(1e-12));
      CHECK(kinematics.creepage.lateral == Approx(0).margin(1e-12));
      CHECK(kinematics.creepage.spin == Approx(std::sin(pose.roll - delta) / r0).margin(1e-12));
      // Backwards: the same creepages' signs turn with V, the contact rolls towards −x.
      velocity.forward = -speed;
      velocity.pitch_rate = speed / r0;
      const auto backwards = wr::patch_kinematics(wheelset, pose, velocity, frame);
      CHECK(backwards.direction == fastnorm::RollingDirection::negative_x);
      CHECK(backwards.creepage.longitudinal == Approx(-(rho / r0 - 1)).margin(1e-12));
      CHECK(backwards.creepage.spin == Approx(-std::sin(pose.roll - delta) / r0).margin(1e-12));
    }
  }
}

TEST_CASE("The model's creep forces are its method's on its patches and enter its sums", "[wheelrail][creep]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  auto options = creep_options(0.3);
  const auto method = GENERATE(wr::CreepMethod::strip_theory, wr::CreepMethod::fastsim);
  options.creep.method = method;
  INFO("method " << wr::to_string(method));
  wr::WheelsetContact<> model(track, wheelset, options);
  const auto pose = lowered_pose(track, wheelset, 2e-3, 3e-3, options);
  auto velocity = rolling_at_30();
  velocity.yaw_rate = 0.05;
  const auto normal_only = model.evaluate(pose);  // a copy
  const auto& result = model.evaluate(pose, velocity);
  REQUIRE(result.ok());
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  for (const auto& wheel : result.wheels) {
    for (std::size_t k = 0; k < wheel.patches.size(); ++k) {
      const auto& patch = wheel.patches[k];
      const auto& alone = normal_only.wheel(wheel.side).patches[k];
      INFO(wr::to_string(wheel.side) << " patch " << k << ": xi " << patch.creepage.longitudinal << " eta "
                                     << patch.creepage.lateral << " phi " << patch.creepage.spin << ", Fx "
                                     << patch.traction.force_x << " Fs " << patch.traction.force_y);
      // The same normal answer (to rounding: the second solve reuses the first's assemblies);
      // creepages at the reference point; the method on its pressure.
      CHECK(patch.normal_force == Approx(alone.normal_force).epsilon(1e-12));
      const auto kinematics = wr::patch_kinematics(wheelset, pose, velocity, patch.patch.frame);
      CHECK(patch.creepage.longitudinal == kinematics.creepage.longitudinal);
      CHECK(patch.creepage.spin == kinematics.creepage.spin);
      const auto expected =
          method == wr::CreepMethod::fastsim
              ? fastnorm::solve_fastsim(patch.patch.grid, options.material, patch.solution, 0.3, kinematics.creepage,
                                        kinematics.direction)
              : fastnorm::StripTheory<>(options.material)
                    .solve(patch.patch.grid, patch.solution, 0.3, kinematics.creepage, kinematics.direction);
      CHECK(patch.traction.ok());
      CHECK(patch.traction.force_x == expected.force_x);
      CHECK(patch.traction.force_y == expected.force_y);
      CHECK(patch.traction.spin_moment == expected.spin_moment);
      CHECK(patch.traction.slip_elements > 0);
      CHECK(patch.traction.adhesion_elements > 0);
      // On the wheel: the normal force plus −(Fx e_x + Fs t_s); the moment gains the creep
      // force's about the centre and −Mn n.
      const Eigen::Vector3d creep =
          -(expected.force_x * Eigen::Vector3d::UnitX() + expected.force_y * patch.patch.frame.lateral_axis());
      CHECK((patch.creep_force - creep).norm() <= 1e-9 * creep.norm());
      CHECK((patch.force - alone.force - creep).norm() <= 1e-9 * patch.force.norm());
      const Eigen::Vector3d arm = patch.patch.frame.reference - wheelset.centre(pose);
      const Eigen::Vector3d creep_moment = arm.cross(creep) - expected.spin_moment * patch.patch.frame.normal();
      CHECK((patch.moment - alone.moment - creep_moment).norm() <= 1e-9 * patch.moment.norm());
      force += patch.force;
    }
  }
  CHECK((result.force - force).norm() <= 1e-9 * force.norm());
  CHECK(result.wheels[0].patches[0].creep_jacobian.hasNaN());  // sensitivities not asked for
  // Without velocities again: normal only, the creep cleared.
  const auto& again = model.evaluate(pose);
  CHECK((again.force - normal_only.force).norm() <= 1e-9 * normal_only.force.norm());
  CHECK(again.wheels[0].patches[0].traction.status == fastnorm::Status::not_solved);
  CHECK(again.wheels[0].patches[0].creep_force.isZero());
}

TEST_CASE("A locked wheelset slides: the creep force is mu Fn against the motion", "[wheelrail][creep]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  const auto options = creep_options(0.25);
  wr::WheelsetContact<> model(track, wheelset, options);
  const auto pose = lowered_pose(track, wheelset, 0.0, 0.0, options);
  wr::WheelsetVelocity velocity;
  velocity.forward = 10;  // no pitch rate: ξ = −1, full sliding
  const auto& result = model.evaluate(pose, velocity);
  for (const auto& wheel : result.wheels) {
    for (const auto& patch : wheel.patches) {
      CHECK(patch.creepage.longitudinal == Approx(-1).margin(1e-3));
      CHECK(patch.traction.adhesion_elements == 0);
      // On the rail +μFn along x (ξ < 0), on the wheel backwards, with a small part from spin.
      CHECK(patch.creep_force.x() == Approx(-0.25 * patch.normal_force).epsilon(1e-3));
    }
  }
}

TEST_CASE("Creep forces refuse bad velocities and options by name", "[wheelrail][creep]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  wr::WheelsetContactOptions options;
  options.grid.elements = 20;
  const auto pose = lowered_pose(track, wheelset, 0.0, 0.0, options);
  wr::WheelsetVelocity velocity;
  velocity.forward = 30;
  {
    wr::WheelsetContact<> model(track, wheelset, options);
    CHECK_THROWS_WITH(model.evaluate(pose, velocity), Contains("creep.friction"));
  }
  options.creep.friction = -0.1;
  CHECK_THROWS_WITH(wr::WheelsetContact<>(track, wheelset, options), Contains("creep.friction"));
  options.creep.friction = 0.3;
  wr::WheelsetContact<> model(track, wheelset, options);
  velocity.forward = 0;
  CHECK_THROWS_WITH(model.evaluate(pose, velocity), Contains("velocity.forward"));
  velocity.forward = 30;
  velocity.yaw_rate = std::nan("");
  CHECK_THROWS_WITH(model.evaluate(pose, velocity), Contains("velocity must be finite"));
}

TEST_CASE("The model gives each patch its method's sensitivities when asked", "[wheelrail][creep]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  auto options = creep_options(0.3);
  options.creep.sensitivities = true;
  const auto method = GENERATE(wr::CreepMethod::strip_theory, wr::CreepMethod::fastsim);
  options.creep.method = method;
  INFO("method " << wr::to_string(method));
  wr::WheelsetContact<> model(track, wheelset, options);
  const auto pose = lowered_pose(track, wheelset, 2e-3, 3e-3, options);
  const auto velocity = rolling_at_30();
  const auto& result = model.evaluate(pose, velocity);
  for (const auto& wheel : result.wheels) {
    for (const auto& patch : wheel.patches) {
      const auto kinematics = wr::patch_kinematics(wheelset, pose, velocity, patch.patch.frame);
      const auto& grid = patch.patch.grid;
      if (method == wr::CreepMethod::fastsim) {
        fastnorm::TangentialSolution<double> answer;
        fastnorm::CreepJacobian<double> expected;
        fastnorm::solve_fastsim(grid, patch.solution, 0.3, kinematics.creepage,
                                fastnorm::kalker_flexibility(fastnorm::equivalent_ellipse(grid, patch.solution),
                                                             options.material),
                                kinematics.direction, answer, &expected);
        CHECK(patch.creep_jacobian == expected);
      } else {
        // Central differences a hundred times wider than the model's: the forces are smooth
        // in the creepages, so both agree to a percent of each column.
        fastnorm::StripTheory<> strips(options.material);
        const double size = std::sqrt(static_cast<double>(patch.solution.in_contact.count()) * grid.element_area() /
                                      fastnorm::pi<double>);
        for (int column = 0; column < 3; ++column) {
          const double step = column == 2 ? 1e-5 / size : 1e-5;
          Eigen::Vector3d sides[2];
          for (int side = 0; side < 2; ++side) {
            auto shifted = kinematics.creepage;
            (column == 0 ? shifted.longitudinal : column == 1 ? shifted.lateral : shifted.spin) +=
                side == 0 ? step : -step;
            const auto answer = strips.solve(grid, patch.solution, 0.3, shifted, kinematics.direction);
            sides[side] = {answer.force_x, answer.force_y, answer.spin_moment};
          }
          const Eigen::Vector3d expected = (sides[0] - sides[1]) / (2 * step);
          INFO("column " << column << ": model " << patch.creep_jacobian.col(column).transpose() << ", wide steps "
                         << expected.transpose());
          CHECK((patch.creep_jacobian.col(column) - expected).norm() <= 0.01 * expected.norm());
        }
      }
      CHECK(patch.creep_jacobian(0, 0) < 0);  // more ξ, more negative Fx on the rail
      CHECK(patch.creep_jacobian(1, 1) < 0);
    }
  }
}
