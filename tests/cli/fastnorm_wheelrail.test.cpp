// fastnorm-wheelrail as a user runs it: one line per patch with the specified fields,
// the single-wheel mode against CONTACT, --compare, --write-case, --svg, exit statuses.

#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <fastnorm/fastnorm.hpp>
#include <sstream>
#include <string>
#include <utility>

#include "support/peer_cases.hpp"
#include "support/run_command.hpp"
#include "support/scratch_directory.hpp"

using Catch::Matchers::Contains;
namespace fs = std::filesystem;
using fastnorm::test::field;

namespace {

fastnorm::test::Outcome run_wheelrail(const std::string& arguments) {
  return fastnorm::test::run_command(FASTNORM_WHEELRAIL_EXE, arguments);
}

/// The line of the first patch of `wheel` (left, right) in a run's output.
std::string patch_line(const std::string& output, const std::string& wheel) {
  const auto at = output.find("wheel=" + wheel + " patch=1 ");
  REQUIRE(at != std::string::npos);
  return output.substr(at, output.find('\n', at) - at);
}

}  // namespace

TEST_CASE("fastnorm-wheelrail prints one line per patch", "[cli][wheelrail]") {
  const auto run = run_wheelrail("--y 3 --elements 30 --solver elliptic --compare");
  REQUIRE(run.status == 0);
  std::istringstream lines(run.output);
  std::string line;
  std::getline(lines, line);
  CHECK_THAT(line, Contains("# status=converged"));
  int patches = 0;
  double vertical = 0;
  while (std::getline(lines, line)) {
    ++patches;
    CHECK((line.rfind("wheel=left patch=1 ", 0) == 0 || line.rfind("wheel=right patch=1 ", 0) == 0));
    for (const char* name : {"ncontact", "pmax", "x_track", "y_track"}) CHECK(std::isfinite(field(line, name)));
    const double fn = field(line, "fn"), angle = field(line, "contact_angle");
    CHECK(field(line, "approach") > 0);
    CHECK(std::abs(field(line, "rel_fn_err_vs_norm")) < 1e-3);
    // Both contact angles lean to the track centre at y = 3 mm.
    CHECK(angle > 0);
    vertical += fn * std::cos(angle);
  }
  CHECK(patches == 2);
  CHECK(vertical == Approx(2e5).epsilon(1e-5));  // printed to 6 digits
}

TEST_CASE("fastnorm-wheelrail single-wheel mode writes cases and drawings", "[cli][wheelrail]") {
  const fastnorm::test::ScratchDirectory scratch_dir("fastnorm_wheelrail_");
  const fs::path& dir = scratch_dir.path();
  const auto run = run_wheelrail("--fz 1e5 --wheel right --y 0 --elements 30 --write-case " + (dir / "p").string() +
                                 " --svg " + (dir / "p").string());
  REQUIRE(run.status == 0);
  // CONTACT, wr_y0.0_psi0.0_right: Fn = 100061.7 N, YCP = 750.3853 mm, DELTCP = −0.0351.
  CHECK(field(run.output, "fn") == Approx(100061.7).epsilon(5e-5));
  CHECK(field(run.output, "y_track") == Approx(750.3853).margin(0.01));
  CHECK(field(run.output, "contact_angle") == Approx(0.0351).margin(2e-4));
  const auto problem = fastnorm::read_case_file<double>((dir / "p_right_1.case").string());
  REQUIRE(problem.result);
  CHECK(problem.result->normal_force == Approx(field(run.output, "fn")).epsilon(1e-5));
  // The written case solves to the printed force.
  const auto again = fastnorm::NormSolver<double>(problem.grid, problem.material)
                         .solve(problem.undeformed_distance, fastnorm::Loading<double>::approach());
  CHECK(again.normal_force == Approx(problem.result->normal_force).epsilon(1e-9));
  std::ifstream svg(dir / "p_right_1.svg");
  std::string first;
  std::getline(svg, first);
  CHECK_THAT(first, Contains("<svg"));
}

TEST_CASE("fastnorm-wheelrail refuses bad input with status 2", "[cli][wheelrail]") {
  const std::pair<const char*, const char*> cases[] = {{"--load 2e5 --fz 1e5 --wheel left", "exclude"},
                                                       {"--fz 1e5", "--wheel"},
                                                       {"--y three", "--y needs a number"},
                                                       {"--solver magic", "unknown solver"},
                                                       {"--load -5", "load"},
                                                       {"--radius 50", "--radius"},
                                                       {"--gauge 3000", "--gauge"},
                                                       {"--poisson 0.7", "--poisson"},
                                                       {"--young 210 --shear 82", "exclude"},
                                                       {"--rail-young 0", "--rail-young"},
                                                       // issue #15: std::bad_alloc, and an internal message
                                                       {"--elements 1e12", "--elements must be in [4, 2000]"},
                                                       {"--load 1e300", "--load must be in (0, 1e+07]"}};
  for (const auto& [arguments, message] : cases) {
    INFO(arguments);
    const auto run = run_wheelrail(arguments);
    CHECK(run.status == 2);
    CHECK_THAT(run.output, Contains(message));
  }
}

TEST_CASE("fastnorm-wheelrail takes measured profile files", "[cli][wheelrail][peer]") {
  const std::string wheel = fastnorm::test::shared_profile("MBench_S1002_v3.prw");
  const std::string rail = fastnorm::test::shared_profile("MBench_UIC60_v3.prr");
  if (wheel.empty() || rail.empty()) {
    fastnorm::test::reference_data_missing("the MBench profiles are not in ../shared/profiles");
    return;
  }
  // The Manchester benchmark's files are the closed-form S1002 and MB UIC60 sampled (the
  // rail already canted 1:40): the same equilibrium, up to the splines through the points.
  const auto closed_form = run_wheelrail("--y 3 --elements 30");
  const auto measured =
      run_wheelrail("--y 3 --elements 30 --wheel-profile " + wheel + " --rail-profile " + rail + " --cant 0");
  REQUIRE(closed_form.status == 0);
  REQUIRE(measured.status == 0);
  std::istringstream expected(closed_form.output), got(measured.output);
  std::string expected_line, got_line;
  std::getline(expected, expected_line);
  std::getline(got, got_line);
  CHECK(field(got_line, "z") == Approx(field(expected_line, "z")).margin(1e-5));  // mm; measured 3e-6
  int patches = 0;
  while (std::getline(expected, expected_line) && std::getline(got, got_line)) {
    ++patches;
    INFO(expected_line << "\n" << got_line);
    CHECK(field(got_line, "fn") == Approx(field(expected_line, "fn")).epsilon(1e-5));  // measured: 6 digits equal
    CHECK(field(got_line, "pmax") == Approx(field(expected_line, "pmax")).epsilon(5e-4));  // measured 8e-5
    CHECK(field(got_line, "y_track") == Approx(field(expected_line, "y_track")).margin(1e-3));  // mm
    CHECK(field(got_line, "contact_angle") == Approx(field(expected_line, "contact_angle")).margin(1e-5));
  }
  CHECK(patches == 2);

  const auto missing = run_wheelrail("--wheel-profile /nonexistent/wheel.prw");
  CHECK(missing.status == 2);
  CHECK_THAT(missing.output, Contains("/nonexistent/wheel.prw"));
}

TEST_CASE("fastnorm-wheelrail --z gives the contact at a fixed pose", "[cli][wheelrail]") {
  // At the equilibrium's own pose the fixed-pose mode finds the equilibrium's patches.
  const auto equilibrium = run_wheelrail("--y 3 --elements 30");
  REQUIRE(equilibrium.status == 0);
  std::istringstream lines(equilibrium.output);
  std::string pose_line;
  std::getline(lines, pose_line);
  char arguments[256];
  std::snprintf(arguments, sizeof arguments, "--y 3 --elements 30 --z %.6f --roll %.6e", field(pose_line, "z"),
                field(pose_line, "roll"));
  const auto fixed = run_wheelrail(arguments);
  INFO(arguments << "\n" << fixed.output);
  REQUIRE(fixed.status == 0);
  std::istringstream fixed_lines(fixed.output);
  std::string fixed_line, line;
  std::getline(fixed_lines, fixed_line);
  CHECK_THAT(fixed_line, Contains("mode=fixed-pose"));
  // z printed to 1e-6 mm and roll to 7 digits: Fn moves by at most stiffness·1e-9 m ≈ 2 N.
  CHECK(field(fixed_line, "vertical_force") == Approx(2e5).epsilon(5e-5));
  int patches = 0;
  while (std::getline(lines, line) && std::getline(fixed_lines, fixed_line)) {
    ++patches;
    CHECK(field(fixed_line, "fn") == Approx(field(line, "fn")).epsilon(5e-5));
    CHECK(field(fixed_line, "ncontact") == field(line, "ncontact"));
    CHECK(field(fixed_line, "y_track") == Approx(field(line, "y_track")).margin(1e-3));
    CHECK(field(fixed_line, "stiffness") > 0);
  }
  CHECK(patches == 2);

  const auto both = run_wheelrail("--z 0.1 --load 1e5");
  CHECK(both.status == 2);
  CHECK_THAT(both.output, Contains("--z and --load exclude each other"));
  const auto nan = run_wheelrail("--z nan");
  CHECK(nan.status == 2);
  CHECK_THAT(nan.output, Contains("--z needs a number"));
}

TEST_CASE("fastnorm-wheelrail reports flange climb by status", "[cli][wheelrail]") {
  // y = 8 mm: the equilibrium has the right wheel on its flange tip (climbed 5.7 mm);
  // y = 7 mm: no equilibrium, the flange contact lies on the steepest flank.
  const auto found = run_wheelrail("--y 8 --elements 20");
  CHECK(found.status == 1);
  CHECK_THAT(found.output, Contains("# status=flange climb") && Contains("past the steepest flank"));
  CHECK_THAT(found.output, Contains("wheel=right patch=1"));
  const auto none = run_wheelrail("--y -7 --elements 20");
  CHECK(none.status == 1);
  CHECK_THAT(none.output, Contains("# status=flange climb") && Contains("no equilibrium found"));
  CHECK_THAT(none.output, !Contains("wheel="));
  const auto fixed = run_wheelrail("--y 8 --z -5.68 --roll -7.82e-3 --elements 20");
  CHECK(fixed.status == 1);
  CHECK_THAT(fixed.output, Contains("# status=flange climb"));
  CHECK(run_wheelrail("--y 6 --elements 20").status == 0);
  // Issue #15: at y = -29 mm the left flange rested on the rail head, reported converged.
  const auto far = run_wheelrail("--y -29 --elements 20");
  CHECK(far.status == 1);
  CHECK_THAT(far.output, Contains("# status=flange climb") && Contains("the left wheel's contact"));
}

TEST_CASE("fastnorm-wheelrail takes the Manchester benchmark's radius and materials", "[cli][wheelrail]") {
  // at y = 3 mm, right wheel, 10 kN: CONTACT's weighted centre x = −4.9990 mm
  // (wheelset-geometry.md §6.1); G and E give the same material.
  const std::string pose = "--fz 1e4 --wheel right --y 3 --yaw 0.41252961 --roll -0.180e-3 --radius 460 --elements 30";
  const auto by_shear = run_wheelrail(pose + " --shear 82 --poisson 0.28");
  REQUIRE(by_shear.status == 0);
  CHECK(field(by_shear.output, "x_track") == Approx(-4.9990).margin(0.3e-3));
  const auto by_young = run_wheelrail(pose + " --young 209.92 --poisson 0.28");
  REQUIRE(by_young.status == 0);
  CHECK(field(by_young.output, "pmax") == Approx(field(by_shear.output, "pmax")).epsilon(1e-6));
  // A stiffer rail raises the peak pressure; the wheel's radius changes the patch.
  const auto stiff_rail = run_wheelrail(pose + " --shear 82 --poisson 0.28 --rail-young 400");
  REQUIRE(stiff_rail.status == 0);
  CHECK(field(stiff_rail.output, "pmax") > 1.1 * field(by_shear.output, "pmax"));
  const auto standard_radius = run_wheelrail("--fz 1e4 --wheel right --y 3 --yaw 0.41252961 --roll -0.180e-3 --elements 30");
  REQUIRE(standard_radius.status == 0);
  CHECK(field(standard_radius.output, "x_track") != Approx(field(by_shear.output, "x_track")).margin(1e-3));
  // A wider gauge moves the wheelset's taping lines with it: the same contact, shifted.
  const auto wide = run_wheelrail(pose + " --shear 82 --poisson 0.28 --gauge 1445");
  REQUIRE(wide.status == 0);
  CHECK(field(wide.output, "y_track") == Approx(field(by_shear.output, "y_track") + 5).margin(0.01));
}

TEST_CASE("fastnorm-wheelrail --friction gives each patch its creep forces", "[cli][wheelrail][tangential]") {
  // Full sliding (ξ = 0.1): every element slips and the force on the rail is −μ Fn along x.
  const auto sliding = run_wheelrail("--y 3 --elements 30 --friction 0.3 --creepage-x 0.1");
  REQUIRE(sliding.status == 0);
  std::istringstream lines(sliding.output);
  std::string line;
  std::getline(lines, line);  // the '#' line
  int patches = 0;
  while (std::getline(lines, line)) {
    ++patches;
    INFO(line);
    const double limit = 0.3 * field(line, "fn");
    CHECK_THAT(line, Contains("tangential=converged"));
    CHECK(field(line, "nadh") == 0);
    CHECK(field(line, "fx") == Approx(-limit).epsilon(1e-4));
    CHECK(std::abs(field(line, "fs")) <= 1e-4 * limit);
  }
  CHECK(patches == 2);

  // Centred (y = 0), the right patch is the left one mirrored in s (which points to +y_track
  // on both wheels): the left patch's (fx, fs, mn) at (ξ, η, φ) are the right patch's
  // (fx, −fs, −mn) at (ξ, −η, −φ), to the printed digits; in partial slip.
  const auto forward = run_wheelrail("--y 0 --elements 30 --friction 0.3 --creepage-x 1e-3 --creepage-y 5e-4 --spin 0.5");
  const auto mirrored =
      run_wheelrail("--y 0 --elements 30 --friction 0.3 --creepage-x 1e-3 --creepage-y -5e-4 --spin -0.5");
  REQUIRE(forward.status == 0);
  REQUIRE(mirrored.status == 0);
  const std::string left = patch_line(forward.output, "left"), right = patch_line(mirrored.output, "right");
  INFO(left << "\n" << right);
  CHECK(field(left, "nadh") > 0);
  CHECK(field(left, "nslip") > 0);
  CHECK(std::hypot(field(left, "fx"), field(left, "fs")) < 0.3 * field(left, "fn"));
  CHECK(field(right, "fx") == Approx(field(left, "fx")).epsilon(1e-5));
  CHECK(field(right, "fs") == Approx(-field(left, "fs")).epsilon(1e-5));
  CHECK(field(right, "mn") == Approx(-field(left, "mn")).epsilon(1e-5));
  CHECK(field(right, "nadh") == field(left, "nadh"));

  const auto without_friction = run_wheelrail("--creepage-x 1e-3");
  CHECK(without_friction.status == 2);
  CHECK_THAT(without_friction.output, Contains("--creepage-x needs --friction"));
}

TEST_CASE("fastnorm-wheelrail --patch-fn prescribes each patch's normal force", "[cli][wheelrail][tangential]") {
  // Centred, the two patches are mirror images: 90 and 110 kN instead of their own 100 kN
  // give those forces, a smaller and a larger approach and contact, and creep forces that
  // grow with the load (in partial slip Fx grows less than in proportion).
  const auto own = run_wheelrail("--y 0 --elements 30 --friction 0.3 --creepage-x 1e-3");
  const auto given = run_wheelrail("--y 0 --elements 30 --friction 0.3 --creepage-x 1e-3 --patch-fn 90000,110000");
  REQUIRE(own.status == 0);
  REQUIRE(given.status == 0);
  const std::string left = patch_line(given.output, "left"), right = patch_line(given.output, "right");
  const std::string reference = patch_line(own.output, "left");
  INFO(reference << "\n" << left << "\n" << right);
  CHECK(field(left, "fn") == Approx(90000).epsilon(1e-5));
  CHECK(field(right, "fn") == Approx(110000).epsilon(1e-5));
  CHECK(field(left, "approach") < field(reference, "approach"));
  CHECK(field(right, "approach") > field(reference, "approach"));
  CHECK(field(left, "ncontact") < field(right, "ncontact"));
  CHECK(-field(left, "fx") < -field(reference, "fx"));
  CHECK(-field(right, "fx") > -field(reference, "fx"));
  const auto miscounted = run_wheelrail("--y 0 --elements 30 --patch-fn 90000");
  CHECK(miscounted.status == 2);
  CHECK_THAT(miscounted.output, Contains("--patch-fn gives 1 forces for 2 patches"));
}

TEST_CASE("fastnorm-wheelrail --write-case with --friction writes cases fastnorm-solve rolls the same",
          "[cli][wheelrail][tangential]") {
  // Each patch's case holds its tangential line; fastnorm-solve, given nothing but the case,
  // solves the same normal and steady-rolling problems: the same fx, fs, mn and areas.
  const fastnorm::test::ScratchDirectory scratch_dir("fastnorm_wheelrail_rolling_");
  const fs::path& dir = scratch_dir.path();
  const auto run = run_wheelrail("--fz 1e5 --wheel right --y 0 --elements 30 --friction 0.3 --creepage-x 1e-3 "
                                 "--creepage-y 5e-4 --spin 0.5 --tangential strip --write-case " +
                                 (dir / "p").string());
  REQUIRE(run.status == 0);
  const std::string written = (dir / "p_right_1.case").string();
  const auto problem = fastnorm::read_case_file<double>(written);
  REQUIRE(problem.rolling.has_value());
  CHECK(problem.rolling->friction == 0.3);
  CHECK(problem.rolling->creepage.spin == 0.5);
  const auto solved = fastnorm::test::run_command(FASTNORM_SOLVE_EXE, written + " --quiet --tangential strip");
  REQUIRE(solved.status == 0);
  INFO(run.output << solved.output);
  for (const char* name : {"fx", "fs", "mn"}) {
    CHECK(field(solved.output, name) == Approx(field(run.output, name)).epsilon(1e-5));  // printed to 6 digits
  }
  CHECK(field(solved.output, "nadh") == field(run.output, "nadh"));
}
