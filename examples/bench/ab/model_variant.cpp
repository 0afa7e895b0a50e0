// One header tree's wheelset model behind plain C functions, for ab_headers (ab.sh).
// ab.sh compiles this file twice, once per header tree, with the library's namespaces
// renamed (-Dfastnorm=fastnorm_a, …) and AB_VARIANT set to a or b, so that both versions
// of the headers live in one executable without clashing.
#include "bench/trajectory.hpp"

#include <cstddef>
#include <memory>
#include <vector>

#define AB_JOIN2(a, b) a##b
#define AB_JOIN(a, b) AB_JOIN2(a, b)
#define AB_NAME(name) AB_JOIN(name, AB_VARIANT)

namespace {

using namespace fastnorm_bench;

// A pose and its velocity as ab_headers passes them: y, z, roll, yaw, then forward,
// lateral, vertical, roll rate, yaw rate, pitch rate (SI).
constexpr std::size_t values_per_step = 10;

struct Model {
  std::vector<wr::WheelsetPose> poses;
  std::vector<wr::WheelsetVelocity> velocities;
  wr::Track track;
  wr::Wheelset wheelset;
  std::unique_ptr<TrajectoryRunner> runner;
};

}  // namespace

extern "C" {

/// The trajectory's poses and velocities (trajectory_poses, trajectory_velocities), flat.
void AB_NAME(ab_trajectory_)(int steps, std::vector<double>* flat) {
  const wr::Track track;
  const wr::Wheelset wheelset;
  const auto poses = trajectory_poses(track, wheelset, steps);
  const auto velocities = trajectory_velocities(wheelset, poses);
  for (std::size_t step = 0; step < poses.size(); ++step) {
    const auto& pose = poses[step];
    const auto& velocity = velocities[step];
    for (const double value : {pose.y, pose.z, pose.roll, pose.yaw, velocity.forward, velocity.lateral,
                               velocity.vertical, velocity.roll_rate, velocity.yaw_rate, velocity.pitch_rate}) {
      flat->push_back(value);
    }
  }
}

/// A model of `solver` (a fastnorm-bench --trajectory name) over `steps` flat poses.
void* AB_NAME(ab_create_)(const double* flat, std::size_t steps, const char* solver) {
  auto model = std::make_unique<Model>();
  for (std::size_t step = 0; step < steps; ++step) {
    const double* v = flat + values_per_step * step;
    wr::WheelsetPose pose;
    pose.y = v[0], pose.z = v[1], pose.roll = v[2], pose.yaw = v[3];
    wr::WheelsetVelocity velocity;
    velocity.forward = v[4], velocity.lateral = v[5], velocity.vertical = v[6];
    velocity.roll_rate = v[7], velocity.yaw_rate = v[8], velocity.pitch_rate = v[9];
    model->poses.push_back(pose);
    model->velocities.push_back(velocity);
  }
  model->runner = std::make_unique<TrajectoryRunner>(model->track, model->wheelset, model->poses,
                                                     model->velocities, solver);
  return model.release();
}

/// Evaluates steps [first, end).
void AB_NAME(ab_run_)(void* model, std::size_t first, std::size_t end) {
  static_cast<Model*>(model)->runner->run_steps(first, end);
}

/// Medians per wheel and step (s): search, h, solve, total; every step's wheel forces (N),
/// left then right; then frees the model.
void AB_NAME(ab_finish_)(void* model, double* medians, std::vector<double>* forces) {
  const std::unique_ptr<Model> owned(static_cast<Model*>(model));
  const TrajectoryRun run = owned->runner->finish();
  medians[0] = quantile(run.search, 0.5);
  medians[1] = quantile(run.distance, 0.5);
  medians[2] = quantile(run.solve, 0.5);
  medians[3] = quantile(run.total, 0.5);
  for (const auto& force : run.wheel_force) forces->insert(forces->end(), force.begin(), force.end());
}

}  // extern "C"
