// Full NORM against Hertz theory: a sphere on a plane and an ellipsoidal contact, steel
// on steel, on refined grids, one row per grid with the relative differences. Then the
// reduced solvers against full NORM on the same problems (approach control, as
// docs/method.md measures them): force error, contact-set mismatch and speed-up.
//
//   hertz_comparison [--quick]
#include <fastnorm/fastnorm.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

void compare(const char* shape, double radius_x, double radius_y, double force, const std::vector<int>& sizes) {
  const auto steel = fastnorm::Material<>::steel();
  const auto hertz = fastnorm::hertz_from_force(radius_x, radius_y, steel.combined_modulus(), force);
  std::printf("\n%s: R_x = %.3f m, R_y = %.3f m, Fn = %.0f N; Hertz a = %.4f mm, b = %.4f mm, p0 = %.1f MPa, "
              "approach = %.3f um\n",
              shape, radius_x, radius_y, force, hertz.semi_axis_x * 1e3, hertz.semi_axis_y * 1e3,
              hertz.max_pressure * 1e-6, hertz.approach * 1e6);
  std::printf("%7s %9s %13s %10s %13s %10s %10s %9s %8s\n", "grid", "ncontact", "approach_um", "err",
              "pmax_MPa", "err", "area_err", "iters", "solve_s");
  for (int n : sizes) {
    const auto grid = fastnorm::hertz_grid(hertz, n, 1.25);
    const fastnorm::NormSolver<> solver(grid, steel);
    const auto start = std::chrono::steady_clock::now();
    const auto solution = solver.solve(fastnorm::hertz_undeformed_distance(grid, radius_x, radius_y),
                                       fastnorm::Loading<>::force(force));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double area = static_cast<double>(solution.contact_count()) * grid.element_area();
    std::printf("%3dx%-3d %9ld %13.4f %10.2e %13.2f %10.2e %10.2e %9d %8.3f  %s\n", n, n,
                static_cast<long>(solution.contact_count()), solution.approach * 1e6,
                solution.approach / hertz.approach - 1, solution.pressure.maxCoeff() * 1e-6,
                solution.pressure.maxCoeff() / hertz.max_pressure - 1,
                area / (fastnorm::pi<> * hertz.semi_axis_x * hertz.semi_axis_y) - 1, solution.iterations, seconds,
                fastnorm::to_string(solution.status));
  }
}

template <typename Run>
double seconds_of(Run run) {
  const auto start = std::chrono::steady_clock::now();
  run();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void compare_reduced(const char* shape, double radius_x, double radius_y, double force, int n) {
  const auto steel = fastnorm::Material<>::steel();
  const auto hertz = fastnorm::hertz_from_force(radius_x, radius_y, steel.combined_modulus(), force);
  const auto grid = fastnorm::hertz_grid(hertz, n, 1.25);
  const Eigen::VectorXd h = fastnorm::hertz_undeformed_distance(grid, radius_x, radius_y).array() - hertz.approach;
  const auto loading = fastnorm::Loading<>::approach();
  fastnorm::Solution<> reference;
  const double norm_seconds = seconds_of([&] { reference = fastnorm::NormSolver<>(grid, steel).solve(h, loading); });
  std::printf("\n%s, %dx%d, approach control: full NORM %ld contact elements, %.3f s\n", shape, n, n,
              static_cast<long>(reference.contact_count()), norm_seconds);
  std::printf("%-22s %12s %10s %10s %9s\n", "solver", "force_err", "mismatch", "speedup", "status");
  for (const char* name : {"elliptic", "polynomial:4", "elliptic-edge", "polynomial-edge", "polynomial-edge:4:2"}) {
    const fastnorm::AnySolver<> solver(name, grid, steel);
    fastnorm::Solution<> solution;
    const double seconds = seconds_of([&] { solution = solver.solve(h, loading); });
    std::printf("%-22s %12.2e %10ld %9.1fx %9s\n", solver.name().c_str(),
                std::abs(solution.normal_force / reference.normal_force - 1),
                static_cast<long>((solution.in_contact != reference.in_contact).count()), norm_seconds / seconds,
                fastnorm::to_string(solution.status));
  }
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::string(argv[1]) == "--quick";
  const std::vector<int> sizes = quick ? std::vector<int>{11, 21} : std::vector<int>{21, 41, 61, 81};
  std::printf("fastnorm %d.%d.%d: full NORM against Hertz theory (steel on steel, E = 210 GPa, nu = 0.3)\n",
              FASTNORM_VERSION_MAJOR, FASTNORM_VERSION_MINOR, FASTNORM_VERSION_PATCH);
  std::printf("grids cover +-1.25 semi-axes; err = numerical / Hertz - 1\n");
  compare("sphere on plane", 0.3, 0.3, 5e4, sizes);
  compare("ellipsoidal contact", 0.46, 0.3, 1e5, sizes);
  std::printf("\nReduced strip-basis solvers against full NORM (single runs; fastnorm-bench gives medians)\n");
  compare_reduced("sphere on plane", 0.3, 0.3, 5e4, sizes.back());
  compare_reduced("ellipsoidal contact", 0.46, 0.3, 1e5, sizes.back());
  return 0;
}
