// fastnorm-solve as a user runs it: output line, --write-case, exit statuses, messages.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <fastnorm/fastnorm.hpp>
#include <string>

#include "support/peer_cases.hpp"
#include "support/run_command.hpp"
#include "support/scratch_directory.hpp"
#include "support/surfaces.hpp"

using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

using fastnorm::test::field;
using fastnorm::test::Outcome;

Outcome run_solver(const std::string& arguments) { return fastnorm::test::run_command(FASTNORM_SOLVE_EXE, arguments); }

// A small sphere problem in force control, written as a case without a result.
fs::path write_sphere_case(const fs::path& dir) {
  using fastnorm::test::steel;
  const auto hertz = fastnorm::hertz_from_force(0.3, 0.3, steel.combined_modulus(), 5e4);
  const auto grid = fastnorm::hertz_grid(hertz, 15);
  fastnorm::Case<> problem{"sphere 15x15", "cli test", grid, steel, fastnorm::Loading<>::force(5e4), 0.0,
                           fastnorm::hertz_undeformed_distance(grid, 0.3, 0.3), std::nullopt, std::nullopt};
  const fs::path path = dir / "sphere.case";
  std::ofstream out(path);
  fastnorm::write_case(out, problem);
  return path;
}

}  // namespace

TEST_CASE("fastnorm-solve solves a case, writes it back and compares with its result", "[cli]") {
  const fastnorm::test::ScratchDirectory scratch_dir("fastnorm_cli_");
  const fs::path& dir = scratch_dir.path();
  const fs::path input = write_sphere_case(dir), output = dir / "solved.case";

  const auto first = run_solver(input.string() + " --write-case " + output.string());
  INFO(first.output);
  REQUIRE(first.status == 0);
  CHECK_THAT(first.output, Contains("status converged"));
  CHECK(field(first.output, "fn") == Approx(5e4).epsilon(1e-9));
  CHECK(field(first.output, "approach") > 0);
  CHECK(field(first.output, "ncontact") > 0);
  CHECK(field(first.output, "iterations") >= 1);
  CHECK(field(first.output, "solve_s") >= 0);
  CHECK_THAT(first.output, !Contains("ref_fn="));

  const auto written = fastnorm::read_case_file(output.string());
  REQUIRE(written.result.has_value());
  CHECK(written.result->pressure.sum() * written.grid.element_area() == Approx(5e4).epsilon(1e-9));
  CHECK(written.result->contact_count == static_cast<Eigen::Index>(field(first.output, "ncontact")));

  const auto again = run_solver(output.string() + " --quiet");
  INFO(again.output);
  REQUIRE(again.status == 0);
  CHECK_THAT(again.output, !Contains("status"));
  CHECK(field(again.output, "ref_fn") == Approx(5e4).epsilon(1e-9));
  CHECK(field(again.output, "rel_fn_diff") < 1e-12);
  CHECK(field(again.output, "max_abs_dp_over_pmax") < 1e-12);
  CHECK(field(again.output, "contact_mismatch") == 0);

  // Approach control takes h as it stands: this h is the unloaded gap, so no contact.
  const auto approach = run_solver(input.string() + " --control approach --quiet");
  CHECK(approach.status == 0);
  CHECK(field(approach.output, "fn") == 0);
  CHECK(field(approach.output, "ncontact") == 0);
}

TEST_CASE("fastnorm-solve runs a reduced solver and compares it with full NORM", "[cli]") {
  const fastnorm::test::ScratchDirectory scratch_dir("fastnorm_cli_");
  const fs::path& dir = scratch_dir.path();
  const fs::path input = write_sphere_case(dir);
  const auto outcome = run_solver(input.string() + " --solver polynomial-edge:4:2 --compare");
  INFO(outcome.output);
  REQUIRE(outcome.status == 0);
  CHECK_THAT(outcome.output, Contains("solver polynomial-edge:4:2"));
  CHECK(field(outcome.output, "fn") == Approx(5e4).epsilon(1e-9));  // force control holds Fn exactly
  CHECK(field(outcome.output, "rel_fn_err_vs_norm") < 1e-9);
  CHECK(field(outcome.output, "contact_mismatch_vs_norm") >= 0);
  CHECK(field(outcome.output, "max_dp_over_pmax_vs_norm") < 0.1);
  CHECK(field(outcome.output, "speedup_vs_norm") > 0);
}

TEST_CASE("fastnorm-solve runs the CG solver with the contact set and force of NORM", "[cli][cg]") {
  const fastnorm::test::ScratchDirectory scratch_dir("fastnorm_cli_");
  const fs::path& dir = scratch_dir.path();
  const fs::path input = write_sphere_case(dir);
  const auto outcome = run_solver(input.string() + " --solver cg --compare");
  INFO(outcome.output);
  REQUIRE(outcome.status == 0);
  CHECK_THAT(outcome.output, Contains("solver cg"));
  CHECK(field(outcome.output, "approach") > 0);
  CHECK(field(outcome.output, "contact_mismatch_vs_norm") == 0);
  CHECK(field(outcome.output, "max_dp_over_pmax_vs_norm") < 1e-6);
}

TEST_CASE("fastnorm-solve rejects bad input with status 2 and writes nothing", "[cli]") {
  const fastnorm::test::ScratchDirectory scratch_dir("fastnorm_cli_");
  const fs::path& dir = scratch_dir.path();
  const fs::path good = write_sphere_case(dir), bad = dir / "bad.case", out = dir / "out.case";
  std::ofstream(bad) << "fastnorm-case 1\nname bad\nsource test\ngrid mx 2 my 2 dx 1e-4 dy -1e-4 x0 0 y0 0\n";

  struct Bad {
    std::string arguments, message;
  };
  for (const Bad& c : {Bad{bad.string(), "bad.case:4"}, Bad{(dir / "missing.case").string(), "missing.case"},
                       Bad{good.string() + " --solver multigrid", "unknown solver 'multigrid'"},
                       Bad{good.string() + " --solver polynomial:99", "grade"},
                       Bad{good.string() + " --control sideways", "--control"},
                       Bad{good.string() + " --bogus", "unknown option '--bogus'"},
                       Bad{good.string() + " --solver", "needs a value"}, Bad{"", "no CASE"}}) {
    const auto outcome = run_solver("--write-case " + out.string() + " " + c.arguments);
    INFO(c.arguments << "\n" << outcome.output);
    CHECK(outcome.status == 2);
    CHECK_THAT(outcome.output, Contains(c.message));
    CHECK_FALSE(fs::exists(out));
  }
}

TEST_CASE("fastnorm-solve fails clearly on the issue-15 inputs", "[cli]") {
  // Each was a crash (std::bad_alloc, exit 134) or a wrong answer with a clean status (the
  // final check of an answer, E = 1e30, is tested in tests/norm/norm_solver.test.cpp).
  const fastnorm::test::ScratchDirectory scratch_dir("fastnorm_cli_");
  const fs::path& dir = scratch_dir.path();
  const fs::path good = write_sphere_case(dir);
  std::ifstream in(good);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto variant = [&](const std::string& from, const std::string& to, const std::string& name) {
    std::string edited = text;
    const auto at = edited.find(from);
    REQUIRE(at != std::string::npos);
    const fs::path path = dir / name;
    std::ofstream(path) << edited.replace(at, from.size(), to);
    return path.string();
  };
  const auto huge = run_solver(variant("grid mx 15 my 15", "grid mx 3000000000 my 3000000000", "huge.case"));
  CHECK(huge.status == 2);
  CHECK_THAT(huge.output, Contains("huge.case:4: grid mx x my") && Contains("memory"));
  const auto hexadecimal = run_solver(variant("control force 50000", "control force 0x10", "hex.case"));
  CHECK(hexadecimal.status == 2);
  CHECK_THAT(hexadecimal.output, Contains("hex.case:6") && Contains("decimal numbers only"));
  const auto edge = run_solver(variant("control force 50000", "control force 1e300", "edge.case"));
  CHECK_THAT(edge.output, Contains("warning: the contact reaches the edge of the grid"));
  CHECK(field(edge.output, "at_edge") == 1);
  CHECK(field(run_solver(good.string()).output, "at_edge") == 0);
}

TEST_CASE("fastnorm-solve reproduces a CONTACT peer case", "[cli][peer]") {
  const auto files = fastnorm::test::peer_case_files("hertz_sphere_30x30");
  if (files.empty()) {
    fastnorm::test::reference_data_missing("peer cases not found in " + fastnorm::test::peer_cases_dir());
    return;
  }
  const auto outcome = run_solver(files.front() + " --quiet");
  INFO(outcome.output);
  REQUIRE(outcome.status == 0);
  CHECK(field(outcome.output, "rel_fn_diff") < 1e-7);
  CHECK(field(outcome.output, "max_abs_dp_over_pmax") < 1e-6);
  CHECK(field(outcome.output, "contact_mismatch") == 0);
}

TEST_CASE("fastnorm-solve --friction adds the steady-rolling creep forces", "[cli][tangential]") {
  // A sphere rolling towards +x: at ξ = 0.1 every element slides and Fx = −μ Fn; Coulomb's
  // law is odd, so −ξ gives the opposite forces and the same areas.
  const fastnorm::test::ScratchDirectory scratch_dir("fastnorm_cli_");
  const fs::path input = write_sphere_case(scratch_dir.path());
  const auto sliding = run_solver(input.string() + " --quiet --friction 0.3 --creepage-x 0.1");
  REQUIRE(sliding.status == 0);
  INFO(sliding.output);
  CHECK_THAT(sliding.output, Contains("tangential=converged"));
  CHECK(field(sliding.output, "nadh") == 0);
  CHECK(field(sliding.output, "fx") == Approx(-0.3 * field(sliding.output, "fn")).epsilon(1e-5));
  const auto forward = run_solver(input.string() + " --quiet --friction 0.3 --creepage-x 1e-3 --creepage-y 4e-4");
  const auto backward = run_solver(input.string() + " --quiet --friction 0.3 --creepage-x -1e-3 --creepage-y -4e-4");
  REQUIRE(forward.status == 0);
  REQUIRE(backward.status == 0);
  INFO(forward.output << backward.output);
  CHECK(field(forward.output, "nadh") > 0);
  CHECK(field(forward.output, "nslip") > 0);
  CHECK(field(forward.output, "fx") < 0);
  CHECK(field(backward.output, "fx") == Approx(-field(forward.output, "fx")).epsilon(1e-5));
  CHECK(field(backward.output, "fs") == Approx(-field(forward.output, "fs")).epsilon(1e-5));
  CHECK(field(backward.output, "nadh") == field(forward.output, "nadh"));
  const auto without_friction = run_solver(input.string() + " --spin 0.5");
  CHECK(without_friction.status == 2);
  CHECK_THAT(without_friction.output, Contains("--spin needs --friction"));
  // CONTACT's stopping rule (docs/tangential.md §7): fewer sweeps, the same areas, the forces
  // within 1e-6 μFn of the default rule's.
  const auto contact_rule =
      run_solver(input.string() + " --quiet --friction 0.3 --creepage-x 1e-3 --creepage-y 4e-4 --contact-eps 1e-5");
  REQUIRE(contact_rule.status == 0);
  INFO(contact_rule.output);
  CHECK(field(contact_rule.output, "sweeps") < field(forward.output, "sweeps"));
  CHECK(field(contact_rule.output, "nadh") == field(forward.output, "nadh"));
  CHECK(field(contact_rule.output, "nslip") == field(forward.output, "nslip"));
  // (plus the two printed values' rounding to 6 digits, each within 5e-7 of |fx|)
  const double mu_fn = 0.3 * field(forward.output, "fn"), printed = std::abs(field(forward.output, "fx"));
  CHECK(std::abs(field(contact_rule.output, "fx") - field(forward.output, "fx")) <= 1e-6 * mu_fn + 1e-6 * printed);
  const auto strip_with_eps = run_solver(input.string() + " --friction 0.3 --tangential strip --contact-eps 1e-5");
  CHECK(strip_with_eps.status == 2);
  CHECK_THAT(strip_with_eps.output, Contains("--contact-eps needs --tangential exact"));
}

TEST_CASE("fastnorm-solve rolls a case's tangential line, and --write-case keeps it", "[cli][tangential]") {
  // The options on the plain case and the case's own line give the same answer; the options
  // replace the line; a case written after a solve with --friction holds the line.
  const fastnorm::test::ScratchDirectory scratch_dir("fastnorm_cli_");
  const fs::path& dir = scratch_dir.path();
  const fs::path input = write_sphere_case(dir);
  auto problem = fastnorm::read_case_file(input.string());
  problem.rolling = fastnorm::CaseRolling<>{0.3, {}, fastnorm::RollingDirection::negative_x};
  problem.rolling->creepage.longitudinal = -1e-3;
  problem.rolling->creepage.lateral = 4e-4;
  const fs::path rolling = dir / "rolling.case";
  fastnorm::write_case_file(rolling.string(), problem);
  const auto from_case = run_solver(rolling.string() + " --quiet");
  REQUIRE(from_case.status == 0);
  INFO(from_case.output);
  CHECK_THAT(from_case.output, Contains("tangential=converged"));
  // Towards −x, (−ξ, η) is the mirror in x of (ξ, η) towards +x: the same areas, −fx, fs.
  const auto by_options = run_solver(input.string() + " --quiet --friction 0.3 --creepage-x 1e-3 --creepage-y 4e-4");
  REQUIRE(by_options.status == 0);
  INFO(by_options.output);
  CHECK(field(from_case.output, "fx") == Approx(-field(by_options.output, "fx")).epsilon(1e-5));
  CHECK(field(from_case.output, "fs") == Approx(field(by_options.output, "fs")).epsilon(1e-5));
  CHECK(field(from_case.output, "nadh") == field(by_options.output, "nadh"));
  const auto replaced = run_solver(rolling.string() + " --quiet --friction 0.3 --creepage-x 0.1");
  CHECK(field(replaced.output, "nadh") == 0);
  const auto strip = run_solver(rolling.string() + " --quiet --tangential strip");
  CHECK(strip.status == 0);
  CHECK(field(strip.output, "sweeps") == 1);

  const fs::path out = dir / "written.case";
  REQUIRE(run_solver(input.string() + " --quiet --friction 0.25 --spin 0.5 --write-case " + out.string()).status == 0);
  const auto written = fastnorm::read_case_file(out.string());
  REQUIRE(written.rolling.has_value());
  CHECK(written.rolling->friction == 0.25);
  CHECK(written.rolling->creepage.spin == 0.5);
  CHECK(written.rolling->direction == fastnorm::RollingDirection::positive_x);
  REQUIRE(run_solver(input.string() + " --quiet --write-case " + out.string()).status == 0);
  CHECK_FALSE(fastnorm::read_case_file(out.string()).rolling.has_value());
}

TEST_CASE("fastnorm-solve --tangential strip and fastsim give the fast paths' creep forces", "[cli][tangential]") {
  // Full sliding is the fast paths' as the exact path's, Fx = −μ Fn; in partial slip they
  // differ from it by a few percent of μFn on this sphere (docs/validation.md §7).
  const fastnorm::test::ScratchDirectory scratch_dir("fastnorm_cli_");
  const fs::path input = write_sphere_case(scratch_dir.path());
  const auto exact = run_solver(input.string() + " --quiet --friction 0.3 --creepage-x 1e-3 --creepage-y 4e-4");
  for (const std::string method : {"strip", "fastsim"}) {
    const auto sliding =
        run_solver(input.string() + " --quiet --friction 0.3 --creepage-x 0.1 --tangential " + method);
    REQUIRE(sliding.status == 0);
    INFO(sliding.output);
    CHECK(field(sliding.output, "sweeps") == 1);
    CHECK(field(sliding.output, "nadh") == 0);
    CHECK(field(sliding.output, "fx") == Approx(-0.3 * field(sliding.output, "fn")).epsilon(1e-9));
    const auto fast = run_solver(input.string() + " --quiet --friction 0.3 --creepage-x 1e-3 --creepage-y 4e-4 --tangential " +
                                 method);
    REQUIRE(fast.status == 0);
    INFO(exact.output << fast.output);
    CHECK(field(fast.output, "nadh") > 0);
    CHECK(field(fast.output, "nslip") > 0);
    const double scale = 0.3 * field(fast.output, "fn");
    CHECK(std::abs(field(fast.output, "fx") - field(exact.output, "fx")) <= 0.1 * scale);
    CHECK(field(fast.output, "fx") != field(exact.output, "fx"));
  }
  const auto unknown = run_solver(input.string() + " --friction 0.3 --tangential fast");
  CHECK(unknown.status == 2);
  CHECK_THAT(unknown.output, Contains("--tangential must be exact, strip or fastsim"));
  const auto alone = run_solver(input.string() + " --tangential strip");
  CHECK(alone.status == 2);
  CHECK_THAT(alone.output, Contains("--tangential needs --friction"));
}
