// fastnorm-bench: times the solvers side by side, medians of several repeats, one run.
//
//   fastnorm-bench [--repeats 5] [--solvers norm,elliptic,...] [--sizes 30,45,60] [CASE...]
//
// Without CASE: the Hertz sphere of the CONTACT peer cases (R = 0.3 m, 50 kN, grid over
// ±1.2 a) on n × n grids. With CASEs: each case in approach control on its h minus its
// stored approach (docs/validation.md §2), as the accuracy of the reduced solvers is defined.
// One line per problem:
//   case=<name> ncontact=<n> norm_s=<t> <solver>_s=<t> … err_<solver>=<x> … speedup_<solver>=<x> …
// err = |Fn/Fn_norm − 1|; speedup = norm_s / <solver>_s; <solver> is the solver's name with
// ':' and '-' replaced by '_' (polynomial:4 → polynomial_4).
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

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> items;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) items.push_back(item);
  return items;
}

std::string label(std::string name) {
  std::replace(name.begin(), name.end(), ':', '_');
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

struct Problem {
  std::string name;
  fastnorm::Grid<> grid;
  fastnorm::Material<> material;
  Eigen::VectorXd h;
  fastnorm::Loading<> loading;
};

void bench(const Problem& problem, const std::vector<std::string>& solver_names, int repeats) {
  const fastnorm::AnySolver<> norm("norm", problem.grid, problem.material);
  fastnorm::Solution<> reference;
  const double norm_seconds = median_seconds(repeats, [&] { reference = norm.solve(problem.h, problem.loading); });
  std::ostringstream times, errors, speedups;
  times.precision(4);
  errors.precision(3);
  speedups.precision(3);
  for (const auto& name : solver_names) {
    const fastnorm::AnySolver<> solver(name, problem.grid, problem.material);
    fastnorm::Solution<> solution;
    const double seconds = median_seconds(repeats, [&] { solution = solver.solve(problem.h, problem.loading); });
    const std::string key = label(solver.name());
    times << ' ' << key << "_s=" << seconds;
    errors << " err_" << key << '=' << std::abs(solution.normal_force / reference.normal_force - 1);
    if (!solution.ok()) errors << " status_" << key << "=" << label(fastnorm::to_string(solution.status));
    speedups << " speedup_" << key << '=' << norm_seconds / seconds;
  }
  std::cout.precision(4);
  std::cout << "case=" << problem.name << " ncontact=" << reference.contact_count() << " norm_s=" << norm_seconds
            << times.str() << errors.str() << speedups.str() << std::endl;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes{30, 45, 60};
  std::vector<std::string> solvers{"elliptic", "polynomial:4", "elliptic-edge", "polynomial-edge"};
  std::vector<std::string> cases;
  int repeats = 5;
  try {
    for (int n = 1; n < argc; ++n) {
      const std::string word = argv[n];
      const bool has_value = n + 1 < argc;
      if (word == "--sizes" && has_value) {
        sizes.clear();
        for (const auto& item : split(argv[++n])) sizes.push_back(std::stoi(item));
      } else if (word == "--repeats" && has_value) {
        repeats = std::max(1, std::stoi(argv[++n]));
      } else if (word == "--solvers" && has_value) {
        solvers = split(argv[++n]);
      } else if (!word.empty() && word[0] == '-') {
        throw std::invalid_argument("unknown option or missing value: " + word);
      } else {
        cases.push_back(word);
      }
    }
    if (cases.empty()) {
      const fastnorm::Material<> steel(2.1e11, 0.3);
      const auto hertz = fastnorm::hertz_from_force(0.3, 0.3, steel.combined_modulus(), 5e4);
      for (int size : sizes) {
        const auto grid = fastnorm::hertz_grid(hertz, size);
        bench({"hertz_sphere_" + std::to_string(size) + "x" + std::to_string(size), grid, steel,
               fastnorm::hertz_undeformed_distance(grid, 0.3, 0.3), fastnorm::Loading<>::force(5e4)},
              solvers, repeats);
      }
    }
    for (const auto& path : cases) {
      const auto problem = fastnorm::read_case_file(path);
      const double stored_approach = problem.result ? problem.result->approach : 0.0;
      bench({problem.name, problem.grid, problem.material,
             problem.undeformed_distance.array() - stored_approach, fastnorm::Loading<>::approach()},
            solvers, repeats);
    }
  } catch (const std::exception& error) {
    std::cerr << "fastnorm-bench: " << error.what()
              << "\nusage: fastnorm-bench [--repeats 5] [--solvers a,b] [--sizes 30,45,60] [CASE...]\n";
    return 2;
  }
  return 0;
}
