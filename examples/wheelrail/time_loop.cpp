// Contact in the time loop: what a vehicle-dynamics code writes around fastnorm. One
// wheelset runs along a hunting-like motion at 1 kHz, forwards at 30 m/s; at every step the
// model gets the pose and the velocities and returns the forces, moments, normal stiffness
// and creep forces of both wheels (docs/wheel-rail.md §9–10).
//
//   time_loop [--steps N] [--solver NAME] [--friction MU]
//
// Prints every 100th step: t, y, Fn and stiffness per wheel, the vertical force on the
// wheelset, each wheel's creepages (ξ, η, φ of its first patch) and creep force (on the
// wheel, track frame); then the mean time per step.
#include <fastnorm/fastnorm.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "support/arguments.hpp"

namespace wr = fastnorm::wheelrail;

int main(int argc, char** argv) {
  int steps = 500;
  std::string solver = "elliptic";
  double friction = 0.3;
  fastnorm_example::CommandLine line("time_loop", "A wheelset in the time loop: contact forces at every step.");
  line.option("--steps", steps, "N", "time steps of 1 ms", fastnorm_example::at_least(1));
  line.option("--solver", solver, "NAME", std::string("the patch solver: ") + fastnorm::SolverSpec<double>::grammar);
  line.option("--friction", friction, "MU", "Coulomb's coefficient of every patch", fastnorm_example::positive());
  return fastnorm_example::run_tool(line, argc, argv, [&] {
    // Built once: track, wheelset, and the contact model with its solvers and state.
    const wr::Track track;        // UIC60 rails, 1:40, gauge 1435 mm
    const wr::Wheelset wheelset;  // S1002 wheels, r0 = 450 mm
    wr::WheelsetContactOptions options;
    options.solver = fastnorm::SolverSpec<double>::parse(solver);
    options.grid.elements = 30;  // across the largest patch at the reference pose
    options.creep.friction = friction;
    wr::WheelsetContact<> contact(track, wheelset, options);

    // The integrator's states, here a prescribed motion: y and yaw oscillate, z and roll
    // follow the rigid contact lowered by 0.1 mm (found before the loop, not timed); the
    // wheelset runs at 30 m/s, rolling, with the rates of y and yaw and z's and roll's by
    // differences.
    const double speed = 30, omega = 2 * fastnorm::pi<>;  // m/s; the motion's 1 Hz
    std::vector<wr::WheelsetPose> poses;
    for (int step = 0; step <= steps; ++step) {
      const double t = 1e-3 * step;
      auto pose = wr::rigid_contact_pose(track, wheelset, 3e-3 * std::sin(omega * t), 2e-3 * std::cos(omega * t));
      pose.z += 0.1e-3;
      poses.push_back(pose);
    }
    std::vector<wr::WheelsetVelocity> velocities;
    for (int step = 0; step < steps; ++step) {
      const double t = 1e-3 * step;
      const auto& now = poses[static_cast<std::size_t>(step)];
      const auto& next = poses[static_cast<std::size_t>(step) + 1];
      wr::WheelsetVelocity velocity;
      velocity.forward = speed;
      velocity.pitch_rate = -speed / wheelset.layout().nominal_radius;
      velocity.lateral = 3e-3 * omega * std::cos(omega * t);
      velocity.yaw_rate = -2e-3 * omega * std::sin(omega * t);
      velocity.vertical = (next.z - now.z) / 1e-3;
      velocity.roll_rate = (next.roll - now.roll) / 1e-3;
      velocities.push_back(velocity);
    }
    const auto start = std::chrono::steady_clock::now();
    for (int step = 0; step < steps; ++step) {
      const double t = 1e-3 * step;
      const wr::WheelsetPose& pose = poses[static_cast<std::size_t>(step)];  // y, z (down), roll, yaw
      const wr::WheelsetContactResult& result = contact.evaluate(pose, velocities[static_cast<std::size_t>(step)]);
      if (!result.ok()) {
        std::fprintf(stderr, "step %d: a patch solve failed\n", step);
        return 1;
      }
      // result.force and result.moment (track frame, about the wheelset centre) go into the
      // equations of motion; each patch's stiffness into the integrator's Jacobian.
      if (step % 100 == 0) {
        const auto& left = result.wheel(wr::Side::left);
        const auto& right = result.wheel(wr::Side::right);
        std::printf("t=%.3f s y=%.3f mm Fn_left=%.1f N Fn_right=%.1f N patches=%zu+%zu vertical=%.1f N", t,
                    pose.y * 1e3, left.normal_force, right.normal_force, left.patches.size(), right.patches.size(),
                    -result.force.z());
        for (const auto* wheel : {&left, &right}) {
          for (const auto& patch : wheel->patches) std::printf(" k_%s=%.3e", wr::to_string(wheel->side), patch.stiffness);
        }
        std::printf("\n   ");
        for (const auto* wheel : {&left, &right}) {
          if (wheel->patches.empty()) continue;
          const auto& first = wheel->patches.front();
          Eigen::Vector3d creep = Eigen::Vector3d::Zero();
          for (const auto& patch : wheel->patches) creep += patch.creep_force;
          std::printf(" %s: xi=%.2e eta=%.2e phi=%.3f creep_force=(%.0f, %.0f, %.0f) N", wr::to_string(wheel->side),
                      first.creepage.longitudinal, first.creepage.lateral, first.creepage.spin, creep.x(), creep.y(),
                      creep.z());
        }
        std::printf("\n");
      }
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%d steps, %.1f us per step (both wheels, geometry and creep forces included)\n", steps,
                1e6 * seconds / steps);
    return 0;
  });
}
