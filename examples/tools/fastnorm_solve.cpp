// fastnorm-solve: solves a .case file and compares with the result it carries.
//
//   fastnorm-solve CASE [--solver NAME] [--control approach|force] [--compare]
//                  [--friction MU [--creepage-x XI] [--creepage-y ETA] [--spin PHI] [--tangential exact|strip|fastsim]]
//                  [--write-case OUT] [--quiet] [--help]
//
// NAME: norm (default) | cg | elliptic | polynomial[:G] | elliptic-edge[:K] | polynomial-edge[:G[:K]].
// Prints one line `fn=<N> approach=<m> ncontact=<n> iterations=<k> solve_s=<s>`, followed on
// the same line, when the case carries a result, by `ref_fn=<N> rel_fn_diff=<x>
// max_abs_dp_over_pmax=<x> contact_mismatch=<n>`, and with --compare by
// `rel_fn_err_vs_norm=<x> contact_mismatch_vs_norm=<n> max_dp_over_pmax_vs_norm=<x>
// speedup_vs_norm=<x>` (full NORM on the same case and control), and with --friction, or a
// case with a tangential line (docs/case-format.md; --friction and the creepage options
// replace it), by the steady-rolling answer on the solution, `fx=<N> fs=<N> mn=<N m> nadh=<n>
// nslip=<n> sweeps=<k> tangential=<status>` (docs/tangential.md: forces on body 1, creepages
// of body 1 against body 2, rolling towards +x unless the case says otherwise, mn about the
// grid's origin). --write-case writes the tangential problem solved with the case. Exit status: 0 solved,
// 1 the solver gave no usable answer, 2 bad input (the message names the file, line or
// argument; nothing written).
#include <fastnorm/fastnorm.hpp>

#include <chrono>
#include <fstream>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "support/arguments.hpp"
#include "support/tangential_arguments.hpp"

namespace {

using fastnorm_example::UsageError;

struct Arguments {
  std::vector<std::string> case_path;  // exactly one
  std::string solver = "norm";
  std::string control;  // empty: as the case's control line says
  std::string write_path;
  bool quiet = false;
  bool compare = false;
  fastnorm_example::TangentialArguments tangential;
  bool tangential_given = false;  // --tangential on the command line
};

fastnorm_example::CommandLine command_line(Arguments& a) {
  fastnorm_example::CommandLine line("fastnorm-solve",
                                   "Solves a .case file (docs/case-format.md) and compares with the result it carries.");
  line.positional("CASE", a.case_path, "the .case file to solve");
  line.option("--solver", a.solver, "NAME", std::string("the solver: ") + fastnorm::SolverSpec<double>::grammar);
  line.choice("--control", a.control, {"approach", "force"},
              "approach: solve on h as it stands; force: the force of the case's control line (default: as the case says)");
  line.flag("--compare", a.compare, "also solve with full NORM and print the differences and the speed-up");
  line.option("--write-case", a.write_path, "FILE", "write the case with this solution to FILE");
  line.flag("--quiet", a.quiet, "print the result line only");
  a.tangential.add_to(line, "y");
  return line;
}

// Solves and times one run.
std::pair<fastnorm::Solution<>, double> timed_solve(const fastnorm::AnySolver<>& solver, const fastnorm::Case<>& problem) {
  const auto start = std::chrono::steady_clock::now();
  auto solution = solver.solve(problem.undeformed_distance, problem.loading);
  return {std::move(solution), std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

// Largest |p − p_ref| over the peak of p_ref.
double max_difference_over_peak(const Eigen::VectorXd& pressure, const Eigen::VectorXd& reference) {
  const double peak = reference.maxCoeff();
  return peak > 0 ? (pressure - reference).cwiseAbs().maxCoeff() / peak : 0.0;
}


int run(Arguments arguments) {
  fastnorm::Case<> problem = fastnorm::read_case_file(arguments.case_path.front());
  arguments.tangential.adopt(problem.rolling);
  if (arguments.tangential_given && !arguments.tangential.wanted()) {
    throw UsageError("--tangential needs --friction MU or a case with a tangential line");
  }
  const fastnorm::AnySolver<> solver(arguments.solver, problem.grid, problem.material);
  if (arguments.control == "approach") {
    problem.loading = fastnorm::Loading<>::approach();  // h as it stands
  } else if (arguments.control == "force" && problem.loading.control != fastnorm::Control::force) {
    throw UsageError("--control force needs a case whose control line gives the force");
  }

  const auto [solution, seconds] = timed_solve(solver, problem);

  if (!arguments.quiet) {
    std::cout << "case " << problem.name << ": solver " << solver.name() << ", "
              << (problem.loading.control == fastnorm::Control::force ? "force" : "approach")
              << " control, status " << fastnorm::to_string(solution.status) << " (" << solution.message << ")\n";
    if (solution.at_edge) {
      std::cout << "warning: the contact reaches the edge of the grid; the answer is that of a body cut off "
                   "there (enlarge the grid)\n";
    }
  }
  std::cout.precision(10);
  std::cout << "fn=" << solution.normal_force << " approach=" << solution.approach
            << " ncontact=" << solution.contact_count() << " iterations=" << solution.iterations
            << " at_edge=" << solution.at_edge << " solve_s=" << seconds;
  if (problem.result) {
    const auto& reference = *problem.result;
    std::cout << " ref_fn=" << reference.normal_force
              << " rel_fn_diff=" << std::abs(solution.normal_force - reference.normal_force) / reference.normal_force
              << " max_abs_dp_over_pmax=" << max_difference_over_peak(solution.pressure, reference.pressure)
              << " contact_mismatch=" << (solution.in_contact != (reference.pressure.array() > 0)).count();
  }
  if (arguments.compare) {
    const auto [norm, norm_seconds] = timed_solve(fastnorm::AnySolver<>("norm", problem.grid, problem.material), problem);
    std::cout << " rel_fn_err_vs_norm="
              << (norm.normal_force > 0 ? std::abs(solution.normal_force / norm.normal_force - 1) : 0.0)
              << " contact_mismatch_vs_norm=" << (solution.in_contact != norm.in_contact).count()
              << " max_dp_over_pmax_vs_norm=" << max_difference_over_peak(solution.pressure, norm.pressure)
              << " speedup_vs_norm=" << norm_seconds / seconds;
  }
  if (arguments.tangential.wanted() && solution.ok()) {
    std::cout << arguments.tangential.solve_fields(problem.grid, problem.material, solution);
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
    if (arguments.tangential.wanted()) problem.rolling = arguments.tangential.as_case();
    problem.source = "fastnorm-solve --solver " + solver.name();
    std::ofstream out(arguments.write_path);
    if (!out) throw UsageError("cannot write '" + arguments.write_path + "'");
    fastnorm::write_case(out, problem);
  }
  return solution.ok() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  Arguments arguments;
  auto line = command_line(arguments);
  return fastnorm_example::run_tool(line, argc, argv, [&] {
    arguments.tangential.check(line, true);
    arguments.tangential_given = line.given("--tangential");
    return run(arguments);
  });
}
