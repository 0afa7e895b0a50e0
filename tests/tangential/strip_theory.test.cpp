// Strip theory (strip_theory.hpp, docs/tangential.md §10) against independent truths: Kalker's
// linear theory, Carter's two-dimensional solution, CONTACT's exact results on its creep
// curve and large-spin case; its symmetries, saturation, regions and errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <fastnorm/strip_theory.hpp>
#include <map>
#include <string>
#include <vector>

#include "support/hertz_rolling.hpp"

using Catch::Matchers::Contains;
using fastnorm::test::creepage;
using fastnorm::test::HertzProblem;
using fastnorm::test::linear_case;
using fastnorm::test::linear_checks;
using fastnorm::test::LinearCase;
using fastnorm::test::number;
using fastnorm::test::peer_rows;

namespace {

/// Strip theory on CONTACT's problem of a peer row (mm, N, rad/mm converted to SI); the
/// normal problem solved once per example (the rows of one example share it).
fastnorm::TangentialSolution<> solve_peer_row(const std::map<std::string, std::string>& row) {
  static std::map<std::string, HertzProblem> problems;
  auto found = problems.find(row.at("source"));
  if (found == problems.end()) found = problems.emplace(row.at("source"), fastnorm::test::peer_row_problem(row)).first;
  const HertzProblem& problem = found->second;
  REQUIRE(number(row, "chi_rad") == 0);
  REQUIRE(problem.normal.normal_force == Approx(number(row, "fn_N")).epsilon(1e-9));
  auto answer = fastnorm::StripTheory<>(problem.material)
                    .solve(problem.grid, problem.normal, number(row, "mu"), fastnorm::test::peer_row_creepage(row));
  REQUIRE(answer.ok());
  return answer;
}

}  // namespace

TEST_CASE("Strip theory gives Kalker's linear theory in full adhesion", "[tangential]") {
  // (T9) within 3 % on NORM's pressure, 40 × 40 elements, a/b ≈ 0.5, 1 and 2 (measured
  // 0.4 % for ξ and η, 0.9 % for φ): each element holds the closed form's mean, so there is
  // no step at a strip's leading edge as in FASTSIM.
  for (double ratio : {0.35, 1.0, 2.83}) {
    const LinearCase hertz_case = linear_case(0.3 * ratio, 0.3, 40);
    const auto& problem = hertz_case.problem;
    fastnorm::StripTheory<> strips(problem.material);
    for (const auto& check : linear_checks(hertz_case)) {
      const auto answer = strips.solve(problem.grid, problem.normal, 0.3, check.creepage);
      REQUIRE(answer.ok());
      CHECK(answer.slip_elements == 0);
      const double force = check.longitudinal ? answer.force_x : answer.force_y;
      INFO("a/b = " << hertz_case.ellipse.a / hertz_case.ellipse.b << ", " << check.name << ": strip theory " << force
                    << " N, linear theory " << check.expected << " N");
      CHECK(std::abs(force / check.expected - 1) <= 0.03);
    }
  }
}

TEST_CASE("Strip theory gives Carter's solution on the middle of a long cylinder", "[tangential]") {
  const auto cylinder = fastnorm::test::long_cylinder();
  fastnorm::StripTheory<> strips(cylinder.material);
  for (const double fraction : {0.25, 0.5, 0.75}) {
    const double xi = fraction * cylinder.friction * cylinder.nominal_half_width / cylinder.radius;
    const auto answer = strips.solve(cylinder.grid, cylinder.normal, cylinder.friction, creepage(xi, 0, 0));
    REQUIRE(answer.ok());
    const double carter = cylinder.carter(xi), strip = cylinder.middle_strip_force(answer);
    INFO("xi R/(mu a) = " << xi * cylinder.radius / (cylinder.friction * cylinder.half_width) << ": middle strip "
                          << strip << ", Carter " << carter);
    CHECK(std::abs(strip - carter) <= 0.015);  // measured 0.001–0.005
  }
  // On so slender a contact the calibrated compliances are the plane-strain and antiplane
  // ones of the two-dimensional theory, 2(1 − ν)/G and 2/G (docs/tangential.md Eq. (T15)).
  REQUIRE(strips.compliances().size() == 1);
  const double shear_modulus = cylinder.material.combined_shear_modulus(), nu = cylinder.material.combined_poisson_ratio();
  CHECK(strips.compliances()[0].longitudinal == Approx(2 * (1 - nu) / shear_modulus).epsilon(0.01));
  CHECK(strips.compliances()[0].lateral == Approx(2 / shear_modulus).epsilon(0.01));
}

TEST_CASE("Strip theory follows CONTACT's exact creep curve, large-spin case and 2-D Carter example", "[tangential][peer]") {
  const auto rows = peer_rows();
  if (rows.empty()) return fastnorm::test::reference_data_missing("peer-tangential/hertz.tsv");
  int curve = 0;
  for (const auto& row : rows) {
    if (row.at("variant") != "exact") continue;
    const auto answer = solve_peer_row(row);
    const double mm = 1e-3, scale = number(row, "mu") * number(row, "fn_N");
    const double c = row.at("source") == "carter2d" ? 0.0 : std::sqrt(number(row, "aa_mm") * number(row, "bb_mm")) * mm;
    INFO(row.at("source") << " case " << row.at("case") << ": Fx " << answer.force_x << " (CONTACT " << row.at("fx_N")
                          << "), Fy " << answer.force_y << " (" << row.at("fs_N") << "), Mz " << answer.spin_moment
                          << " N m (" << number(row, "mn_Nmm") * mm << ")");
    if (row.at("source") == "carter2d") {
      // One row of CONTACT's plane strain: issue 29 asks 0.03 μFn; measured 0.0007.
      CHECK(std::abs(answer.force_x - number(row, "fx_N")) <= 0.01 * scale);
    } else if (row.at("source") == "tractcurv") {
      // Issue 29 asks 0.04 μFn; measured 0.0049 (FASTSIM: 0.045).
      CHECK(std::abs(answer.force_x - number(row, "fx_N")) <= 0.01 * scale);
      ++curve;
    } else {
      // Issue 29 asks 0.04 μFn and 0.025 μFn·c; measured 0.032 and 0.0246 (CONTACT's own
      // FaStrip: 0.036 and 0.002).
      CHECK(std::abs(answer.force_y - number(row, "fs_N")) <= 0.04 * scale);
      CHECK(std::abs(answer.spin_moment - number(row, "mn_Nmm") * mm) <= 0.025 * scale * c);
    }
  }
  CHECK(curve == 30);
}

TEST_CASE("Strip theory keeps the problem's symmetries and saturates against the rigid slip", "[tangential]") {
  const LinearCase hertz_case = linear_case(0.46, 0.3, 40);
  const auto& problem = hertz_case.problem;
  const double mu = 0.3, scale = mu * problem.normal.normal_force, c = 5e-3;
  fastnorm::StripTheory<> strips(problem.material);
  const auto solve = [&](const fastnorm::Creepage<>& value, fastnorm::RollingDirection direction) {
    auto answer = strips.solve(problem.grid, problem.normal, mu, value, direction);
    REQUIRE(answer.ok());
    return answer;
  };
  const auto positive = fastnorm::RollingDirection::positive_x;
  const auto base = solve(creepage(4e-4, -3e-4, 0.4), positive);
  REQUIRE(base.slip_elements > 0);
  REQUIRE(base.adhesion_elements > 0);
  fastnorm::test::check_mirror_and_reversal(solve, base, 1e-9 * scale, c);
  SECTION("continuity: a creepage changed by 1e-9 of itself changes the forces by as little") {
    const auto near = solve(creepage(4e-4 * (1 + 1e-9), -3e-4, 0.4), positive);
    CHECK(near.force_x == Approx(base.force_x).margin(1e-6 * scale));
    CHECK(near.force_y == Approx(base.force_y).margin(1e-6 * scale));
  }
  SECTION("large creepage: full slip, |F| = mu Fn against w") {
    const auto sliding = solve(creepage(0.06, -0.08, 0), positive);
    CHECK(sliding.adhesion_elements == 0);
    CHECK(sliding.force_x / scale == Approx(-0.6).margin(1e-9));
    CHECK(sliding.force_y / scale == Approx(0.8).margin(1e-9));
    CHECK(sliding.frictional_power_per_speed > 0);
  }
  SECTION("the slip is against the traction wherever an element slips") {
    for (Eigen::Index k = 0; k < problem.grid.size(); ++k) {
      if (base.state(k) != fastnorm::TractionState::slip) continue;
      CHECK(base.slip_x(k) * base.traction_x(k) + base.slip_y(k) * base.traction_y(k) <= 0);
    }
  }
}

TEST_CASE("Strip theory calibrates each connected region of a contact on its own", "[tangential]") {
  // Two Hertzian contacts of different shapes on one grid, apart along y: the answer is the
  // one of each contact alone, and each region has its own compliances.
  const auto material = fastnorm::Material<>::steel();
  const fastnorm::Grid<> grid(40, 60, 0.25e-3, 0.25e-3, -4.875e-3, -7.375e-3);
  const auto contact = [&](double y0, double ry) {
    fastnorm::Solution<> normal;
    normal.status = fastnorm::Status::converged;
    normal.pressure = Eigen::VectorXd::Zero(grid.size());
    normal.in_contact = fastnorm::Solution<>::Mask::Constant(grid.size(), false);
    for (Eigen::Index k = 0; k < grid.size(); ++k) {
      const double x = grid.x(grid.i_of(k)) / 4e-3, y = (grid.y(grid.j_of(k)) - y0) / ry;
      if (x * x + y * y >= 1) continue;
      normal.in_contact(k) = true;
      normal.pressure(k) = 1e9 * std::sqrt(1 - x * x - y * y);
    }
    normal.normal_force = normal.pressure.sum() * grid.element_area();
    return normal;
  };
  const auto lower = contact(-4e-3, 2e-3), upper = contact(4.5e-3, 3e-3);
  fastnorm::Solution<> both = lower;
  both.pressure += upper.pressure;
  both.in_contact = lower.in_contact || upper.in_contact;
  both.normal_force += upper.normal_force;
  const auto rolling = creepage(3e-4, 2e-4, 0.3);
  fastnorm::StripTheory<> strips(material);
  const auto together = strips.solve(grid, both, 0.3, rolling);
  REQUIRE(strips.compliances().size() == 2);
  CHECK(strips.compliances()[0].longitudinal != strips.compliances()[1].longitudinal);
  const auto alone_lower = strips.solve(grid, lower, 0.3, rolling), alone_upper = strips.solve(grid, upper, 0.3, rolling);
  REQUIRE(strips.compliances().size() == 1);
  CHECK(together.force_x == Approx(alone_lower.force_x + alone_upper.force_x).epsilon(1e-12));
  CHECK(together.force_y == Approx(alone_lower.force_y + alone_upper.force_y).epsilon(1e-12));
  CHECK(together.spin_moment == Approx(alone_lower.spin_moment + alone_upper.spin_moment).epsilon(1e-12));
  CHECK(together.adhesion_elements == alone_lower.adhesion_elements + alone_upper.adhesion_elements);
}

TEST_CASE("Strip theory refuses bad input by name and answers no contact", "[tangential]") {
  const LinearCase hertz_case = linear_case(0.46, 0.3, 20, false);
  const auto& problem = hertz_case.problem;
  fastnorm::StripTheory<> strips(problem.material);
  CHECK_THROWS_WITH(strips.solve(problem.grid, problem.normal, 0.0, creepage(1e-3, 0, 0)), Contains("friction"));
  CHECK_THROWS_WITH(strips.solve(problem.grid, problem.normal, 0.3, creepage(0, std::nan(""), 0)), Contains("creepage"));
  const fastnorm::Grid<> other(5, 5, 1e-3, 1e-3);
  CHECK_THROWS_WITH(strips.solve(other, problem.normal, 0.3, creepage(1e-3, 0, 0)), Contains("normal"));
  fastnorm::Solution<> empty = problem.normal;
  empty.pressure.setZero();
  empty.in_contact.setConstant(false);
  empty.status = fastnorm::Status::no_contact;
  const auto answer = strips.solve(problem.grid, empty, 0.3, creepage(1e-3, 0, 0));
  CHECK(answer.status == fastnorm::Status::no_contact);
  CHECK(answer.force_x == 0);
}
