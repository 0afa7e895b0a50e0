// fastnorm-bench: times the solvers on Hertz problems; medians of several repeats.
//
//   fastnorm-bench [--sizes 30,45,60] [--repeats 5]
//
// One line per problem: `case=<name> ncontact=<n> norm_s=<median> repeats=<r>`. Later
// solvers add their own `<solver>_s=` fields and ratios to the same line.
#include <fastnorm/fastnorm.hpp>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

template <typename Run>
double median_seconds(int repeats, Run run) {
  std::vector<double> times;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    run();
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(times.begin(), times.end());
  const std::size_t middle = times.size() / 2;
  return times.size() % 2 ? times[middle] : (times[middle - 1] + times[middle]) / 2;
}

std::vector<int> parse_sizes(const std::string& text) {
  std::vector<int> sizes;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) sizes.push_back(std::stoi(item));
  return sizes;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes{30, 45, 60};
  int repeats = 5;
  for (int n = 1; n + 1 < argc; n += 2) {
    const std::string option = argv[n];
    if (option == "--sizes") {
      sizes = parse_sizes(argv[n + 1]);
    } else if (option == "--repeats") {
      repeats = std::max(1, std::stoi(argv[n + 1]));
    } else {
      std::cerr << "usage: fastnorm-bench [--sizes 30,45,60] [--repeats 5]\n";
      return 2;
    }
  }
  // The CONTACT Hertz peer case: sphere R = 0.3 m on a plane, 50 kN, grid over ±1.2 a.
  const fastnorm::Material<> steel(2.1e11, 0.3);
  const double radius = 0.3, force = 5e4;
  const auto hertz = fastnorm::hertz_from_force(radius, radius, steel.combined_modulus(), force);
  std::cout.precision(4);
  for (int size : sizes) {
    const auto grid = fastnorm::hertz_grid(hertz, size);
    const Eigen::VectorXd h = fastnorm::hertz_undeformed_distance(grid, radius, radius);
    const fastnorm::NormSolver<> norm(grid, steel);
    fastnorm::Solution<> solution;
    const double norm_seconds =
        median_seconds(repeats, [&] { solution = norm.solve(h, fastnorm::Loading<>::force(force)); });
    std::cout << "case=hertz_sphere_" << size << "x" << size << " ncontact=" << solution.contact_count()
              << " norm_s=" << norm_seconds << " repeats=" << repeats << std::endl;
  }
  return 0;
}
