// fastnorm-bench --tangential: the steady-rolling solvers (tangential_solver.hpp, fastsim.hpp) on CONTACT's
// two Hertzian examples of ../shared/peer-tangential (docs/tangential.md §8), built here from
// their definitions: "tractcurv" (h = 0.8 x² + 0.2814 y² per metre, a/b = 0.5, 48 × 44
// elements of 0.2889 × 0.6304 mm, Fn = 106.7 kN, μ = 0.33) at four longitudinal creepages
// from a quarter of the area sliding to full slip, and "fastsim" (h = 0.8464 x² + 2.406 y²,
// 44 × 44 elements of 0.4 × 0.2 mm, Fn = 82 kN, μ = 0.3, η = −6.25e-4, φ = 0.625 rad/m);
// G = 82 GPa, ν = 0.28. One line per problem:
//
//   tangential case=<name> elements=<N> ncontact=<n> xi=<x> eta=<x> phi=<x> solve_ms=<median>
//     sweeps=<k> nadh=<n> nslip=<n> fx=<N> fy=<N> mz=<N m>
//
// With .case files (e.g. CONTACT's wheel–rail patches in ../shared/peer-cases), each case's
// normal problem as stored, then steady rolling with μ = 0.3 at ξ = 1e-3, η = 5e-4 and
// φ = 0.5 rad/m (partial slip on those patches), rolling towards +x:
//
//   tangential case=<file name> elements=<N> ncontact=<n> ... (the same fields)
//
// and after each, the same problem by FASTSIM (fastsim.hpp: Kalker's flexibilities of the
// equivalent ellipse, the NORM pressure as its bound) and by strip theory (strip_theory.hpp),
// with their differences from the exact path in μFn (forces) and μFn·c (moment, c = √(ab) of
// the equivalent ellipse):
//
//   fastsim case=<name> solve_us=<median> speedup=<exact/fastsim> nadh=<n> nslip=<n> fx=<N> fy=<N>
//     mz=<N m> dfx=<μFn> dfy=<μFn> dmz=<μFn c>
//   strip_theory case=<name> ... (the same fields)
//
// and the exact path once more with CONTACT's stopping rule at the EPS of CONTACT's wheel–rail
// runs (TangentialStop::rms_change, tolerance 10⁻⁵: the root mean square of a sweep's traction
// changes at most 10⁻⁵ times the tractions'; the default stops when no traction changes by
// more than 10⁻⁹ μ·max p_n), with its differences from the default's answer:
//
//   contact_rule case=<name> eps=1e-05 solve_ms=<median> sweeps=<k> speedup=<default/this> nadh=<n>
//     nslip=<n> dfx=<μFn> dfy=<μFn> dmz=<μFn c>
//
// The normal problem is solved once by NORM and the solver's tables built once; the times
// are medians over --repeats solves (the fast paths' of 100 solves each), interleaved, one thread.
//
// With --creep-accuracy, the fast paths' accuracy against the exact path on each case (issue
// 29, docs/validation.md §7): the creepages (ξ, η, φ) = s·(10⁻³, 5·10⁻⁴, 0.5 rad/m), μ = 0.3,
// scaled so that the exact path's adhesion fraction is about 0.2, 0.5, 0.8 and 0.95
// (bisection on log s over a factor 5 below FASTSIM's scale for the level, 7 exact solves:
// s within 6 %), FASTSIM and strip theory at the same creepages; per case and level (exact_ms
// the last bisection solve's), then each method's largest differences:
//
//   creep_accuracy case=<name> target_adhesion=<f> scale=<s> adhesion_exact=<f> exact_ms=<t>
//     fastsim adhesion=<f> dfx=<μFn> dfy=<μFn> dmz=<μFn c>
//     strip_theory adhesion=<f> dfx=<μFn> dfy=<μFn> dmz=<μFn c>
//   creep_accuracy_summary method=<m> patches=<n> max_dfx=<μFn> max_dfy=<μFn> max_dmz=<μFn c>
//     forces_within_0.05=<k>/<n> moment_within_0.08=<k>/<n>
#pragma once

#include <fastnorm/fastnorm.hpp>
#include <fastnorm/tangential_solver.hpp>

#include <cmath>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace fastnorm_bench {

/// Times `repeats` solves of one steady-rolling problem by the exact path (with its default
/// stopping rule and with CONTACT's), by FASTSIM (Kalker's flexibilities of the equivalent
/// ellipse, on the same NORM pressure) and by strip theory, interleaved, and prints a line for
/// each; the fast paths' times are medians of samples of `batch` solves each.
inline void time_steady_rolling(const std::string& name, const fastnorm::Grid<>& grid, const fastnorm::Material<>& material,
                                const fastnorm::Solution<>& normal, double friction,
                                const fastnorm::Creepage<>& creepage, int repeats) {
  const fastnorm::SteadyRollingSolver<> rolling(grid, material);
  fastnorm::TangentialOptions<> contact_options;
  contact_options.stop = fastnorm::TangentialStop::rms_change;
  contact_options.tolerance = 1e-5;
  const fastnorm::SteadyRollingSolver<> contact_rule(grid, material, fastnorm::RollingDirection::positive_x, contact_options);
  const auto ellipse = fastnorm::equivalent_ellipse(grid, normal);
  const auto flexibility = fastnorm::kalker_flexibility(ellipse, material);
  const int batch = 100;
  fastnorm::StripTheory<> strips(material);
  std::vector<double> times, contact_times, fast_times, strip_times;
  fastnorm::TangentialSolution<> answer, contact_answer, fast, strip;
  for (int r = 0; r < repeats; ++r) {
    auto start = std::chrono::steady_clock::now();
    answer = rolling.solve(normal, friction, creepage);
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    start = std::chrono::steady_clock::now();
    contact_answer = contact_rule.solve(normal, friction, creepage);
    contact_times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    start = std::chrono::steady_clock::now();
    for (int b = 0; b < batch; ++b) fast = fastnorm::solve_fastsim(grid, normal, friction, creepage, flexibility);
    fast_times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / batch);
    start = std::chrono::steady_clock::now();
    for (int b = 0; b < batch; ++b) strips.solve(grid, normal, friction, creepage, fastnorm::RollingDirection::positive_x, strip);
    strip_times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / batch);
  }
  std::sort(times.begin(), times.end());
  std::sort(contact_times.begin(), contact_times.end());
  std::sort(fast_times.begin(), fast_times.end());
  std::sort(strip_times.begin(), strip_times.end());
  const double exact_time = times[times.size() / 2];
  std::printf("tangential case=%s elements=%ld ncontact=%ld xi=%g eta=%g phi=%g solve_ms=%.2f sweeps=%d nadh=%ld "
              "nslip=%ld fx=%.1f fy=%.1f mz=%.4f\n",
              name.c_str(), static_cast<long>(grid.size()), static_cast<long>(normal.in_contact.count()),
              creepage.longitudinal, creepage.lateral, creepage.spin, exact_time * 1e3, answer.sweeps,
              static_cast<long>(answer.adhesion_elements), static_cast<long>(answer.slip_elements), answer.force_x,
              answer.force_y, answer.spin_moment);
  // Differences from the exact path in μFn and μFn·c, c = √(ab) of the equivalent ellipse.
  const double scale = friction * normal.normal_force, c = std::sqrt(ellipse.a * ellipse.b);
  const double contact_time = contact_times[contact_times.size() / 2];
  std::printf("contact_rule case=%s eps=%.0e solve_ms=%.2f sweeps=%d speedup=%.2f nadh=%ld nslip=%ld dfx=%.1e dfy=%.1e "
              "dmz=%.1e\n",
              name.c_str(), contact_options.tolerance, contact_time * 1e3, contact_answer.sweeps,
              exact_time / contact_time, static_cast<long>(contact_answer.adhesion_elements),
              static_cast<long>(contact_answer.slip_elements), (contact_answer.force_x - answer.force_x) / scale,
              (contact_answer.force_y - answer.force_y) / scale,
              (contact_answer.spin_moment - answer.spin_moment) / (scale * c));
  for (int method = 0; method < 2; ++method) {
    const auto& result = method == 0 ? fast : strip;
    const double time = method == 0 ? fast_times[fast_times.size() / 2] : strip_times[strip_times.size() / 2];
    std::printf("%s case=%s solve_us=%.1f speedup=%.0f nadh=%ld nslip=%ld fx=%.1f fy=%.1f mz=%.4f dfx=%.4f dfy=%.4f "
                "dmz=%.4f\n",
                method == 0 ? "fastsim" : "strip_theory", name.c_str(), time * 1e6, exact_time / time,
                static_cast<long>(result.adhesion_elements), static_cast<long>(result.slip_elements), result.force_x,
                result.force_y, result.spin_moment, (result.force_x - answer.force_x) / scale,
                (result.force_y - answer.force_y) / scale, (result.spin_moment - answer.spin_moment) / (scale * c));
  }
}

inline void bench_tangential_cases(const std::vector<std::string>& paths, int repeats) {
  for (const auto& path : paths) {
    const auto stored = fastnorm::read_case_file(path);
    const auto normal = fastnorm::NormSolver<>(stored.grid, stored.material).solve(stored.undeformed_distance, stored.loading);
    fastnorm::Creepage<> creepage;
    creepage.longitudinal = 1e-3;
    creepage.lateral = 5e-4;
    creepage.spin = 0.5;
    time_steady_rolling(stored.name, stored.grid, stored.material, normal, 0.3, creepage, repeats);
  }
}

inline void bench_tangential(int repeats) {
  struct Problem {
    const char* name;
    double a1, b1, dx, dy;
    Eigen::Index mx, my;
    double normal_force, friction, xi, eta, phi;
  };
  const std::vector<Problem> problems{
      {"tractcurv", 0.8, 0.2814, 0.2889e-3, 0.6304e-3, 48, 44, 106700, 0.33, 4e-4, 0, 0},
      {"tractcurv", 0.8, 0.2814, 0.2889e-3, 0.6304e-3, 48, 44, 106700, 0.33, 1.6e-3, 0, 0},
      {"tractcurv", 0.8, 0.2814, 0.2889e-3, 0.6304e-3, 48, 44, 106700, 0.33, 2.8e-3, 0, 0},
      {"tractcurv", 0.8, 0.2814, 0.2889e-3, 0.6304e-3, 48, 44, 106700, 0.33, 1e-2, 0, 0},
      {"fastsim", 0.8464, 2.406, 0.4e-3, 0.2e-3, 44, 44, 82000, 0.3, 0, -6.25e-4, 0.625},
  };
  const double shear_modulus = 82e9, poisson_ratio = 0.28;
  const fastnorm::Material<> material(2 * shear_modulus * (1 + poisson_ratio), poisson_ratio);
  for (const Problem& problem : problems) {
    const fastnorm::Grid<> grid(problem.mx, problem.my, problem.dx, problem.dy,
                                -static_cast<double>(problem.mx - 1) * problem.dx / 2,
                                -static_cast<double>(problem.my - 1) * problem.dy / 2);
    Eigen::VectorXd h(grid.size());
    for (Eigen::Index k = 0; k < grid.size(); ++k) {
      const double x = grid.x(grid.i_of(k)), y = grid.y(grid.j_of(k));
      h(k) = problem.a1 * x * x + problem.b1 * y * y;
    }
    const auto normal =
        fastnorm::NormSolver<>(grid, material).solve(h, fastnorm::Loading<>::force(problem.normal_force));
    fastnorm::Creepage<> creepage;
    creepage.longitudinal = problem.xi;
    creepage.lateral = problem.eta;
    creepage.spin = problem.phi;
    time_steady_rolling(problem.name, grid, material, normal, problem.friction, creepage, repeats);
  }
}

/// FASTSIM against the exact path at four adhesion levels on each case (see the top of
/// this file).
inline void bench_creep_accuracy(const std::vector<std::string>& paths) {
  const double friction = 0.3;
  const std::vector<double> levels{0.2, 0.5, 0.8, 0.95};
  struct Summary {
    double largest_force_x = 0, largest_force_y = 0, largest_moment = 0;
    int count = 0, forces_within = 0, moment_within = 0;
    void add(double dfx, double dfy, double dmz) {
      largest_force_x = std::max(largest_force_x, std::abs(dfx));
      largest_force_y = std::max(largest_force_y, std::abs(dfy));
      largest_moment = std::max(largest_moment, std::abs(dmz));
      ++count;
      forces_within += std::abs(dfx) <= 0.05 && std::abs(dfy) <= 0.05 ? 1 : 0;
      moment_within += std::abs(dmz) <= 0.08 ? 1 : 0;
    }
    void print(const char* method) const {
      std::printf("creep_accuracy_summary method=%s patches=%d max_dfx=%.4f max_dfy=%.4f max_dmz=%.4f "
                  "forces_within_0.05=%d/%d moment_within_0.08=%d/%d\n",
                  method, count, largest_force_x, largest_force_y, largest_moment, forces_within, count, moment_within,
                  count);
    }
  };
  Summary summaries[2];
  for (const auto& path : paths) {
    const auto stored = fastnorm::read_case_file(path);
    const auto normal = fastnorm::NormSolver<>(stored.grid, stored.material).solve(stored.undeformed_distance, stored.loading);
    const fastnorm::SteadyRollingSolver<> rolling(stored.grid, stored.material);
    const auto ellipse = fastnorm::equivalent_ellipse(stored.grid, normal);
    const auto flexibility = fastnorm::kalker_flexibility(ellipse, stored.material);
    fastnorm::StripTheory<> strips(stored.material);
    const auto scaled = [](double scale) {
      fastnorm::Creepage<> creepage;
      creepage.longitudinal = 1e-3 * scale;
      creepage.lateral = 5e-4 * scale;
      creepage.spin = 0.5 * scale;
      return creepage;
    };
    const auto adhesion = [](const fastnorm::TangentialSolution<>& answer) {
      return static_cast<double>(answer.adhesion_elements) /
             static_cast<double>(answer.adhesion_elements + answer.slip_elements);
    };
    const double scale_force = friction * normal.normal_force, c = std::sqrt(ellipse.a * ellipse.b);
    for (const double level : levels) {
      // FASTSIM's scale for the level first (microseconds a solve), then the exact path's by
      // bisection on log s below it: the exact path adheres less at the same creepages.
      double low = std::log(1e-4), high = std::log(1e2);  // adhesion falls as s grows
      for (int step = 0; step < 50; ++step) {
        const double middle = (low + high) / 2;
        const auto fast = fastnorm::solve_fastsim(stored.grid, normal, friction, scaled(std::exp(middle)), flexibility);
        (adhesion(fast) > level ? low : high) = middle;
      }
      high = (low + high) / 2, low = high + std::log(0.2);
      double exact_seconds = 0;
      fastnorm::TangentialSolution<> exact;
      for (int step = 0; step < 7; ++step) {
        const double middle = (low + high) / 2;
        const auto start = std::chrono::steady_clock::now();
        exact = rolling.solve(normal, friction, scaled(std::exp(middle)));
        exact_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        (adhesion(exact) > level ? low : high) = middle;
      }
      const double scale = std::exp((low + high) / 2);
      exact = rolling.solve(normal, friction, scaled(scale));
      const auto fast = fastnorm::solve_fastsim(stored.grid, normal, friction, scaled(scale), flexibility);
      const auto strip = strips.solve(stored.grid, normal, friction, scaled(scale));
      std::printf("creep_accuracy case=%s target_adhesion=%.2f scale=%.4g adhesion_exact=%.3f exact_ms=%.1f%s\n",
                  stored.name.c_str(), level, scale, adhesion(exact), exact_seconds * 1e3,
                  exact.ok() ? "" : " exact_not_converged");
      for (int method = 0; method < 2; ++method) {
        const auto& answer = method == 0 ? fast : strip;
        const double dfx = (answer.force_x - exact.force_x) / scale_force;
        const double dfy = (answer.force_y - exact.force_y) / scale_force;
        const double dmz = (answer.spin_moment - exact.spin_moment) / (scale_force * c);
        std::printf("  %s adhesion=%.3f dfx=%.4f dfy=%.4f dmz=%.4f\n", method == 0 ? "fastsim" : "strip_theory",
                    adhesion(answer), dfx, dfy, dmz);
        summaries[method].add(dfx, dfy, dmz);
      }
      std::fflush(stdout);
    }
  }
  for (int method = 0; method < 2; ++method) summaries[method].print(method == 0 ? "fastsim" : "strip_theory");
}

}  // namespace fastnorm_bench
