// The paper's study (Giner-Navarro et al., Wear 2023) on fastnorm's default set-up: an
// S1002 wheelset on UIC60 rails 1:40, 200 kN. For each position the static equilibrium is
// found with full NORM; the same patches are then solved with the elliptic basis and the
// polynomial bases of grade 2…10, and their normal forces compared with NORM's.
//
//   wheelrail_study [--out DIR] [--elements N] [--quick] [--help]
//
// Positions: y = 0…6 mm at yaw 0; yaw 0, ±1°, ±2° at y = 0 and 4 mm; wheelset loads 100…300 kN
// at y = 0 and 4 mm. Prints the table of force errors and the median solve times; writes
// DIR/study.csv (every number), DIR/error_vs_y.svg, error_vs_yaw_y{0,4}.svg,
// error_vs_load_y{0,4}.svg and pressure maps DIR/patch_*.svg (NORM and elliptic outlines).
// --quick: y = 0 and 4 mm only, 30 elements (the smoke test).
#include <fastnorm/fastnorm.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "support/arguments.hpp"
#include "svg.hpp"

namespace {

namespace wr = fastnorm::wheelrail;

struct Position {
  double y_mm = 0, yaw_deg = 0, load = 2e5;
  std::string group;  // "y", "yaw" or "load"
};

struct Measured {
  std::string solver;
  double force = 0, relative_error = 0, seconds = 0;
  long contact = 0;
};

struct PatchRecord {
  wr::PatchContact norm;  // the equilibrium's patch, solved by NORM
  std::vector<Measured> by_solver;
  fastnorm::Solution<double> elliptic;  // for the pressure maps' second outline
};

struct Outcome {
  Position position;
  wr::Equilibrium equilibrium;
  std::vector<PatchRecord> patches;
};

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

template <typename Function>
double seconds_of(Function&& run) {
  const auto start = std::chrono::steady_clock::now();
  run();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct Arguments {
  std::string out_dir = "wheelrail-study";
  long elements = 60;
  bool quick = false;
};

fastnorm_example::CommandLine command_line(Arguments& a) {
  fastnorm_example::CommandLine line("wheelrail_study",
                                   "The paper's study: S1002 on UIC60, equilibria with full NORM, the same patches "
                                   "with the elliptic and polynomial bases; table, CSV and SVG figures.");
  line.option("--out", a.out_dir, "DIR", "folder for study.csv and the figures");
  line.option("--elements", a.elements, "N", "elements across the largest patch",
              fastnorm_example::within(4, static_cast<double>(fastnorm::wheelrail::PatchGridOptions::max_elements)));
  line.flag("--quick", a.quick, "y = 0 and 4 mm only, at most 30 elements (the smoke test)");
  return line;
}

std::vector<Position> study_positions(bool quick) {
  std::vector<Position> positions;
  const std::vector<double> lateral = quick ? std::vector<double>{0, 4} : std::vector<double>{0, 1, 2, 3, 4, 5, 6};
  for (double y : lateral) positions.push_back({y, 0, 2e5, "y"});
  if (!quick) {
    for (double y : {0.0, 4.0}) {
      for (double yaw : {-2.0, -1.0, 1.0, 2.0}) positions.push_back({y, yaw, 2e5, "yaw"});
      for (double load : {1e5, 1.5e5, 2.5e5, 3e5}) positions.push_back({y, 0, load, "load"});
    }
  }
  return positions;
}

std::vector<std::string> study_solvers() {
  std::vector<std::string> solvers{"elliptic"};
  for (int grade = 2; grade <= 10; ++grade) solvers.push_back("polynomial:" + std::to_string(grade));
  return solvers;
}

// 1. Equilibria with full NORM, positions shared between the cores (each search finds its
//    element sizes with the fast elliptic basis and starts NORM at that pose: §5).
std::vector<Outcome> find_equilibria(const std::vector<Position>& positions, long elements) {
  const wr::Track track;
  const wr::Wheelset wheelset;
  std::vector<Outcome> outcomes(positions.size());
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t k = next++; k < positions.size(); k = next++) {
      const auto& p = positions[k];
      wr::EquilibriumOptions options;  // NORM
      options.contact.grid.elements = elements;
      outcomes[k] = {p, wr::solve_equilibrium(track, wheelset, p.y_mm * 1e-3, p.yaw_deg * fastnorm::pi<> / 180, p.load, options),
                     {}};
    }
  };
  std::vector<std::thread> workers;
  for (unsigned t = 0; t < std::max(1u, std::min(2u, std::thread::hardware_concurrency())); ++t) workers.emplace_back(work);
  for (auto& worker : workers) worker.join();
  return outcomes;
}

// 2. The same patches with every solver, one after another (timings undisturbed): NORM
//    once, each reduced solver the median of three. Returns the speed-ups over NORM.
std::map<std::string, std::vector<double>> compare_solvers(std::vector<Outcome>& outcomes,
                                                           const std::vector<std::string>& solvers) {
  const auto material = fastnorm::Material<double>::steel();
  const auto approach = fastnorm::Loading<double>::approach();
  std::map<std::string, std::vector<double>> speedups;
  for (auto& outcome : outcomes) {
    if (!outcome.equilibrium.ok()) continue;
    for (const auto& patch : outcome.equilibrium.patches) {
      PatchRecord record{patch, {}, {}};
      const auto& h = patch.patch.undeformed_distance;
      fastnorm::Solution<double> norm;
      const double norm_seconds =
          seconds_of([&] { norm = fastnorm::NormSolver<double>(patch.patch.grid, material).solve(h, approach); });
      record.by_solver.push_back({"norm", norm.normal_force, 0, norm_seconds, static_cast<long>(norm.contact_count())});
      for (const auto& name : solvers) {
        fastnorm::Solution<double> reduced;
        std::vector<double> times;
        for (int repeat = 0; repeat < 3; ++repeat) {
          times.push_back(seconds_of(
              [&] { reduced = fastnorm::AnySolver<double>(name, patch.patch.grid, material).solve(h, approach); }));
        }
        const double time = median(times);
        record.by_solver.push_back({name, reduced.normal_force, reduced.normal_force / norm.normal_force - 1, time,
                                    static_cast<long>(reduced.contact_count())});
        speedups[name].push_back(norm_seconds / time);
        if (name == "elliptic") record.elliptic = reduced;
      }
      outcome.patches.push_back(std::move(record));
    }
  }
  return speedups;
}

// The largest |Fn/Fn_norm − 1| of solver s over the patches of one position.
double worst_error(const Outcome& outcome, std::size_t s) {
  double worst = 0;
  for (const auto& record : outcome.patches) worst = std::max(worst, std::abs(record.by_solver[s + 1].relative_error));
  return worst;
}

void write_csv_rows(std::ofstream& csv, const Outcome& outcome) {
  const auto& p = outcome.position;
  const auto& eq = outcome.equilibrium;
  int per_side[2] = {0, 0};
  for (const auto& record : outcome.patches) {
    const auto& patch = record.norm.patch;
    const int k = ++per_side[patch.frame.side == wr::Side::right];
    for (const auto& m : record.by_solver) {
      csv << p.group << ',' << p.y_mm << ',' << p.yaw_deg << ',' << p.load << ',' << to_string(eq.status) << ','
          << eq.pose.z * 1e3 << ',' << eq.pose.roll << ',' << wr::to_string(patch.frame.side) << ',' << k << ','
          << patch.frame.reference.x() * 1e3 << ',' << patch.frame.reference.y() * 1e3 << ','
          << patch.frame.contact_angle() << ',' << -patch.undeformed_distance.minCoeff() << ',' << patch.grid.mx()
          << ',' << patch.grid.my() << ',' << m.solver << ',' << m.force << ',' << m.relative_error << ','
          << m.contact << ',' << m.seconds << '\n';
    }
  }
}

// 3. The table of worst errors per position, and every number in DIR/study.csv.
void report(const std::vector<Outcome>& outcomes, const std::vector<std::string>& solvers, const Arguments& a) {
  std::ofstream csv(a.out_dir + "/study.csv");
  csv << std::setprecision(12);
  csv << "group,y_mm,yaw_deg,load_N,status,z_mm,roll_rad,wheel,patch,x_track_mm,y_track_mm,contact_angle_rad,"
         "approach_m,grid_mx,grid_my,solver,fn_N,rel_fn_err_vs_norm,ncontact,solve_s\n";
  std::printf("fastnorm wheel-rail study: S1002 on UIC60 1:40, %ld elements across the largest patch\n", a.elements);
  std::printf("force error vs full NORM: largest |Fn/Fn_norm - 1| over the patches of each position\n");
  std::printf("(np: patches; steps: contact evaluations of the equilibrium search, elliptic then NORM,\n"
              " each solving every patch once)\n\n");
  std::printf("%-5s %6s %6s %6s %-9s %3s %5s", "group", "y_mm", "yaw", "kN", "status", "np", "steps");
  for (const auto& name : solvers) std::printf(" %9s", name == "elliptic" ? "elliptic" : ("g=" + name.substr(11)).c_str());
  std::printf("\n");
  for (const auto& outcome : outcomes) {
    const auto& p = outcome.position;
    const auto& eq = outcome.equilibrium;
    std::printf("%-5s %6.2f %6.2f %6.0f %-9s %3zu %5d", p.group.c_str(), p.y_mm, p.yaw_deg, p.load / 1e3,
                eq.ok() ? "converged" : to_string(eq.status), eq.patches.size(), eq.iterations);
    for (std::size_t s = 0; s < solvers.size(); ++s) std::printf(" %9.2e", eq.ok() ? worst_error(outcome, s) : std::nan(""));
    std::printf("\n");
    write_csv_rows(csv, outcome);
  }
}

// Figures: the worst patch error per position against y, yaw or load (group), per solver.
void error_chart(const std::vector<Outcome>& outcomes, const std::vector<std::string>& solvers, const std::string& group,
                 double y_mm, const std::string& path, const std::string& title, const std::string& x_label) {
  auto x_of = [&](const Position& p) { return group == "y" ? p.y_mm : group == "yaw" ? p.yaw_deg : p.load / 1e3; };
  std::vector<fastnorm_example::Series> series;
  for (std::size_t s = 0; s < solvers.size(); ++s) {
    std::vector<std::pair<double, double>> points;
    for (const auto& outcome : outcomes) {
      const auto& p = outcome.position;
      const bool in_group = p.group == group || (p.group == "y" && group != "y");
      if (!in_group || (group != "y" && p.y_mm != y_mm) || !outcome.equilibrium.ok()) continue;
      points.emplace_back(x_of(p), worst_error(outcome, s));
    }
    std::sort(points.begin(), points.end());
    fastnorm_example::Series line{solvers[s], {}, {}};
    for (const auto& [x, y] : points) line.x.push_back(x), line.y.push_back(y);
    series.push_back(line);
  }
  fastnorm_example::write_line_chart(path, title, x_label, "|Fn / Fn_NORM - 1| (worst patch)", series, true);
}

void error_charts(const std::vector<Outcome>& outcomes, const std::vector<std::string>& solvers, const Arguments& a) {
  using fastnorm_example::number;
  error_chart(outcomes, solvers, "y", 0, a.out_dir + "/error_vs_y.svg", "Force error vs lateral shift (yaw 0, 200 kN)",
              "lateral shift y (mm)");
  if (a.quick) return;
  for (double y : {0.0, 4.0}) {
    const std::string tag = y == 0 ? "y0" : "y4";
    error_chart(outcomes, solvers, "yaw", y, a.out_dir + "/error_vs_yaw_" + tag + ".svg",
                "Force error vs yaw (y = " + number(y) + " mm, 200 kN)", "yaw (deg)");
    error_chart(outcomes, solvers, "load", y, a.out_dir + "/error_vs_load_" + tag + ".svg",
                "Force error vs load (y = " + number(y) + " mm, yaw 0)", "wheelset load (kN)");
  }
}

// Pressure maps with NORM's and the elliptic basis's contact outlines (as the paper's
// Figs. 2-4 and 6-8), for the yaw-0 200 kN positions.
void pressure_maps(const std::vector<Outcome>& outcomes, const std::string& out_dir) {
  using fastnorm_example::number;
  for (const auto& outcome : outcomes) {
    if (outcome.position.group != "y" || !outcome.equilibrium.ok()) continue;
    int per_side[2] = {0, 0};
    for (const auto& record : outcome.patches) {
      const auto& patch = record.norm.patch;
      const int k = ++per_side[patch.frame.side == wr::Side::right];
      const std::string side = wr::to_string(patch.frame.side);
      const std::string y = number(outcome.position.y_mm);
      fastnorm_example::write_patch_svg(
          out_dir + "/patch_y" + y + "_" + side + "_" + std::to_string(k) + ".svg",
          side + " wheel, y = " + y + " mm: Fn = " + number(record.norm.solution.normal_force / 1e3, "%.1f") + " kN",
          patch.grid, record.norm.solution, "NORM", &record.elliptic, "elliptic");
    }
  }
}

int run(Arguments a) {
  if (a.quick) a.elements = std::min(a.elements, 30L);
  const auto solvers = study_solvers();
  std::vector<Outcome> outcomes;
  const double equilibrium_seconds = seconds_of([&] { outcomes = find_equilibria(study_positions(a.quick), a.elements); });
  const auto speedups = compare_solvers(outcomes, solvers);
  std::filesystem::create_directories(a.out_dir);
  report(outcomes, solvers, a);
  std::printf("\nmedian speed-up over full NORM (same patch, NORM once, reduced median of 3):\n");
  for (const auto& name : solvers) {
    const auto found = speedups.find(name);  // absent when no equilibrium was found
    if (found != speedups.end()) std::printf("  %-14s %6.1fx\n", name.c_str(), median(found->second));
  }
  std::printf("equilibria (elliptic start, then NORM, 2 threads): %.1f s\n", equilibrium_seconds);
  error_charts(outcomes, solvers, a);
  pressure_maps(outcomes, a.out_dir);
  std::printf("wrote %s/study.csv and the SVG figures\n", a.out_dir.c_str());
  const bool all_converged = std::all_of(outcomes.begin(), outcomes.end(), [](const Outcome& o) { return o.equilibrium.ok(); });
  return all_converged ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  Arguments arguments;
  auto line = command_line(arguments);
  return fastnorm_example::run_tool(line, argc, argv, [&] { return run(arguments); });
}
