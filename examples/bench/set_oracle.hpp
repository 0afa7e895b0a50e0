// fastnorm-bench --trajectory, the set_oracle line of every reduced solver that starts warm
// (elliptic-edge starts cold by default, "+cold" makes any do so): how much of a warm
// patch solve is the active-set loop's search for the contact set (docs/performance.md §8).
//
// The model runs along the trajectory and records at every step the right wheel's first patch:
// its grid, h and final contact set. The recorded problems are then replayed three times by
// three workspaces of the same solver that follow the trajectory:
//   last     starts each solve from the previous step's final set (the model's warm start);
//   oracle   from this step's own final set, as a perfect predictor of the set would;
//   rebuilt  from that set too, its workspace forgotten first (every block assembled and
//            factorised anew).
// Their order rotates from step to step. The first replay meets the tables; the second times
// the solves straight after one another, the third after reading a buffer larger than the
// caches, so that no solve finds the tables of the one before it there. Only steps whose patch kept
// its grid box (size and origin) since the step before count:
//
//   set_oracle solver=<name> steps=<n> last_us=<t>/<t> oracle_us=<t>/<t> rebuilt_us=<t>/<t>
//     oracle_ratio=<x>/<x> iterations_last=<x> iterations_oracle=<x> max_force_diff=<x>
//
// Times are medians of one patch solve, straight / after the buffer; oracle_ratio the median of
// oracle/last step by step; max_force_diff the largest |Fn_last/Fn_oracle − 1| (the loop's
// paths can end on different sides of a resolved cycle).
#pragma once

#include <fastnorm/fastnorm.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "trajectory.hpp"

namespace fastnorm_bench {

/// The set_oracle line of one solver along `poses` (see the head of this file).
inline void bench_set_oracle(const wr::Track& track, const wr::Wheelset& wheelset,
                             const std::vector<wr::WheelsetPose>& poses, const std::string& solver) {
  const TrajectorySolver parsed = TrajectorySolver::parse(solver);
  const wr::WheelsetContactOptions options = parsed.options();
  struct Recorded {
    fastnorm::Grid<double> grid{1, 1, 1, 1};
    Eigen::VectorXd undeformed_distance;
    fastnorm::WarmStart<double> final_set;  // empty: no patch, or its solve failed
    const std::vector<Eigen::Index>& contact_set() const { return final_set.contact_set(); }
  };
  std::vector<Recorded> recorded(poses.size());
  {
    wr::WheelsetContact<> contact(track, wheelset, options);
    for (std::size_t step = 0; step < poses.size(); ++step) {
      const auto& wheel = contact.evaluate(poses[step]).wheel(wr::Side::right);
      if (wheel.patches.empty()) continue;
      const auto& patch = wheel.patches.front();
      recorded[step].grid = patch.patch.grid;
      recorded[step].undeformed_distance = patch.patch.undeformed_distance;
      recorded[step].final_set.remember_set(patch.solution);
    }
  }
  const auto same_box = [](const fastnorm::Grid<double>& a, const fastnorm::Grid<double>& b) {
    return a.mx() == b.mx() && a.my() == b.my() && a.x0() == b.x0() && a.y0() == b.y0();
  };

  // One solver per grid size, all sharing the segment tables of one on the largest box met,
  // as the model's solvers do (the element sizes are the model's, the same on every box).
  const auto no_steps = [&parsed] { std::printf("set_oracle solver=%s steps=0\n", parsed.label().c_str()); };
  const auto met = std::find_if(recorded.begin(), recorded.end(), [](const Recorded& step) { return !step.contact_set().empty(); });
  if (met == recorded.end()) return no_steps();
  const fastnorm::Grid<double>& sizes = met->grid;
  Eigen::Index largest_mx = 1, largest_my = 1;
  for (const auto& step : recorded) {
    largest_mx = std::max(largest_mx, step.grid.mx()), largest_my = std::max(largest_my, step.grid.my());
  }
  const fastnorm::AnySolver<double> largest(options.solver, fastnorm::Grid<double>(largest_mx, largest_my, sizes.dx(), sizes.dy()),
                                            options.material);
  std::map<std::pair<Eigen::Index, Eigen::Index>, std::unique_ptr<fastnorm::AnySolver<double>>> solvers;

  enum Start : std::size_t { last, oracle, rebuilt };
  std::array<fastnorm::AnyWorkspace<double>, 3> workspaces;
  std::array<std::array<std::vector<double>, 3>, 2> seconds;  // [straight, after the buffer][start]
  std::array<double, 3> iterations{};
  std::vector<double> ratio_straight, ratio_flushed;
  double largest_force_diff = 0;
  long counted = 0;
  std::vector<double> buffer(std::size_t(4) << 20, 1.0);  // 32 MB
  volatile double sink = 0;
  using Clock = std::chrono::steady_clock;
  for (int replay = 0; replay < 3; ++replay) {
    const bool timed = replay > 0, flushed = replay == 2;
    for (std::size_t step = 1; step < recorded.size(); ++step) {
      const Recorded& problem = recorded[step];
      if (problem.contact_set().empty() || !same_box(problem.grid, recorded[step - 1].grid)) continue;
      auto& grid_solver = solvers[{problem.grid.mx(), problem.grid.my()}];
      if (!grid_solver) grid_solver = std::make_unique<fastnorm::AnySolver<double>>(largest.for_grid(problem.grid));
      std::array<fastnorm::Solution<double>, 3> answers;
      std::array<double, 3> taken{};
      for (std::size_t turn = 0; turn < 3; ++turn) {
        const auto start = static_cast<Start>((step + turn) % 3);
        auto& workspace = workspaces[start];
        if (start == rebuilt) workspace.forget();
        workspace.start().set_contact_set(start == last ? recorded[step - 1].contact_set() : problem.contact_set());
        if (flushed) sink = sink + std::accumulate(buffer.begin(), buffer.end(), 0.0);
        const auto from = Clock::now();
        answers[start] = grid_solver->solve(problem.undeformed_distance, fastnorm::Loading<double>::approach(), workspace);
        taken[start] = std::chrono::duration<double>(Clock::now() - from).count();
      }
      if (!timed) continue;
      for (std::size_t start = 0; start < 3; ++start) seconds[flushed][start].push_back(taken[start]);
      (flushed ? ratio_flushed : ratio_straight).push_back(taken[oracle] / taken[last]);
      if (flushed) continue;
      ++counted;
      for (std::size_t start = 0; start < 3; ++start) iterations[start] += answers[start].iterations;
      if (answers[oracle].normal_force > 0) {
        largest_force_diff = std::max(largest_force_diff, std::abs(answers[last].normal_force / answers[oracle].normal_force - 1));
      }
    }
  }
  if (counted == 0) return no_steps();
  const auto median_us = [&](std::size_t flushed, Start start) { return 1e6 * quantile(seconds[flushed][start], 0.5); };
  std::printf("set_oracle solver=%s steps=%ld last_us=%.1f/%.1f oracle_us=%.1f/%.1f rebuilt_us=%.1f/%.1f "
              "oracle_ratio=%.3f/%.3f iterations_last=%.2f iterations_oracle=%.2f max_force_diff=%.1e\n",
              parsed.label().c_str(), counted, median_us(0, last), median_us(1, last), median_us(0, oracle),
              median_us(1, oracle), median_us(0, rebuilt), median_us(1, rebuilt), quantile(ratio_straight, 0.5),
              quantile(ratio_flushed, 0.5), iterations[last] / static_cast<double>(counted),
              iterations[oracle] / static_cast<double>(counted), largest_force_diff);
  std::fflush(stdout);
}

/// The set_oracle line of every reduced solver of `solvers` whose model starts warm (the loop
/// this measures), along `poses` (trajectory_poses of `track` and `wheelset`).
inline void bench_set_oracles(const wr::Track& track, const wr::Wheelset& wheelset,
                              const std::vector<wr::WheelsetPose>& poses, const std::vector<std::string>& solvers) {
  for (const auto& name : solvers) {
    const TrajectorySolver parsed = TrajectorySolver::parse(name);
    if (parsed.spec.is_reduced() && parsed.options().starts_warm()) bench_set_oracle(track, wheelset, poses, name);
  }
}

}  // namespace fastnorm_bench
