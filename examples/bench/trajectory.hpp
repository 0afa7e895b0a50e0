// fastnorm-bench --trajectory: the wheelset contact model along a time history, geometry
// included (docs/performance.md §8). y(t) = 5 mm·sin(2π·1 Hz·t), yaw ψ(t) = 3 mrad·cos(2π·1 Hz·t),
// z(t) and roll(t) the rigid two-wheel contact at (y, ψ) lowered by 0.1 mm plus
// 20 µm·sin(2π·8 Hz·t), at 1 kHz; element sizes what 60 elements give at y = 0 (the model's
// default reference pose). One line per solver:
//
//   trajectory solver=<name> steps=<n> search_us=<t> h_us=<t> solve_us=<t> tangential_us=<t>
//     total_us=<t> total_p99_us=<t> switch_step_us=<t> max_err_vs_norm=<x> max_set_diff=<n>
//     roughness=<x> roughness_norm=<x> allocations_per_step=<x> allocating_steps=<n>
//     iterations_per_patch=<x> limited_solves=<n> total_halves_us=<t>/<t>
//
// The solvers' models (NORM's first) are stepped in turns of 100 steps (interleave_block),
// so that every solver meets the machine of the same minutes; total_halves_us are the
// medians of the run's first and second half, which along 2 000 steps are the motion's two
// periods, the same poses: their difference is how far the machine moved the figures (the
// first period also meets every grid size for the first time). The first steps of each turn
// find the caches as the other models left them (NORM's dense solves read some 100 MB):
// switch_step_us is the median of the first step of every turn. That is a cost of the bench's
// interleaving, not of the model, and it falls on 1 % of the steps at 100 steps a turn, where
// the 99th percentile lies: total_p99_us, over all steps, holds it. The p99 of a model alone
// is the warm_up line's alone_p99_us (warm_up.hpp).
//
// The wheelset moves forwards at 30 m/s, rolling (pitch rate −V/r0), with the pose's rates
// by central differences: each step also gives every patch's creep forces (strip theory,
// μ = 0.3, docs/wheel-rail.md §10; "+fastsim" after the name: FASTSIM), timed as
// tangential_us; total_us is search + h + solve, the normal contact, as before.
//
// A solver runs with the model's defaults (WheelsetContactOptions::starts_warm: every solver
// warm but the edge-enriched elliptic basis); "+warm" or "+cold"
// (e.g. elliptic+warm, cg+cold) starts every solve from the patch's previous contact set (CG:
// pressures), or makes it start cold. When a reduced solver runs both ways, one more line
// compares them step by step on the checked steps (the same grids and h):
//
//   warm_vs_cold solver=<name> checked=<n> max_force_diff=<x> max_err_warm=<x> max_err_cold=<x>
//     steps_set_further=<n> max_set_further=<n>
//
// max_force_diff = the largest |Fn_warm/Fn_cold − 1| of a patch; steps_set_further = the
// checked patches whose warm contact set differs from NORM's in more elements than the cold
// one's, max_set_further = by how many at most.
//
// Then, for every reduced solver named (NORM and CG take milliseconds a wheel, too slow for
// a vehicle at every step), a vehicle: four wheelsets (eight wheels) on the same trajectory,
// the first's model and three copies of it (one set of tables, docs/wheel-rail.md §9),
// each a quarter period (250 steps) ahead of the one before, every step all four evaluated
// one after the other on one thread, and spread over two threads (OpenMP, one wheelset per
// thread at a time; built without it, the line says threads=unavailable). The two vehicles
// are stepped alternately, so that both see the same machine:
//
//   vehicle solver=<name> wheels=8 threads=<n> step_us=<median> step_p99_us=<t> failed_steps=<n>
//
// step_us is the wall time of a whole vehicle step, geometry included.
//
// And for every reduced solver named, trial steps as an integrator takes them
// (docs/wheel-rail.md §9): at every step the model's history taken into one History, a trial
// pose halfway to the next step evaluated, the history restored, the step evaluated:
//
//   trial_steps solver=<name> steps=<n> history_us=<t> trial_us=<t> restore_us=<t> step_us=<t>
//     allocations_per_step=<x> allocating_steps=<n> differing_steps=<n>
//
// medians per step of both wheels; differing_steps counts the steps whose force is not that
// of a model evaluated at the steps alone, to the last bit (0 is the contract).
//
// "+cap<N>" (e.g. elliptic+cap3) stops every warm-started patch solve after N iterations
// (WheelsetContactOptions::warm_solve_iterations) with its last admissible iterate, and the
// next step goes on from where it stopped (docs/wheel-rail.md §9, a cap per warm solve);
// limited_solves counts the patch solves that ended so.
//
// Times are medians per wheel per step (p99 of the total); errors and contact-set
// differences against NORM on the same h at every 20th step (on the same grids: the grids
// depend on the geometry only); roughness = the largest
// |Fn(t+1) − 2Fn(t) + Fn(t−1)| / Fn(t) of a wheel's total normal force; allocations per
// step inside evaluate, after the first ten, and the number of those steps that allocated
// at all (-1: not counted in this build).
#pragma once

#include <fastnorm/fastnorm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "support/allocation_counter.hpp"

namespace fastnorm_bench {

namespace wr = fastnorm::wheelrail;

/// The pose of step `step` (1 kHz) of the benchmark trajectory (docs/performance.md §8).
inline wr::WheelsetPose trajectory_pose(const wr::Track& track, const wr::Wheelset& wheelset, int step) {
  const double t = 1e-3 * step;
  auto pose = wr::rigid_contact_pose(track, wheelset, 5e-3 * std::sin(2 * fastnorm::pi<> * t), 3e-3 * std::cos(2 * fastnorm::pi<> * t));
  pose.z += 0.1e-3 + 20e-6 * std::sin(2 * fastnorm::pi<> * 8 * t);
  return pose;
}

/// Its first `steps` poses (about 4 ms each: the roll and drop at which both wheels touch are searched).
inline std::vector<wr::WheelsetPose> trajectory_poses(const wr::Track& track, const wr::Wheelset& wheelset, int steps) {
  std::vector<wr::WheelsetPose> poses;
  for (int step = 0; step < steps; ++step) poses.push_back(trajectory_pose(track, wheelset, step));
  return poses;
}

inline constexpr double trajectory_speed = 30;  // m/s

/// Forward at trajectory_speed, rolling without slip at the nominal radius (pitch rate
/// −V/r0), every other rate zero.
inline wr::WheelsetVelocity rolling_velocity(const wr::Wheelset& wheelset) {
  wr::WheelsetVelocity velocity;
  velocity.forward = trajectory_speed;
  velocity.pitch_rate = -trajectory_speed / wheelset.layout().nominal_radius;
  return velocity;
}

/// The wheelset's velocities along `poses` (1 kHz): rolling_velocity plus the pose's rates
/// by central differences (one-sided at the ends).
inline std::vector<wr::WheelsetVelocity> trajectory_velocities(const wr::Wheelset& wheelset,
                                                              const std::vector<wr::WheelsetPose>& poses) {
  std::vector<wr::WheelsetVelocity> velocities(poses.size(), rolling_velocity(wheelset));
  for (std::size_t step = 0; step < poses.size(); ++step) {
    const std::size_t before = step > 0 ? step - 1 : step, after = step + 1 < poses.size() ? step + 1 : step;
    const double span = 1e-3 * static_cast<double>(after - before);
    auto& velocity = velocities[step];
    if (span == 0) continue;
    velocity.lateral = (poses[after].y - poses[before].y) / span;
    velocity.vertical = (poses[after].z - poses[before].z) / span;
    velocity.roll_rate = (poses[after].roll - poses[before].roll) / span;
    velocity.yaw_rate = (poses[after].yaw - poses[before].yaw) / span;
  }
  return velocities;
}

/// The allocations inside the timed calls of a run's steps, counted after its first ten
/// (the warm-up): per step on average and the steps with any (-1: not counted in this build).
class StepAllocations {
 public:
  static constexpr std::size_t warm_up = 10;
  /// Before the step's calls.
  void start() { before_ = fastnorm_example::allocation_count(); }
  /// After them: step `step` of the run.
  void stop(std::size_t step) {
    if (step < warm_up) return;
    const long count = fastnorm_example::allocation_count() - before_;
    total_ += count;
    steps_ += count > 0 ? 1 : 0;
  }
  bool counted(std::size_t steps) const { return steps > warm_up && fastnorm_example::allocation_count() >= 0; }
  double per_step(std::size_t steps) const {
    return counted(steps) ? static_cast<double>(total_) / static_cast<double>(steps - warm_up) : -1.0;
  }
  long steps_allocating(std::size_t steps) const { return counted(steps) ? steps_ : -1; }

 private:
  long before_ = 0, total_ = 0, steps_ = 0;
};

/// A wheel's normal contact in a step (s): search + h + solve, the lines' total_us.
inline double normal_contact_seconds(const wr::WheelContact& wheel) {
  return wheel.times.search + wheel.times.distance + wheel.times.solve;
}

/// What one solver's run records.
struct TrajectoryRun {
  std::vector<double> search, distance, solve, tangential, total;  // s, per wheel per step
  std::vector<std::array<double, 2>> wheel_force;       // Σ Fn per wheel, per step
  std::vector<std::vector<fastnorm::Solution<double>>> checked;  // every 20th step: the patches' solutions
  double allocations_per_step = -1;
  long allocating_steps = -1;  // steps after the first ten with any allocation inside evaluate
  double iterations_per_patch = 0;  // mean active-set or CG iterations of a patch solve
  long limited_solves = 0;          // patch solves stopped by their iteration limit or cap
};

/// A bench name: a solver spec, a start forced by "+warm" or "+cold" (else the default), an
/// iteration cap per warm patch solve by "+cap<N>" (WheelsetContactOptions::
/// warm_solve_iterations), and "+fastsim" for creep forces by FASTSIM
/// instead of strip theory (the default), in that order.
struct TrajectorySolver {
  fastnorm::SolverSpec<double> spec;
  std::optional<bool> warm;
  int cap = 0;  // iterations per warm patch solve; 0: none
  wr::CreepMethod creep = wr::CreepMethod::strip_theory;

  static TrajectorySolver parse(std::string name) {
    TrajectorySolver solver;
    const auto strip_suffix = [&name](const std::string& suffix) {
      const bool found =
          name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
      if (found) name.resize(name.size() - suffix.size());
      return found;
    };
    if (strip_suffix("+fastsim")) solver.creep = wr::CreepMethod::fastsim;
    const auto cap_at = name.rfind("+cap");
    if (cap_at != std::string::npos && cap_at + 4 < name.size() &&
        name.find_first_not_of("0123456789", cap_at + 4) == std::string::npos) {
      solver.cap = std::stoi(name.substr(cap_at + 4));
      FASTNORM_CHECK(solver.cap >= 1, "--trajectory-solvers: +cap<N> needs N >= 1 in " + name);
      name.resize(cap_at);
    }
    if (strip_suffix("+warm")) solver.warm = true;
    if (strip_suffix("+cold")) solver.warm = false;
    solver.spec = fastnorm::SolverSpec<double>::parse(name);
    return solver;
  }
  std::string label() const {
    return spec.name() + (!warm ? "" : *warm ? "+warm" : "+cold") + (cap > 0 ? "+cap" + std::to_string(cap) : "") +
           (creep == wr::CreepMethod::fastsim ? "+fastsim" : "");
  }
  wr::WheelsetContactOptions options() const {
    wr::WheelsetContactOptions options;
    options.solver = spec;
    options.creep.friction = 0.3;
    options.creep.method = creep;
    options.reduced_warm_start = warm;
    options.warm_solve_iterations = cap;
    if (warm) options.warm_start = *warm;  // NORM and CG
    return options;
  }
};

inline constexpr int check_every = 20;

/// One solver's model along the poses, stepped a block of steps at a time, so that the
/// bench can interleave the solvers and every solver's steps meet the machine of the same
/// minutes (a shared machine's speed drifts by tens of per cent over minutes).
class TrajectoryRunner {
 public:
  TrajectoryRunner(const wr::Track& track, const wr::Wheelset& wheelset, const std::vector<wr::WheelsetPose>& poses,
                   const std::vector<wr::WheelsetVelocity>& velocities, const std::string& solver)
      : poses_(poses), velocities_(velocities), contact_(track, wheelset, TrajectorySolver::parse(solver).options()) {}

  /// Evaluates steps [first, end) of the poses, in order, after those before `first`.
  void run_steps(std::size_t first, std::size_t end) {
    for (std::size_t step = first; step < end; ++step) {
      allocations_.start();  // inside evaluate only: the run's own records allocate too
      const auto& result = contact_.evaluate(poses_[step], velocities_[step]);
      allocations_.stop(step);
      record(step, result);
    }
  }

  /// The record of the steps run, with the run's means and allocations.
  TrajectoryRun finish() {
    run_.iterations_per_patch = solves_ > 0 ? static_cast<double>(iterations_) / static_cast<double>(solves_) : 0.0;
    run_.allocations_per_step = allocations_.per_step(poses_.size());
    run_.allocating_steps = allocations_.steps_allocating(poses_.size());
    return std::move(run_);
  }

 private:
  void record(std::size_t step, const wr::WheelsetContactResult& result) {
    std::array<double, 2> force{};
    for (std::size_t w = 0; w < 2; ++w) {
      const auto& wheel = result.wheels[w];
      run_.search.push_back(wheel.times.search);
      run_.distance.push_back(wheel.times.distance);
      run_.solve.push_back(wheel.times.solve);
      run_.tangential.push_back(wheel.times.tangential);
      run_.total.push_back(normal_contact_seconds(wheel));
      force[w] = wheel.normal_force;
      for (const auto& patch : wheel.patches) {
        iterations_ += patch.solution.iterations, ++solves_;
        run_.limited_solves += patch.solution.stopped_early() ? 1 : 0;
      }
    }
    run_.wheel_force.push_back(force);
    if (step % check_every == 0) {
      std::vector<fastnorm::Solution<double>> solutions;
      for (const auto& wheel : result.wheels) {
        for (const auto& patch : wheel.patches) solutions.push_back(patch.solution);
      }
      run_.checked.push_back(std::move(solutions));
    }
  }

  const std::vector<wr::WheelsetPose>& poses_;
  const std::vector<wr::WheelsetVelocity>& velocities_;
  wr::WheelsetContact<> contact_;
  TrajectoryRun run_;
  StepAllocations allocations_;
  long iterations_ = 0, solves_ = 0;
};

/// Steps between switches from one solver's model to the next in bench_trajectory: long
/// enough that a switch's cold caches do not move a median, short enough that every solver
/// meets each minute of the machine. They do move the 99th percentile (the first steps after a
/// switch are 1 % of the steps): the trajectory line's switch_step_us.
inline constexpr std::size_t interleave_block = 100;

inline double quantile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  const auto at = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1) + 0.5);
  return values[std::min(at, values.size() - 1)];
}

inline double roughness(const TrajectoryRun& run) {
  double largest = 0;
  for (std::size_t t = 1; t + 1 < run.wheel_force.size(); ++t) {
    for (std::size_t w = 0; w < 2; ++w) {
      const double force = run.wheel_force[t][w];
      if (force <= 0) continue;
      const double second = run.wheel_force[t + 1][w] - 2 * force + run.wheel_force[t - 1][w];
      largest = std::max(largest, std::abs(second) / force);
    }
  }
  return largest;
}

/// Force error and contact-set difference of `run` against `reference` at each checked
/// patch (NaN and -1 where the patches differ, which cannot happen on the same geometry).
struct PatchComparison {
  std::vector<double> error;
  std::vector<long> set_diff;
};

inline PatchComparison compare_patches(const TrajectoryRun& run, const TrajectoryRun& reference) {
  PatchComparison comparison;
  for (std::size_t c = 0; c < run.checked.size(); ++c) {
    const auto& ours = run.checked[c];
    const auto& theirs = reference.checked[c];
    const bool same = ours.size() == theirs.size();
    for (std::size_t k = 0; k < std::max(ours.size(), theirs.size()); ++k) {
      comparison.error.push_back(same ? std::abs(ours[k].normal_force / theirs[k].normal_force - 1) : std::nan(""));
      comparison.set_diff.push_back(same ? static_cast<long>((ours[k].in_contact != theirs[k].in_contact).count()) : -1);
    }
  }
  return comparison;
}

/// The largest value, NaN if any is NaN.
inline double largest(const std::vector<double>& values) {
  double result = 0;
  for (double value : values) result = std::isnan(value) || std::isnan(result) ? std::nan("") : std::max(result, value);
  return result;
}

inline void print_warm_vs_cold(const std::string& name, const TrajectoryRun& warm, const TrajectoryRun& cold,
                               const TrajectoryRun& norm) {
  const PatchComparison to_cold = compare_patches(warm, cold);
  const PatchComparison warm_to_norm = compare_patches(warm, norm), cold_to_norm = compare_patches(cold, norm);
  long further = 0, max_further = 0;
  for (std::size_t k = 0; k < warm_to_norm.set_diff.size(); ++k) {
    const long excess = warm_to_norm.set_diff[k] - cold_to_norm.set_diff[k];
    further += excess > 0 ? 1 : 0;
    max_further = std::max(max_further, excess);
  }
  std::printf("warm_vs_cold solver=%s checked=%zu max_force_diff=%.3e max_err_warm=%.3e max_err_cold=%.3e "
              "steps_set_further=%ld max_set_further=%ld\n",
              name.c_str(), to_cold.error.size(), largest(to_cold.error), largest(warm_to_norm.error),
              largest(cold_to_norm.error), further, max_further);
  std::fflush(stdout);
}

/// The vehicle lines of `solver` (see the top of this file): four wheelsets on `poses`, each
/// `shift` steps ahead of the one before (`poses` holds steps + 3·shift), on one and on two
/// threads, stepped alternately.
inline void bench_vehicle(const wr::Track& track, const wr::Wheelset& wheelset, const std::vector<wr::WheelsetPose>& poses,
                          int steps, int shift, const std::string& solver) {
  constexpr int wheelsets = 4;
  const TrajectorySolver parsed = TrajectorySolver::parse(solver);
  const auto options = parsed.options();
#if defined(_OPENMP)
  const std::vector<int> thread_counts{1, 2};
#else
  const std::vector<int> thread_counts{1};  // a second vehicle would run on one thread too
#endif
  struct Vehicle {
    int threads;
    std::vector<std::unique_ptr<wr::WheelsetContact<>>> wheelsets;
    std::vector<double> step_seconds;
    long failed_steps = 0;
  };
  std::vector<Vehicle> vehicles;
  for (const int threads : thread_counts) {
    Vehicle vehicle{threads, {}, {}, 0};
    // The first wheelset's model, and copies of it: one set of tables for the four.
    vehicle.wheelsets.push_back(std::make_unique<wr::WheelsetContact<>>(track, wheelset, options));
    for (int k = 1; k < wheelsets; ++k) {
      vehicle.wheelsets.push_back(std::make_unique<wr::WheelsetContact<>>(*vehicle.wheelsets.front()));
    }
    vehicles.push_back(std::move(vehicle));
  }
  for (int step = 0; step < steps; ++step) {
    for (auto& vehicle : vehicles) {
      int failed = 0;
      const auto start = std::chrono::steady_clock::now();
#if defined(_OPENMP)
#pragma omp parallel for num_threads(vehicle.threads) schedule(static) reduction(+ : failed)
#endif
      for (int k = 0; k < wheelsets; ++k) {
        const auto pose = poses[static_cast<std::size_t>(step + k * shift)];
        failed += vehicle.wheelsets[static_cast<std::size_t>(k)]->evaluate(pose).ok() ? 0 : 1;
      }
      vehicle.step_seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      vehicle.failed_steps += failed > 0 ? 1 : 0;
    }
  }
  const std::string label = parsed.label();
  for (const auto& vehicle : vehicles) {
    std::printf("vehicle solver=%s wheels=%d threads=%d step_us=%.1f step_p99_us=%.1f failed_steps=%ld\n",
                label.c_str(), 2 * wheelsets, vehicle.threads, 1e6 * quantile(vehicle.step_seconds, 0.5),
                1e6 * quantile(vehicle.step_seconds, 0.99), vehicle.failed_steps);
  }
#if !defined(_OPENMP)
  std::printf("vehicle solver=%s wheels=%d threads=unavailable (built without OpenMP)\n", label.c_str(), 2 * wheelsets);
#endif
  std::fflush(stdout);
}

/// The trial_steps line of `solver` (see the top of this file): at every step the history
/// taken into one History, a trial pose halfway to the next step evaluated (a Runge–Kutta
/// stage), the history restored and the step evaluated; each part timed (medians over the
/// steps, both wheels), the allocations of the whole counted after the first ten steps, and
/// the steps whose answer is not the plain run's to the last bit (there must be none).
inline void bench_trial_steps(const wr::Track& track, const wr::Wheelset& wheelset,
                              const std::vector<wr::WheelsetPose>& poses, const std::string& solver) {
  const TrajectorySolver parsed = TrajectorySolver::parse(solver);
  wr::WheelsetContact<> tried(track, wheelset, parsed.options()), plain(track, wheelset, parsed.options());
  wr::WheelsetContact<>::History saved;
  std::vector<double> history_seconds, trial_seconds, restore_seconds, step_seconds;
  StepAllocations allocations;
  long differing_steps = 0;
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point from, Clock::time_point to) {
    return std::chrono::duration<double>(to - from).count();
  };
  for (std::size_t step = 0; step < poses.size(); ++step) {
    wr::WheelsetPose trial = poses[step];
    if (step + 1 < poses.size()) {
      const auto& next = poses[step + 1];
      trial.y = (trial.y + next.y) / 2, trial.z = (trial.z + next.z) / 2;
      trial.roll = (trial.roll + next.roll) / 2, trial.yaw = (trial.yaw + next.yaw) / 2;
    }
    allocations.start();
    const auto start = Clock::now();
    tried.history(saved);
    const auto taken = Clock::now();
    tried.evaluate(trial);
    const auto tried_at = Clock::now();
    tried.restore(saved);
    const auto restored = Clock::now();
    const auto& result = tried.evaluate(poses[step]);
    const auto done = Clock::now();
    allocations.stop(step);
    history_seconds.push_back(seconds(start, taken));
    trial_seconds.push_back(seconds(taken, tried_at));
    restore_seconds.push_back(seconds(tried_at, restored));
    step_seconds.push_back(seconds(restored, done));
    differing_steps += result.force == plain.evaluate(poses[step]).force ? 0 : 1;
  }
  std::printf("trial_steps solver=%s steps=%zu history_us=%.1f trial_us=%.1f restore_us=%.1f step_us=%.1f "
              "allocations_per_step=%.2f allocating_steps=%ld differing_steps=%ld\n",
              parsed.label().c_str(), poses.size(), 1e6 * quantile(history_seconds, 0.5),
              1e6 * quantile(trial_seconds, 0.5), 1e6 * quantile(restore_seconds, 0.5),
              1e6 * quantile(step_seconds, 0.5),
              allocations.per_step(poses.size()), allocations.steps_allocating(poses.size()), differing_steps);
  std::fflush(stdout);
}

/// Runs NORM first (the reference), then every solver of `solvers`, and prints their lines;
/// then the warm-versus-cold comparison of every reduced solver that ran both ways, and the
/// vehicle lines of every reduced solver, along `poses` (trajectory_poses of `track` and
/// `wheelset`).
inline void bench_trajectory(const wr::Track& track, const wr::Wheelset& wheelset,
                             const std::vector<wr::WheelsetPose>& poses, const std::vector<std::string>& solvers) {
  const int steps = static_cast<int>(poses.size());
  const auto velocities = trajectory_velocities(wheelset, poses);
  // NORM and every other solver named (a "norm" among them is NORM's run), stepped in
  // turns of interleave_block steps.
  std::vector<std::unique_ptr<TrajectoryRunner>> runners;
  std::vector<std::size_t> runner_of(solvers.size(), 0);
  runners.push_back(std::make_unique<TrajectoryRunner>(track, wheelset, poses, velocities, "norm"));
  for (std::size_t s = 0; s < solvers.size(); ++s) {
    if (TrajectorySolver::parse(solvers[s]).label() == "norm") continue;
    runner_of[s] = runners.size();
    runners.push_back(std::make_unique<TrajectoryRunner>(track, wheelset, poses, velocities, solvers[s]));
  }
  for (std::size_t first = 0; first < poses.size(); first += interleave_block) {
    for (auto& runner : runners) runner->run_steps(first, std::min(first + interleave_block, poses.size()));
  }
  std::vector<TrajectoryRun> finished;
  for (auto& runner : runners) finished.push_back(runner->finish());
  const TrajectoryRun& norm = finished.front();
  struct Labelled {
    TrajectorySolver solver;
    const TrajectoryRun& run;
  };
  std::vector<Labelled> runs;
  for (std::size_t s = 0; s < solvers.size(); ++s) {
    const TrajectorySolver solver = TrajectorySolver::parse(solvers[s]);
    const TrajectoryRun& run = finished[runner_of[s]];
    const PatchComparison to_norm = compare_patches(run, norm);
    const long max_set_diff = to_norm.set_diff.empty() ? 0 : *std::max_element(to_norm.set_diff.begin(), to_norm.set_diff.end());
    // The medians of the run's two halves (along 2 000 steps, the motion's two periods: the
    // same poses), a measure of how far the machine moved the figures.
    const auto half = static_cast<std::ptrdiff_t>(run.total.size() / 2);
    const std::vector<double> first_half(run.total.begin(), run.total.begin() + half),
        second_half(run.total.begin() + half, run.total.end());
    std::vector<double> switches;  // the first step of each turn (two wheels a step), after other models' turns
    for (std::size_t k = 0; runners.size() > 1 && k < run.total.size(); ++k) {
      if ((k / 2) % interleave_block == 0) switches.push_back(run.total[k]);
    }
    std::printf("trajectory solver=%s steps=%d search_us=%.1f h_us=%.1f solve_us=%.1f tangential_us=%.1f total_us=%.1f "
                "total_p99_us=%.1f switch_step_us=%.1f "
                "max_err_vs_norm=%.3e max_set_diff=%ld roughness=%.3e roughness_norm=%.3e allocations_per_step=%.2f "
                "allocating_steps=%ld iterations_per_patch=%.2f limited_solves=%ld total_halves_us=%.1f/%.1f\n",
                solver.label().c_str(), steps, 1e6 * quantile(run.search, 0.5),
                1e6 * quantile(run.distance, 0.5), 1e6 * quantile(run.solve, 0.5), 1e6 * quantile(run.tangential, 0.5),
                1e6 * quantile(run.total, 0.5),
                1e6 * quantile(run.total, 0.99), switches.empty() ? 0.0 : 1e6 * quantile(switches, 0.5),
                largest(to_norm.error), max_set_diff, roughness(run), roughness(norm),
                run.allocations_per_step, run.allocating_steps, run.iterations_per_patch, run.limited_solves,
                1e6 * quantile(first_half, 0.5), 1e6 * quantile(second_half, 0.5));
    std::fflush(stdout);
    runs.push_back({solver, run});
  }
  // Pairs of runs of one reduced solver, one warm and one cold.
  for (const auto& warm : runs) {
    if (!warm.solver.spec.is_reduced() || !warm.solver.options().starts_warm()) continue;
    for (const auto& cold : runs) {
      if (cold.solver.spec.name() == warm.solver.spec.name() && !cold.solver.options().starts_warm()) {
        print_warm_vs_cold(warm.solver.spec.name(), warm.run, cold.run, norm);
        break;
      }
    }
  }
  const int quarter_period = 250;  // steps: a quarter of the 1 Hz motion at 1 kHz
  auto vehicle_poses = poses;  // and three quarter periods more for the phase shifts
  for (int step = steps; step < steps + 3 * quarter_period; ++step) {
    vehicle_poses.push_back(trajectory_pose(track, wheelset, step));
  }
  for (const auto& name : solvers) {
    if (!TrajectorySolver::parse(name).spec.is_reduced()) continue;
    bench_vehicle(track, wheelset, vehicle_poses, steps, quarter_period, name);
    bench_trial_steps(track, wheelset, poses, name);
  }
}

}  // namespace fastnorm_bench
