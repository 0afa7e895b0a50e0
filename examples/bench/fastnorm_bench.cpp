// fastnorm-bench: times the solvers side by side in one run and prints medians and ratios
// (docs/performance.md). Three kinds of line:
//
//   fastnorm-bench [--help] [--repeats 5] [--norm-limit 6000] [--solvers EXTRA,...] [--sequence [--calls 50]] CASE...
//     case=<name> ncontact=<n> norm_s=<t> cg_s=<t> elliptic_s=<t> polynomial4_s=<t>
//          err_elliptic=<x> err_polynomial4=<x> speedup_elliptic_vs_cg=<x>
//          speedup_polynomial4_vs_cg=<x> err_cg=<x> cg_as_contact_s=<t> contact_s=<t>
//          speedup_cg_vs_contact=<x> cg_iterations_as_contact=<k> contact_iterations=<k>, then for each extra solver of --solvers (e.g. polynomial-edge:4:1):
//          <label>_s=<t> err_<label>=<x> speedup_<label>_vs_cg=<x> speedup_<label>_vs_norm=<x>
//   with --sequence, then for each case and solver (--sequence-solvers cg,elliptic,polynomial:4):
//     sequence=<name> solver=<s> calls=<n> per_call_s=<t> cold_per_call_s=<t> speedup_warm=<x>
//   fastnorm-bench --growth [--sizes 30,60,120,240,480,960] [--repeats 3]
//   fastnorm-bench --trajectory [--steps 2000] [--trajectory-solvers norm,cg,elliptic,elliptic+warm,...]: trajectory.hpp, then
//     a set_oracle line per warm reduced solver (how much of a solve is the search for its contact set): set_oracle.hpp
//     a warm_up line per reduced solver (allocations from the first step after a warm-up by trial steps): warm_up.hpp
//   fastnorm-bench --tangential [--repeats 5] [CASE...]: steady rolling on CONTACT's Hertz examples or the cases, tangential.hpp
//   fastnorm-bench --creep-accuracy CASE...: FASTSIM and strip theory against the exact path at four adhesion levels, tangential.hpp
//   fastnorm-bench --table [--repeats 5]: ContactTable lookups, multilinear and PCHIP, table_lookup.hpp
//     growth=hertz_<n>x<n> elements=<N> ncontact=<n> norm_s=<t> cg_s=<t> cg_iterations=<k>
//          cg_mb=<m> elliptic_s=<t> polynomial4_s=<t> max_rss_mb=<m>
//
// Every case is solved in approach control on its h minus its stored approach (the loaded
// surfaces, docs/validation.md §2), so that err = |Fn/Fn_norm − 1| measures the reduced
// bases. Times are medians over the repeats; each repeat runs every solver once (a slow
// spell of the machine touches all alike) and a speed-up is the median of the per-repeat
// ratios. NORM is skipped (norm_s=-) on grids of more than --norm-limit elements; the errors
// are then relative to CG's force, which equals NORM's to 1e-9 (docs/performance.md §2).
// contact_s is CONTACT's own solve time stored in the case (solve_s, single thread, 1e-9);
// cg_as_contact_s is CG's on the case as CONTACT solved it (its stored h and loading).
// A sequence is h_s = h + s·2e-5·(y − y_mid), s = 0…calls−1 (a slowly growing tilt): the
// warm per-call time is solve_next's, the cold one solve's on the same h_s; medians over the
// calls after the first. One thread throughout.
#include <fastnorm/fastnorm.hpp>

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "support/arguments.hpp"
#include "table_lookup.hpp"
#include "tangential.hpp"
#include "set_oracle.hpp"
#include "warm_up.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t middle = values.size() / 2;
  return values.size() % 2 ? values[middle] : (values[middle - 1] + values[middle]) / 2;
}

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// "-" for a solver that did not run.
std::string shown(const std::optional<double>& value) {
  if (!value) return "-";
  std::ostringstream out;
  out.precision(4);
  out << *value;
  return out.str();
}

struct Problem {
  std::string name;
  fastnorm::Grid<> grid;
  fastnorm::Material<> material;
  Eigen::VectorXd h;  // loaded: approach control
  std::optional<double> contact_seconds;
  std::optional<fastnorm::Case<>> stored;  // the case as CONTACT solved it
};

/// Medians of each solver's cold time on one h; solvers that do not run stay empty.
struct Timing {
  std::vector<std::optional<double>> seconds;
  std::vector<std::optional<fastnorm::Solution<>>> solutions;
  std::vector<std::vector<double>> per_repeat;
};

Timing time_solvers(const Problem& problem, const std::vector<std::string>& names, const std::vector<bool>& run,
                    int repeats) {
  std::vector<fastnorm::AnySolver<>> solvers;
  for (const auto& name : names) solvers.emplace_back(name, problem.grid, problem.material);
  Timing timing{std::vector<std::optional<double>>(names.size()),
                std::vector<std::optional<fastnorm::Solution<>>>(names.size()),
                std::vector<std::vector<double>>(names.size())};
  for (int r = 0; r < repeats; ++r) {
    for (std::size_t s = 0; s < solvers.size(); ++s) {
      if (!run[s]) continue;
      const auto start = Clock::now();
      timing.solutions[s] = solvers[s].solve(problem.h, fastnorm::Loading<>::approach());
      timing.per_repeat[s].push_back(seconds_since(start));
    }
  }
  for (std::size_t s = 0; s < solvers.size(); ++s) {
    if (run[s]) timing.seconds[s] = median(timing.per_repeat[s]);
  }
  return timing;
}

double median_ratio(const std::vector<double>& numerator, const std::vector<double>& denominator) {
  std::vector<double> ratios;
  for (std::size_t r = 0; r < numerator.size(); ++r) ratios.push_back(numerator[r] / denominator[r]);
  return median(ratios);
}

/// A solver name as a key: polynomial-edge:4:1 → polynomial_edge_4_1.
std::string label(std::string name) {
  std::replace(name.begin(), name.end(), ':', '_');
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

// Solver order in the case line: norm, cg, elliptic, polynomial:4, then the extras.
void bench_case(const Problem& problem, int repeats, Eigen::Index norm_limit, const std::vector<std::string>& extras) {
  std::vector<std::string> names{"norm", "cg", "elliptic", "polynomial:4"};
  names.insert(names.end(), extras.begin(), extras.end());
  const bool norm_runs = problem.grid.size() <= norm_limit;
  std::vector<bool> run(names.size(), true);
  run[0] = norm_runs;
  const Timing t = time_solvers(problem, names, run, repeats);
  const auto& reference = norm_runs ? *t.solutions[0] : *t.solutions[1];
  auto error = [&](std::size_t s) { return std::abs(t.solutions[s]->normal_force / reference.normal_force - 1); };
  std::cout.precision(4);
  std::cout << "case=" << problem.name << " ncontact=" << reference.contact_count() << " norm_s=" << shown(t.seconds[0])
            << " cg_s=" << shown(t.seconds[1]) << " elliptic_s=" << shown(t.seconds[2])
            << " polynomial4_s=" << shown(t.seconds[3]) << " err_elliptic=" << error(2)
            << " err_polynomial4=" << error(3)
            << " speedup_elliptic_vs_cg=" << median_ratio(t.per_repeat[1], t.per_repeat[2])
            << " speedup_polynomial4_vs_cg=" << median_ratio(t.per_repeat[1], t.per_repeat[3])
            << " err_cg=" << (norm_runs ? shown(error(1)) : std::string("-"));
  for (std::size_t s = 4; s < names.size(); ++s) {
    std::cout << ' ' << label(names[s]) << "_s=" << shown(t.seconds[s]) << " err_" << label(names[s]) << '='
              << error(s) << " speedup_" << label(names[s]) << "_vs_cg=" << median_ratio(t.per_repeat[1], t.per_repeat[s]);
    if (norm_runs) std::cout << " speedup_" << label(names[s]) << "_vs_norm=" << median_ratio(t.per_repeat[0], t.per_repeat[s]);
  }
  if (problem.stored && problem.contact_seconds) {
    // CG in the control CONTACT used (force), beside CONTACT's time.
    const fastnorm::CgSolver<> cg(problem.grid, problem.material);
    std::vector<double> seconds;
    int iterations = 0;
    for (int r = 0; r < repeats; ++r) {
      const auto start = Clock::now();
      iterations = cg.solve(problem.stored->undeformed_distance, problem.stored->loading).iterations;
      seconds.push_back(seconds_since(start));
    }
    std::cout << " cg_as_contact_s=" << median(seconds) << " contact_s=" << *problem.contact_seconds
              << " speedup_cg_vs_contact=" << *problem.contact_seconds / median(seconds)
              << " cg_iterations_as_contact=" << iterations
              << " contact_iterations=" << problem.stored->result->iterations;
  }
  for (std::size_t s = 0; s < names.size(); ++s) {
    if (t.solutions[s] && t.solutions[s]->status != fastnorm::Status::converged) {
      std::cout << " status_" << (s == 3 ? std::string("polynomial4") : names[s]) << '='
                << fastnorm::to_string(t.solutions[s]->status);
    }
  }
  std::cout << std::endl;
}

void bench_sequence(const Problem& problem, const std::vector<std::string>& names, int calls) {
  double y_min = problem.grid.y(0), y_max = problem.grid.y(problem.grid.my() - 1);
  std::vector<Eigen::VectorXd> sequence;
  for (int s = 0; s < calls; ++s) {
    Eigen::VectorXd h = problem.h;
    for (Eigen::Index k = 0; k < h.size(); ++k) h(k) += s * 2e-5 * (problem.grid.y_of(k) - (y_min + y_max) / 2);
    sequence.push_back(h);
  }
  for (const auto& name : names) {
    fastnorm::AnySolver<> solver(name, problem.grid, problem.material);
    std::vector<double> warm, cold;
    for (int s = 0; s < calls; ++s) {
      auto start = Clock::now();
      solver.solve_next(sequence[static_cast<std::size_t>(s)], fastnorm::Loading<>::approach());
      const double warm_seconds = seconds_since(start);
      start = Clock::now();
      solver.solve(sequence[static_cast<std::size_t>(s)], fastnorm::Loading<>::approach());
      const double cold_seconds = seconds_since(start);
      if (s > 0 || calls == 1) {
        warm.push_back(warm_seconds);
        cold.push_back(cold_seconds);
      }
    }
    std::cout.precision(4);
    std::cout << "sequence=" << problem.name << " solver=" << solver.name() << " calls=" << calls
              << " per_call_s=" << median(warm) << " cold_per_call_s=" << median(cold)
              << " speedup_warm=" << median(cold) / median(warm) << std::endl;
  }
}

double max_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // kB on Linux
}

// CG's own memory (MB): the most heap its solver, workspace and answer hold at once during
// a construction and a solve, over what was held before (-1 in a build without the
// allocation wrap).
double cg_megabytes(const Problem& problem) {
  const long before = fastnorm_example::held_bytes();
  if (before < 0) return -1;
  fastnorm_example::reset_peak_bytes();
  {
    const fastnorm::CgSolver<> cg(problem.grid, problem.material);
    fastnorm::CgWorkspace<> workspace;
    cg.solve(problem.h, fastnorm::Loading<>::approach(), workspace);
  }
  return static_cast<double>(fastnorm_example::peak_bytes() - before) / 1e6;
}

// Grids of n × n on the Hertz sphere of the peer cases (R = 0.3 m, 50 kN, ±1.2 a), smallest
// first, so that max_rss_mb, which only grows, is set by the grid of its line.
void bench_growth(const std::vector<int>& sizes, int repeats, Eigen::Index norm_limit) {
  const auto steel = fastnorm::Material<>::steel();
  const auto hertz = fastnorm::hertz_from_force(0.3, 0.3, steel.combined_modulus(), 5e4);
  const Eigen::Index reduced_limit = 240 * 240;  // the reduced assembly grows as (strips · length)²
  for (int size : sizes) {
    const auto grid = fastnorm::hertz_grid(hertz, size);
    const Problem problem{"hertz_" + std::to_string(size), grid, steel,
                          fastnorm::hertz_undeformed_distance(grid, 0.3, 0.3).array() - hertz.approach,
                          std::nullopt, std::nullopt};
    const bool reduced_runs = grid.size() <= reduced_limit;
    const Timing t = time_solvers(problem, {"norm", "cg", "elliptic", "polynomial:4"},
                                  {grid.size() <= norm_limit, true, reduced_runs, reduced_runs}, repeats);
    std::cout.precision(4);
    std::cout << "growth=hertz_" << size << 'x' << size << " elements=" << grid.size()
              << " ncontact=" << t.solutions[1]->contact_count() << " norm_s=" << shown(t.seconds[0])
              << " cg_s=" << shown(t.seconds[1]) << " cg_iterations=" << t.solutions[1]->iterations
              << " cg_mb=" << cg_megabytes(problem) << " elliptic_s=" << shown(t.seconds[2])
              << " polynomial4_s=" << shown(t.seconds[3]) << " max_rss_mb=" << max_rss_mb() << std::endl;
  }
}

struct Arguments {
  std::vector<int> sizes{30, 60, 120, 240, 480, 960};
  std::vector<std::string> cases;
  int repeats = 5, calls = 50;
  long norm_limit = 6000;
  bool growth = false, sequence = false, trajectory = false, tangential = false, creep_accuracy = false, table = false;
  int steps = 2000;
  std::vector<std::string> sequence_solvers{"cg", "elliptic", "polynomial:4"}, solvers;
  std::vector<std::string> trajectory_solvers{"norm", "cg", "elliptic", "polynomial:4", "polynomial-edge:4:1"};
};

fastnorm_example::CommandLine command_line(Arguments& a) {
  using fastnorm_example::at_least;
  fastnorm_example::CommandLine line("fastnorm-bench",
                                   "Times the solvers side by side in one run, one thread, and prints medians and "
                                   "ratios (docs/performance.md).");
  line.positional("CASE", a.cases, ".case files to time (none: --growth)", true);
  line.option("--repeats", a.repeats, "N", "runs of every solver per case; times are medians", at_least(1));
  line.option("--norm-limit", a.norm_limit, "N", "skip NORM on grids of more elements", at_least(1));
  line.option("--solvers", a.solvers, "NAME,...", "extra solvers timed beside norm, cg, elliptic, polynomial:4");
  line.flag("--sequence", a.sequence, "also time warm sequences on each case");
  line.option("--sequence-solvers", a.sequence_solvers, "NAME,...", "the solvers of --sequence");
  line.option("--calls", a.calls, "N", "calls in a --sequence", at_least(1));
  line.flag("--growth", a.growth, "time Hertz grids of growing size");
  line.option("--sizes", a.sizes, "N,...", "--growth: elements across each grid", at_least(4));
  line.flag("--trajectory", a.trajectory, "time the wheelset contact model along the 1 kHz trajectory instead");
  line.option("--steps", a.steps, "N", "--trajectory: time steps (1 ms each)", at_least(3));
  line.flag("--tangential", a.tangential, "time the steady-rolling solver on CONTACT's Hertz examples (or on the CASEs) instead");
  line.flag("--creep-accuracy", a.creep_accuracy, "FASTSIM and strip theory against the exact path on the CASEs at four adhesion levels instead");
  line.flag("--table", a.table, "time ContactTable lookups (multilinear, PCHIP) on an 85 x 21 x 5 table instead");
  line.option("--trajectory-solvers", a.trajectory_solvers, "NAME,...", "--trajectory: the solvers, NORM first anyway; NAME+warm, NAME+cold: a reduced solver started warm or cold whatever its default (both: compared step by step); NAME+capN: every warm patch solve stopped after N iterations (status budget reached), continued at the next step; NAME+fastsim: creep forces by FASTSIM instead of strip theory");
  return line;
}

int run(const Arguments& a) {
  if (a.trajectory) {
    const fastnorm::wheelrail::Track track;
    const fastnorm::wheelrail::Wheelset wheelset;
    const auto poses = fastnorm_bench::trajectory_poses(track, wheelset, a.steps);  // seconds: made once for all
    fastnorm_bench::bench_trajectory(track, wheelset, poses, a.trajectory_solvers);
    fastnorm_bench::bench_set_oracles(track, wheelset, poses, a.trajectory_solvers);
    fastnorm_bench::bench_warm_ups(track, wheelset, poses, a.trajectory_solvers);
    return 0;
  }
  if (a.table) {
    fastnorm_bench::bench_table_lookup(a.repeats);
    return 0;
  }
  if (a.creep_accuracy) {
    fastnorm_bench::bench_creep_accuracy(a.cases);
    return 0;
  }
  if (a.tangential) {
    if (a.cases.empty()) fastnorm_bench::bench_tangential(a.repeats);
    fastnorm_bench::bench_tangential_cases(a.cases, a.repeats);
    return 0;
  }
  std::vector<std::string> extra_solvers;
  for (const auto& name : a.solvers) {
    const auto spec = fastnorm::SolverSpec<double>::parse(name);
    if (spec.name() != "norm" && spec.name() != "cg" && spec.name() != "elliptic" && spec.name() != "polynomial:4") {
      extra_solvers.push_back(spec.name());
    }
  }
  if (a.growth || a.cases.empty()) bench_growth(a.sizes, a.repeats, a.norm_limit);
  std::vector<Problem> problems;
  for (const auto& path : a.cases) {
    const auto stored = fastnorm::read_case_file(path);
    const double stored_approach = stored.result ? stored.result->approach : 0.0;
    problems.push_back({stored.name, stored.grid, stored.material, stored.undeformed_distance.array() - stored_approach,
                        stored.result ? std::optional<double>(stored.result->solve_seconds) : std::nullopt, stored});
    bench_case(problems.back(), a.repeats, a.norm_limit, extra_solvers);
  }
  if (a.sequence) {
    for (const auto& problem : problems) bench_sequence(problem, a.sequence_solvers, a.calls);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Eigen::setNbThreads(1);  // one thread, whether or not the build has OpenMP
  Arguments arguments;
  auto line = command_line(arguments);
  return fastnorm_example::run_tool(line, argc, argv, [&] { return run(arguments); });
}
