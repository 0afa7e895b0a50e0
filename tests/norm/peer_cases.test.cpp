// The full solvers, NORM and CG, against CONTACT's own solutions of ../shared/peer-cases
// (docs/validation.md §2). CONTACT discretises exactly as fastnorm does and solved to 1e-9,
// so an exact solve must agree to: force 1e-7 relative, every pressure 1e-6 of the peak, and
// the identical contact set. CG runs at its default tolerance, 1e-9.
#include <catch2/catch.hpp>
#include <type_traits>
#include <fastnorm/case_file.hpp>
#include <fastnorm/cg_solver.hpp>
#include <fastnorm/norm_solver.hpp>

#include "support/complementarity.hpp"
#include "support/peer_cases.hpp"

namespace {

template <typename Solver>
void check_against_contact(const std::string& path) {
  const auto problem = fastnorm::read_case_file(path);
  REQUIRE(problem.result.has_value());
  const auto& reference = *problem.result;
  const Solver solver(problem.grid, problem.material);

  // Force control as the case says; approach control on h minus CONTACT's approach.
  // The wr_* cases store h with the approach already in it (their stored approach is 0);
  // the hertz_* cases store the unloaded gap and CONTACT's approach (docs/validation.md §2).
  const Eigen::VectorXd loaded_h = problem.undeformed_distance.array() - reference.approach;
  struct Run {
    const char* control;
    Eigen::VectorXd h;
    fastnorm::Loading<> loading;
  };
  for (const Run& run : {Run{"force", problem.undeformed_distance, problem.loading},
                         Run{"approach", loaded_h, fastnorm::Loading<>::approach()}}) {
    const auto solution = solver.solve(run.h, run.loading);
    const double peak = reference.pressure.maxCoeff();
    const double force_difference = std::abs(solution.normal_force / reference.normal_force - 1);
    const double pressure_difference = (solution.pressure - reference.pressure).cwiseAbs().maxCoeff() / peak;
    const auto mismatch = (solution.in_contact != (reference.pressure.array() > 0)).count();
    INFO(problem.name << " (" << run.control << " control): rel_fn_diff " << force_difference
                      << ", max_abs_dp_over_pmax " << pressure_difference << ", contact_mismatch " << mismatch
                      << ", iterations " << solution.iterations);
    REQUIRE(solution.status == fastnorm::Status::converged);
    CHECK(force_difference < 1e-7);
    CHECK(pressure_difference < 1e-6);
    CHECK(mismatch == 0);
    CHECK(solution.contact_count() == reference.contact_count);
    fastnorm::test::require_complementarity(solver.influence(), run.h, solution);
    // The case stores CONTACT's iterations for its own control (force): BCCG's count with
    // its FFT preconditioner. CG must need no more (docs/performance.md §9).
    if (std::is_same_v<Solver, fastnorm::CgSolver<>> && run.loading.control == problem.loading.control) {
      CHECK(solution.iterations <= reference.iterations);
    }
  }
}

template <typename Solver>
void check_files(const std::vector<std::string>& files) {
  if (files.empty()) {
    fastnorm::test::reference_data_missing("peer cases not found in " + fastnorm::test::peer_cases_dir());
    return;
  }
  for (const auto& path : files) {
    DYNAMIC_SECTION(path) { check_against_contact<Solver>(path); }
  }
}

}  // namespace

TEST_CASE("NORM reproduces CONTACT on the wheel-rail peer cases", "[norm][peer]") {
  check_files<fastnorm::NormSolver<>>(fastnorm::test::peer_case_files("wr_"));
}

TEST_CASE("CG reproduces CONTACT on every peer case", "[norm][cg][peer]") {
  check_files<fastnorm::CgSolver<>>(fastnorm::test::peer_case_files());
}

TEST_CASE("NORM reproduces CONTACT on the Hertz peer cases up to 60x60", "[norm][peer]") {
  auto files = fastnorm::test::peer_case_files("hertz_sphere_");
  files.erase(std::remove_if(files.begin(), files.end(),
                             [](const std::string& f) { return f.find("120x120") != std::string::npos; }),
              files.end());
  check_files<fastnorm::NormSolver<>>(files);
}

TEST_CASE("NORM reproduces CONTACT on the 120x120 Hertz peer case", "[norm][peer][large]") {
  check_files<fastnorm::NormSolver<>>(fastnorm::test::peer_case_files("hertz_sphere_120x120"));
}
