// fastnorm-solve: solves a .case file and compares with the result it carries.
//
//   fastnorm-solve CASE [--solver norm] [--control approach|force] [--write-case OUT] [--quiet]
//
// Prints one line `fn=<N> approach=<m> ncontact=<n> iterations=<k> solve_s=<s>`, followed on
// the same line, when the case carries a result, by `ref_fn=<N> rel_fn_diff=<x>
// max_abs_dp_over_pmax=<x> contact_mismatch=<n>`. Exit status: 0 solved, 1 the solver did
// not converge, 2 bad input (the message names the file, line or argument; nothing written).
#include <fastnorm/fastnorm.hpp>

#include <chrono>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <string>

namespace {

const char* const usage =
    "usage: fastnorm-solve CASE [--solver norm] [--control approach|force] [--write-case OUT] [--quiet]\n";

struct Arguments {
  std::string case_path;
  std::string solver = "norm";
  std::string control;  // empty: as the case's control line says
  std::string write_path;
  bool quiet = false;
};

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

Arguments parse(int argc, char** argv) {
  Arguments arguments;
  for (int n = 1; n < argc; ++n) {
    const std::string word = argv[n];
    auto value = [&]() -> std::string {
      if (n + 1 >= argc) throw UsageError("option " + word + " needs a value");
      return argv[++n];
    };
    if (word == "--solver") {
      arguments.solver = value();
    } else if (word == "--control") {
      arguments.control = value();
      if (arguments.control != "approach" && arguments.control != "force") {
        throw UsageError("--control must be 'approach' or 'force', not '" + arguments.control + "'");
      }
    } else if (word == "--write-case") {
      arguments.write_path = value();
    } else if (word == "--quiet") {
      arguments.quiet = true;
    } else if (!word.empty() && word[0] == '-') {
      throw UsageError("unknown option '" + word + "'");
    } else if (arguments.case_path.empty()) {
      arguments.case_path = word;
    } else {
      throw UsageError("more than one CASE given ('" + word + "')");
    }
  }
  if (arguments.case_path.empty()) throw UsageError("no CASE given");
  return arguments;
}

using Solve = std::function<fastnorm::Solution<>(const fastnorm::Case<>&, const Eigen::VectorXd&,
                                                 const fastnorm::Loading<>&)>;

// The solvers by name; later solvers add an entry here.
const std::map<std::string, Solve>& solvers() {
  static const std::map<std::string, Solve> table{
      {"norm", [](const fastnorm::Case<>& problem, const Eigen::VectorXd& h, const fastnorm::Loading<>& loading) {
         return fastnorm::NormSolver<>(problem.grid, problem.material).solve(h, loading);
       }}};
  return table;
}

int run(const Arguments& arguments) {
  const auto solver = solvers().find(arguments.solver);
  if (solver == solvers().end()) {
    std::string known;
    for (const auto& entry : solvers()) known += (known.empty() ? "" : ", ") + entry.first;
    throw UsageError("unknown solver '" + arguments.solver + "' (known: " + known + ")");
  }
  fastnorm::Case<> problem = fastnorm::read_case_file(arguments.case_path);
  if (arguments.control == "approach") {
    problem.loading = fastnorm::Loading<>::approach();  // h as it stands
  } else if (arguments.control == "force" && problem.loading.control != fastnorm::Control::force) {
    throw UsageError("--control force needs a case whose control line gives the force");
  }

  const auto start = std::chrono::steady_clock::now();
  const auto solution = solver->second(problem, problem.undeformed_distance, problem.loading);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (!arguments.quiet) {
    std::cout << "case " << problem.name << ": solver " << arguments.solver << ", "
              << (problem.loading.control == fastnorm::Control::force ? "force" : "approach")
              << " control, status " << fastnorm::to_string(solution.status) << " (" << solution.message << ")\n";
  }
  std::cout.precision(10);
  std::cout << "fn=" << solution.normal_force << " approach=" << solution.approach
            << " ncontact=" << solution.contact_count() << " iterations=" << solution.iterations
            << " solve_s=" << seconds;
  if (problem.result) {
    const auto& reference = *problem.result;
    const double peak = reference.pressure.maxCoeff();
    std::cout << " ref_fn=" << reference.normal_force
              << " rel_fn_diff=" << std::abs(solution.normal_force - reference.normal_force) / reference.normal_force
              << " max_abs_dp_over_pmax="
              << (peak > 0 ? (solution.pressure - reference.pressure).cwiseAbs().maxCoeff() / peak : 0.0)
              << " contact_mismatch=" << (solution.in_contact != (reference.pressure.array() > 0)).count();
  }
  std::cout << '\n';

  if (!arguments.write_path.empty()) {
    fastnorm::CaseResult<> result;
    result.normal_force = solution.normal_force;
    result.approach = solution.approach;
    result.contact_count = solution.contact_count();
    result.iterations = solution.iterations;
    result.solve_seconds = seconds;
    result.pressure = solution.pressure;
    problem.result = result;
    problem.source = "fastnorm-solve --solver " + arguments.solver;
    std::ofstream out(arguments.write_path);
    if (!out) throw UsageError("cannot write '" + arguments.write_path + "'");
    fastnorm::write_case(out, problem);
  }
  return solution.ok() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse(argc, argv));
  } catch (const UsageError& error) {
    std::cerr << "fastnorm-solve: " << error.what() << '\n' << usage;
  } catch (const fastnorm::invalid_argument& error) {
    std::cerr << "fastnorm-solve: " << error.what() << '\n';
  }
  return 2;
}
