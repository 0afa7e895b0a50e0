// fastnorm-bench --trajectory, the warm_up line of every reduced solver: how far a warm-up by
// trial steps takes a run's allocations from its first step (docs/wheel-rail.md §9,
// "Warming up"; docs/performance.md §8).
//
// Two models of the solver run the trajectory with creep forces. One is fresh. The other was
// first stepped through an envelope of poses as trial steps: its history taken, the envelope's
// poses evaluated, the history restored. Neither count skips the first steps:
//
//   warm_up solver=<name> envelope_poses=<n> steps=<n> allocations=<n> allocating_steps=<n>
//     fresh_allocations=<n> fresh_allocating_steps=<n> differing_steps=<n>
//     alone_total_us=<t> alone_p99_us=<t>
//
// alone_total_us and alone_p99_us are the median and the 99th percentile of the warmed
// model's steps (search + h + solve a wheel, as the trajectory line's total_us), from its
// first step on: the model alone, no other model stepped between its steps, as in a time
// loop with one model per wheelset.
//
// The envelope does not use the trajectory's poses. It is the rigid two-wheel contact at
// y = −5.5 … 5.5 mm every 0.25 mm and yaw −3.5, −1.5, 0, 1.5 and 3.5 mrad, lowered by 0.07, 0.1
// and 0.13 mm: the motion's range with a margin, each pose a jump from the one before.
// differing_steps counts the steps whose wheelset force differs from the fresh model's in the last bit
// (0 is the contract of restore).
#pragma once

#include <fastnorm/fastnorm.hpp>

#include <cstdio>
#include <string>
#include <vector>

#include "support/allocation_counter.hpp"
#include "trajectory.hpp"

namespace fastnorm_bench {

/// The envelope of the trajectory (see the head of this file).
inline std::vector<wr::WheelsetPose> envelope_poses(const wr::Track& track, const wr::Wheelset& wheelset) {
  std::vector<wr::WheelsetPose> poses;
  for (int k = 0; k <= 44; ++k) {
    for (const double yaw : {-3.5e-3, -1.5e-3, 0.0, 1.5e-3, 3.5e-3}) {
      const auto rigid = wr::rigid_contact_pose(track, wheelset, -5.5e-3 + 0.25e-3 * k, yaw);
      for (const double lowered : {0.07e-3, 0.1e-3, 0.13e-3}) {
        auto pose = rigid;
        pose.z += lowered;
        poses.push_back(pose);
      }
    }
  }
  return poses;
}

/// The warm_up line of one solver along `poses` (see the head of this file).
inline void bench_warm_up(const wr::Track& track, const wr::Wheelset& wheelset, const std::vector<wr::WheelsetPose>& poses,
                          const std::vector<wr::WheelsetPose>& envelope, const std::string& solver) {
  const auto velocities = trajectory_velocities(wheelset, poses);
  const TrajectorySolver parsed = TrajectorySolver::parse(solver);
  struct Run {
    long allocations = 0, allocating_steps = 0;
    std::vector<Eigen::Vector3d> forces;
    std::vector<double> totals;  // s, per wheel per step: search + h + solve
  };
  const auto run = [&](wr::WheelsetContact<>& model) {
    Run counted;
    for (std::size_t step = 0; step < poses.size(); ++step) {
      const long before = fastnorm_example::allocation_count();
      const auto& result = model.evaluate(poses[step], velocities[step]);
      const long allocations = fastnorm_example::allocation_count() - before;
      counted.allocations += allocations;
      counted.allocating_steps += allocations > 0 ? 1 : 0;
      counted.forces.push_back(result.force);
      for (const auto& wheel : result.wheels) counted.totals.push_back(normal_contact_seconds(wheel));
    }
    return counted;
  };
  wr::WheelsetContact<> fresh(track, wheelset, parsed.options()), warmed(track, wheelset, parsed.options());
  {
    const auto rolling = rolling_velocity(wheelset);  // the storage of creep forces too: its size is the patches'
    wr::WheelsetContact<>::History start;
    warmed.history(start);
    for (const auto& pose : envelope) warmed.evaluate(pose, rolling);
    warmed.restore(start);
  }
  const Run plain = run(fresh), after = run(warmed);
  long differing = 0;
  for (std::size_t step = 0; step < poses.size(); ++step) differing += plain.forces[step] != after.forces[step] ? 1 : 0;
  const bool counting = fastnorm_example::allocation_count() >= 0;
  std::printf("warm_up solver=%s envelope_poses=%zu steps=%zu allocations=%ld allocating_steps=%ld fresh_allocations=%ld "
              "fresh_allocating_steps=%ld differing_steps=%ld alone_total_us=%.1f alone_p99_us=%.1f\n",
              parsed.label().c_str(), envelope.size(), poses.size(), counting ? after.allocations : -1L,
              counting ? after.allocating_steps : -1L, counting ? plain.allocations : -1L,
              counting ? plain.allocating_steps : -1L, differing, 1e6 * quantile(after.totals, 0.5),
              1e6 * quantile(after.totals, 0.99));
  std::fflush(stdout);
}

/// The warm_up lines of every reduced solver of `solvers` along `poses`.
inline void bench_warm_ups(const wr::Track& track, const wr::Wheelset& wheelset, const std::vector<wr::WheelsetPose>& poses,
                           const std::vector<std::string>& solvers) {
  std::vector<wr::WheelsetPose> envelope;
  for (const auto& name : solvers) {
    if (!TrajectorySolver::parse(name).spec.is_reduced()) continue;
    if (envelope.empty()) envelope = envelope_poses(track, wheelset);
    bench_warm_up(track, wheelset, poses, envelope, name);
  }
}

}  // namespace fastnorm_bench
