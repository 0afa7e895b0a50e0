// Contact in the time loop: what a vehicle-dynamics code writes around fastnorm. One
// wheelset runs along a hunting-like motion at 1 kHz; at every step the model gets the
// pose and returns the forces, moments and normal stiffness of both wheels.
//
//   time_loop [--steps N] [--solver NAME]
//
// Prints every 100th step: t, y, Fn and stiffness per wheel, and the vertical force on the
// wheelset; then the mean time per step.
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
  fastnorm_example::CommandLine line("time_loop", "A wheelset in the time loop: contact forces at every step.");
  line.option("--steps", steps, "N", "time steps of 1 ms", fastnorm_example::at_least(1));
  line.option("--solver", solver, "NAME", std::string("the patch solver: ") + fastnorm::SolverSpec<double>::grammar);
  return fastnorm_example::run_tool(line, argc, argv, [&] {
    // Built once: track, wheelset, and the contact model with its solvers and state.
    const wr::Track track;        // UIC60 rails, 1:40, gauge 1435 mm
    const wr::Wheelset wheelset;  // S1002 wheels, r0 = 450 mm
    wr::WheelsetContactOptions options;
    options.solver = fastnorm::SolverSpec<double>::parse(solver);
    options.grid.elements = 30;  // across the largest patch at the reference pose
    wr::WheelsetContact<> contact(track, wheelset, options);

    // The integrator's states, here a prescribed motion: y and yaw oscillate, z and roll
    // follow the rigid contact lowered by 0.1 mm (found before the loop, not timed).
    std::vector<wr::WheelsetPose> poses;
    for (int step = 0; step < steps; ++step) {
      const double t = 1e-3 * step;
      auto pose = wr::rigid_contact_pose(track, wheelset, 3e-3 * std::sin(2 * fastnorm::pi<> * t), 2e-3 * std::cos(2 * fastnorm::pi<> * t));
      pose.z += 0.1e-3;
      poses.push_back(pose);
    }
    const auto start = std::chrono::steady_clock::now();
    for (int step = 0; step < steps; ++step) {
      const double t = 1e-3 * step;
      const wr::WheelsetPose& pose = poses[static_cast<std::size_t>(step)];  // y, z (down), roll, yaw
      const wr::WheelsetContactResult& result = contact.evaluate(pose);
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
        std::printf("\n");
      }
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%d steps, %.1f us per step (both wheels, geometry included)\n", steps, 1e6 * seconds / steps);
    return 0;
  });
}
