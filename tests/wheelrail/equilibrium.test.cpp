// Static equilibrium: residuals, symmetry, yaw, errors, and CONTACT's single-wheel mode
// against the wr_* peer cases (normal force, lateral contact position, contact angle).
#include <catch2/catch.hpp>
#include <fastnorm/fastnorm.hpp>

#include <filesystem>

#include "support/wheelrail_cases.hpp"

namespace wr = fastnorm::wheelrail;
using Catch::Matchers::Contains;

namespace {

wr::EquilibriumOptions coarse_equilibrium() {
  wr::EquilibriumOptions options;
  options.contact.grid.elements = 30;
  return options;
}

}  // namespace

TEST_CASE("The wheelset carries its load with no roll moment", "[wheelrail][equilibrium]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  const double load = 2e5;
  for (double y : {0.0, 3e-3, 6e-3}) {
    INFO("y = " << y * 1e3 << " mm");
    const auto result = wr::solve_equilibrium(track, wheelset, y, 0, load, coarse_equilibrium());
    REQUIRE(result.ok());
    double vertical = 0, moment = 0;
    for (const auto& contact : result.patches) {
      const auto& [frame, grid, h] = contact.patch;
      const auto& solution = contact.solution;
      REQUIRE(solution.ok());
      const Eigen::Vector3d arm = frame.reference - wheelset.centre(result.pose);
      const double c = std::cos(frame.inclination), s = std::sin(frame.inclination);
      vertical += solution.normal_force * c;
      moment -= solution.normal_force * (arm.y() * c + arm.z() * s);
      // approach 0 on the reported h: the solution is the one of h as it stands, and h is
      // the exact undeformed_distance at the reported pose to the model's stated accuracy
      // (interpolated along rows within DistanceAccuracy::tolerance, docs/wheel-rail.md §4)
      CHECK(solution.approach == 0);
      CHECK((h - wr::undeformed_distance(track, wheelset, result.pose, frame, grid)).cwiseAbs().maxCoeff() <=
            wr::DistanceAccuracy{}.tolerance);
      // The search's warm-started NORM gives cold NORM's answer on that h.
      const auto cold = fastnorm::NormSolver<double>(grid, fastnorm::Material<double>(2.1e11, 0.3))
                            .solve(h, fastnorm::Loading<double>::approach());
      CHECK(solution.normal_force == Approx(cold.normal_force).epsilon(1e-9));
      CHECK((solution.in_contact == cold.in_contact).all());
      CHECK(contact.stiffness > 0);
    }
    // Recomputed from the patches, not taken from the result.
    CHECK(std::abs(vertical - load) <= 1e-6 * load);
    CHECK(std::abs(moment) <= 1e-6 * load * 0.75);
    CHECK(result.vertical_force == Approx(vertical).epsilon(1e-12));
    // Both wheels carry load.
    double left = 0, right = 0;
    for (const auto& contact : result.patches) {
      (contact.patch.frame.side == wr::Side::left ? left : right) += contact.normal_force;
    }
    CHECK(left > 0.3 * load);
    CHECK(right > 0.3 * load);
  }
}

TEST_CASE("At y = 0, yaw 0 the equilibrium is mirror-symmetric", "[wheelrail][equilibrium]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  const auto result = wr::solve_equilibrium(track, wheelset, 0, 0, 2e5, coarse_equilibrium());
  REQUIRE(result.ok());
  REQUIRE(result.patches.size() == 2);
  const auto& a = result.patches[0];
  const auto& b = result.patches[1];
  CHECK(a.patch.frame.side != b.patch.frame.side);
  CHECK(std::abs(result.pose.roll) < 1e-9);
  CHECK(a.solution.normal_force == Approx(b.solution.normal_force).epsilon(1e-9));
  CHECK(a.patch.frame.reference.y() == Approx(-b.patch.frame.reference.y()).epsilon(1e-12));
  CHECK(a.patch.frame.contact_angle() == Approx(b.patch.frame.contact_angle()).epsilon(1e-9));
  CHECK(a.solution.contact_count() == b.solution.contact_count());
  CHECK(std::abs(result.lateral_force) < 1e-6 * 2e5);
}

TEST_CASE("Yaw moves the right patch back and the left patch forward", "[wheelrail][equilibrium]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  for (double yaw_deg : {1.0, -1.0}) {
    const double yaw = yaw_deg * fastnorm::pi<> / 180;
    const auto result = wr::solve_equilibrium(track, wheelset, 0, yaw, 2e5, coarse_equilibrium());
    REQUIRE(result.ok());
    for (const auto& contact : result.patches) {
      const auto& patch = contact.patch;
      const double expected = (patch.frame.side == wr::Side::right ? -1 : 1) * (yaw_deg > 0 ? 1 : -1);
      INFO(wr::to_string(patch.frame.side) << " wheel at yaw " << yaw_deg << " deg: x = " << patch.frame.reference.x());
      CHECK(patch.frame.reference.x() * expected > 0.012);  // ≈ 12.8 mm (§6.3 rigid: 12.973 mm)
    }
  }
}

TEST_CASE("Equilibrium input is checked by name", "[wheelrail][equilibrium]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  CHECK_THROWS_WITH(wr::solve_equilibrium(track, wheelset, 0, 0, -1), Contains("load"));
  CHECK_THROWS_WITH(wr::solve_equilibrium(track, wheelset, std::nan(""), 0, 2e5), Contains("y must"));
  CHECK_THROWS_WITH(wr::solve_equilibrium(track, wheelset, 0, 0.5, 2e5), Contains("yaw"));
  CHECK_THROWS_WITH(wr::solve_single_wheel(track, wheelset, wr::Side::left, 0, 0, 0), Contains("vertical_force"));
  CHECK_THROWS_WITH(wr::solve_single_wheel(track, wheelset, wr::Side::left, 0, 0, 1e5, {}, 0.3), Contains("roll"));
  auto options = coarse_equilibrium();
  CHECK_THROWS_WITH(options.contact.solver = fastnorm::SolverSpec<>::parse("spline"), Contains("unknown solver"));
  options = coarse_equilibrium();
  options.contact.grid.elements = 2;
  CHECK_THROWS_WITH(wr::solve_equilibrium(track, wheelset, 0, 0, 2e5, options), Contains("elements"));
  // Every option is validated up front, by name.
  options = coarse_equilibrium();
  options.force_tolerance = 0;
  CHECK_THROWS_WITH(options.validate(), Contains("force_tolerance"));
  options = coarse_equilibrium();
  options.contact.search.step = -1;
  CHECK_THROWS_WITH(wr::solve_equilibrium(track, wheelset, 0, 0, 2e5, options), Contains("step"));
  options = coarse_equilibrium();
  options.start = wr::WheelsetPose{0, std::nan(""), 0, 0};
  CHECK_THROWS_WITH(wr::solve_equilibrium(track, wheelset, 0, 0, 2e5, options), Contains("start: z must"));
  // One set of pose ranges for every function (wr::PoseLimits).
  CHECK_THROWS_WITH(wr::rigid_contact_pose(track, wheelset, 0, 0.15), Contains("yaw must lie within"));
  CHECK_THROWS_WITH(wr::check_pose({0, 0.2, 0, 0}, "pose"), Contains("pose: z must lie within"));
}

TEST_CASE("A step limit too small is a status, not an exception", "[wheelrail][equilibrium]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  auto options = coarse_equilibrium();
  options.max_iterations = 1;
  const auto result = wr::solve_equilibrium(track, wheelset, 3e-3, 0, 2e5, options);
  CHECK(result.status == wr::EquilibriumStatus::not_converged);
  CHECK_FALSE(result.ok());
  CHECK_THAT(result.message, Contains("1 steps"));
}

TEST_CASE("A wheel lifted off its rail is a lost-contact status", "[wheelrail][equilibrium]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  auto options = coarse_equilibrium();
  options.start = wr::WheelsetPose{0, -5e-3, 0, 0};  // 5 mm above the rails
  const auto both = wr::solve_equilibrium(track, wheelset, 0, 0, 2e5, options);
  CHECK(both.status == wr::EquilibriumStatus::lost_contact);
  CHECK_THAT(both.message, Contains("does not touch"));
  const auto one = wr::solve_single_wheel(track, wheelset, wr::Side::right, 0, 0, 1e5, options);
  CHECK(one.status == wr::EquilibriumStatus::lost_contact);
  CHECK(one.patches.empty());
}

namespace {

// The equilibrium at each lateral shift of `shifts` (m), yaw (rad) and load (N): converged
// within |y| ≤ 6 mm, flange climb from |y| ≥ 7 mm (the rigid contact is on the 70° flank
// from 6.26 mm, wheelset-geometry.md §6.2), one of the two in between, never another
// status. Converged results balance the load; flange-climb results either hold an
// equilibrium whose flange patch lies at the climb point or beyond, or say that none was found.
void check_flange_range(const std::vector<double>& shifts, const std::vector<double>& yaws,
                        const std::vector<double>& loads) {
  const wr::Track track;
  const wr::Wheelset wheelset;
  // Full NORM: a reduced basis's force jumps as elements join its contact set, by more than
  // the force tolerance at times.
  auto options = coarse_equilibrium();
  options.contact.grid.elements = 20;
  int converged = 0, climbing = 0;
  for (double load : loads) {
    for (double yaw : yaws) {
      for (double y : shifts) {
        INFO("y " << y * 1e3 << " mm, yaw " << yaw * 1e3 << " mrad, load " << load / 1e3 << " kN");
        const auto result = wr::solve_equilibrium(track, wheelset, y, yaw, load, options);
        INFO(wr::to_string(result.status) << ": " << result.message);
        if (std::abs(y) <= 6e-3) CHECK(result.status == wr::EquilibriumStatus::converged);
        if (std::abs(y) >= 7e-3) CHECK(result.status == wr::EquilibriumStatus::flange_climb);
        if (result.status == wr::EquilibriumStatus::converged) {
          ++converged;
          CHECK(std::abs(result.vertical_residual) <= options.force_tolerance * load);
          for (const auto& patch : result.patches) CHECK_FALSE(wheelset.at_flange_climb(patch.profile_y));
        } else {
          REQUIRE(result.status == wr::EquilibriumStatus::flange_climb);
          ++climbing;
          const bool found = !result.patches.empty();
          CHECK_THAT(result.message, Contains(found ? "flange climb" : "no equilibrium found"));
          if (found) {
            CHECK(std::abs(result.vertical_residual) <= options.force_tolerance * load);
            CHECK(std::any_of(result.patches.begin(), result.patches.end(),
                              [&](const auto& patch) { return wheelset.at_flange_climb(patch.profile_y); }));
          }
        }
      }
    }
  }
  CHECK(converged > 0);
  CHECK(climbing > 0);
}

}  // namespace

TEST_CASE("Pressed against its flange the wheelset is in equilibrium or at flange climb",
          "[wheelrail][equilibrium]") {
  check_flange_range({-8e-3, -6.5e-3, -6e-3, 0, 6e-3, 6.3e-3, 6.4e-3, 6.5e-3, 7e-3, 8e-3}, {-20e-3, 0, 20e-3},
                     {1e5, 2.5e5});
}

TEST_CASE("From y = -8 to 8 mm the wheelset is in equilibrium or at flange climb", "[wheelrail][equilibrium][large]") {
  std::vector<double> shifts;
  for (int k = -32; k <= 32; ++k) shifts.push_back(k * 0.25e-3);
  check_flange_range(shifts, {-20e-3, -10e-3, 0, 10e-3, 20e-3}, {1e5, 1.75e5, 2.5e5});
}

TEST_CASE("The equilibrium pressed against the flange is mirror-symmetric", "[wheelrail][equilibrium]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  auto options = coarse_equilibrium();
  options.contact.solver = fastnorm::SolverSpec<double>::parse("elliptic");
  const auto right = wr::solve_equilibrium(track, wheelset, 6.3e-3, 10e-3, 2e5, options);
  const auto left = wr::solve_equilibrium(track, wheelset, -6.3e-3, -10e-3, 2e5, options);
  REQUIRE(right.ok());
  REQUIRE(left.ok());
  CHECK(left.pose.z == Approx(right.pose.z).margin(1e-9));
  CHECK(left.pose.roll == Approx(-right.pose.roll).margin(1e-9));
  CHECK(left.lateral_force == Approx(-right.lateral_force).epsilon(1e-6));
  // The flange carries the wheelset: most of the lateral force, at a steep angle.
  double steepest = 0;
  for (const auto& patch : right.patches) steepest = std::max(steepest, patch.contact_angle);
  CHECK(steepest > 0.6);
}

TEST_CASE("With the Manchester set-up the reference point is CONTACT's at yaw", "[wheelrail][equilibrium]") {
  // Benchmark at y = 3 mm (r0 = 460 mm, G = 82 GPa, nu = 0.28, 10 kN per wheel, yaw
  // 7.2 mrad, CONTACT's roll −0.180 mrad): CONTACT's weighted patch centres x,
  // wheelset-geometry.md §6.1 (y = 2 mm is left out: its roll is not given there, and x
  // moves by 1.2 µm per 0.07 mrad of roll).
  const wr::Track track;
  wr::WheelsetLayout layout;
  layout.nominal_radius = 0.46;
  const wr::Wheelset wheelset(wr::s1002_wheel(), layout);
  auto options = coarse_equilibrium();
  const double shear = 82e9, poisson = 0.28;
  options.contact.material = fastnorm::Material<double>(2 * shear * (1 + poisson), poisson);
  struct Case {
    double y_mm, roll;
    double x_right_mm, x_left_mm;
  };
  for (const Case& c : {Case{3, -0.180e-3, -4.9990, 5.4373}}) {
    for (wr::Side side : {wr::Side::right, wr::Side::left}) {
      INFO("y " << c.y_mm << " mm, " << wr::to_string(side));
      const auto result = wr::solve_single_wheel(track, wheelset, side, c.y_mm * 1e-3, 2.4e-3 * c.y_mm, 1e4, options,
                                                 c.roll);
      REQUIRE(result.ok());
      REQUIRE(result.patches.size() == 1);
      const double x = result.patches[0].patch.frame.reference.x() * 1e3;
      CHECK(x == Approx(side == wr::Side::right ? c.x_right_mm : c.x_left_mm).margin(0.3e-3));  // 4 decimals
    }
  }
}

namespace {

// Single-wheel mode on every wr_* case: FZ = 100 kN on CONTACT's wheel, roll 0.
void compare_with_contact(Eigen::Index elements) {
  const auto files = fastnorm::test::wheelrail_peer_cases();
  if (files.empty()) return;
  const wr::Track track;
  const wr::Wheelset wheelset;
  auto options = coarse_equilibrium();
  options.contact.grid.elements = elements;
  double worst_force = 0, worst_y = 0, worst_angle = 0, worst_z = 0;
  for (const auto& path : files) {
    const auto setup = fastnorm::test::read_wheelrail_case(path);
    const auto problem = fastnorm::read_case_file<double>(path);
    const auto result = wr::solve_single_wheel(track, wheelset, setup.side, setup.y_mm * 1e-3, setup.yaw, 1e5, options);
    INFO(std::filesystem::path(path).filename().string());
    REQUIRE(result.ok());
    REQUIRE(result.patches.size() == 1);
    const auto& patch = result.patches[0].patch;
    const auto& solution = result.patches[0].solution;
    const double force = solution.normal_force / problem.result->normal_force - 1;
    const double y = patch.frame.reference.y() * 1e3 - setup.ycp;
    const double angle = patch.frame.contact_angle() - std::abs(setup.deltcp);
    const double z = result.pose.z * 1e3 - setup.z_mm;
    INFO("Fn " << force << ", y " << y << " mm, angle " << angle << " rad, z " << z << " mm");
    CHECK(std::abs(force) <= 5e-5);   // issue: 0.5 %; measured ≤ 2.1e-5
    CHECK(std::abs(y) <= 0.01);       // issue: 0.5 mm; measured ≤ 0.0056 mm
    CHECK(std::abs(angle) <= 2e-4);   // issue: 5 mrad; measured ≤ 6e-5 (DELTCP has 4 decimals)
    CHECK(std::abs(z) <= 2e-4);       // CONTACT's z has 4 decimals
    worst_force = std::max(worst_force, std::abs(force));
    worst_y = std::max(worst_y, std::abs(y));
    worst_angle = std::max(worst_angle, std::abs(angle));
    worst_z = std::max(worst_z, std::abs(z));
  }
  WARN(elements << " elements: max |Fn/Fn_CONTACT - 1| " << worst_force << ", max |y - YCP| " << worst_y
                << " mm, max |angle - |DELTCP|| " << worst_angle << " rad, max |z - Z| " << worst_z << " mm");
}

}  // namespace

TEST_CASE("Single-wheel mode reproduces CONTACT's wr_* patches", "[wheelrail][equilibrium][peer]") {
  compare_with_contact(30);
}

TEST_CASE("Single-wheel mode reproduces CONTACT's wr_* patches at 60 elements", "[wheelrail][equilibrium][peer][large]") {
  compare_with_contact(60);
}
