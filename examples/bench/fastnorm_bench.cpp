// fastnorm-bench: times the solvers side by side, medians of several repeats, one run.
//
//   fastnorm-bench [--repeats 5] [--solvers norm,elliptic,...] [--sizes 30,45,60] [CASE...]
//
// Without CASE: the Hertz sphere of the CONTACT peer cases (R = 0.3 m, 50 kN, grid over
// ±1.2 a) on n × n grids. With CASEs: each case in approach control on its h minus its
// stored approach (docs/validation.md §2), as the accuracy of the reduced solvers is defined.
// One line per problem:
//   case=<name> ncontact=<n> norm_s=<t> <solver>_s=<t> … err_<solver>=<x> … speedup_<solver>=<x> …
// Times are medians over the repeats; err = |Fn/Fn_norm − 1|; speedup = median over the repeats
// of NORM's time / the solver's time, both measured in the same repeat; <solver> is the
// solver's name with ':' and '-' replaced by '_' (polynomial:4 → polynomial_4). A solve that
// did not converge adds status_<solver>=<status>.
#include <fastnorm/fastnorm.hpp>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t middle = values.size() / 2;
  return values.size() % 2 ? values[middle] : (values[middle - 1] + values[middle]) / 2;
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
  std::replace(name.begin(), name.end(), ' ', '_');
  return name;
}

struct Problem {
  std::string name;
  fastnorm::Grid<> grid;
  fastnorm::Material<> material;
  Eigen::VectorXd h;
  fastnorm::Loading<> loading;
};

// Each repeat runs every solver once, NORM first, so that a slow spell of the machine
// touches all of them alike; speed-ups are medians of the per-repeat ratios.
void bench(const Problem& problem, const std::vector<std::string>& solver_names, int repeats) {
  std::vector<fastnorm::AnySolver<>> solvers{fastnorm::AnySolver<>("norm", problem.grid, problem.material)};
  for (const auto& name : solver_names) solvers.emplace_back(name, problem.grid, problem.material);
  std::vector<fastnorm::Solution<>> solutions(solvers.size());
  std::vector<std::vector<double>> seconds(solvers.size());
  for (int r = 0; r < repeats; ++r) {
    for (std::size_t s = 0; s < solvers.size(); ++s) {
      const auto start = std::chrono::steady_clock::now();
      solutions[s] = solvers[s].solve(problem.h, problem.loading);
      seconds[s].push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
  }
  const fastnorm::Solution<>& reference = solutions.front();
  std::ostringstream times, errors, speedups;
  times.precision(4);
  errors.precision(3);
  speedups.precision(3);
  for (std::size_t s = 1; s < solvers.size(); ++s) {
    const std::string key = label(solvers[s].name());
    std::vector<double> ratios;
    for (int r = 0; r < repeats; ++r) ratios.push_back(seconds[0][static_cast<std::size_t>(r)] / seconds[s][static_cast<std::size_t>(r)]);
    times << ' ' << key << "_s=" << median(seconds[s]);
    errors << " err_" << key << '=' << std::abs(solutions[s].normal_force / reference.normal_force - 1);
    if (solutions[s].status != fastnorm::Status::converged) {
      errors << " status_" << key << "=" << label(fastnorm::to_string(solutions[s].status));
    }
    speedups << " speedup_" << key << '=' << median(ratios);
  }
  std::cout.precision(4);
  std::cout << "case=" << problem.name << " ncontact=" << reference.contact_count() << " norm_s=" << median(seconds[0])
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
