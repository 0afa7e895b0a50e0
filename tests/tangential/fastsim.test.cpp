// Kalker's linear theory and simplified theory (kalker_coefficients.hpp, fastsim.hpp,
// docs/tangential.md §9): the coefficient table, the exact path at vanishing creepage against
// the linear theory, FASTSIM against CONTACT's FASTSIM results, and FASTSIM's symmetries.
#include <catch2/catch.hpp>

#include <cmath>
#include <fastnorm/fastsim.hpp>
#include <fastnorm/hertz.hpp>
#include <fastnorm/kalker_coefficients.hpp>
#include <fastnorm/tangential_solver.hpp>
#include <map>
#include <string>
#include <vector>

#include "support/hertz_rolling.hpp"

using Catch::Matchers::Contains;
using fastnorm::test::creepage;
using fastnorm::test::hertz_problem;
using fastnorm::test::HertzProblem;
using fastnorm::test::number;
using fastnorm::test::peer_rows;
using fastnorm::test::analytic_pressure;
using fastnorm::test::linear_case;
using fastnorm::test::linear_checks;
using fastnorm::test::LinearCase;

TEST_CASE("Kalker's coefficients are his table's, interpolated", "[tangential]") {
  // Table E.3 of Kalker (1990) at a/b = 0.5 and b/a = 0.5, ν = 0, 0.25, 0.5.
  const auto wide = fastnorm::kalker_coefficients(0.5, 0.25);
  CHECK(wide.c11 == Approx(3.62).epsilon(1e-12));
  CHECK(wide.c22 == Approx(3.01).epsilon(1e-12));
  CHECK(wide.c23 == Approx(0.929).epsilon(1e-12));
  const auto long_ellipse = fastnorm::kalker_coefficients(2.0, 0.5);
  CHECK(long_ellipse.c11 == Approx(6.11).epsilon(1e-12));
  CHECK(long_ellipse.c22 == Approx(5.56).epsilon(1e-12));
  CHECK(long_ellipse.c23 == Approx(2.96).epsilon(1e-12));
  CHECK(fastnorm::kalker_coefficients(1 / 0.3, 0.0).c23 == Approx(3.79).epsilon(1e-12));
  // The circle is the last row of both halves; the table's range ends at g = 0.1.
  const auto circle = fastnorm::kalker_coefficients(1.0, 0.28);
  const auto circle_other = fastnorm::kalker_coefficients(1.0 + 1e-12, 0.28);
  CHECK(circle.c11 == Approx(circle_other.c11).epsilon(1e-9));
  CHECK(circle.c23 == Approx(circle_other.c23).epsilon(1e-9));
  CHECK(fastnorm::kalker_coefficients(0.1, 0.25).c22 == Approx(2.52).epsilon(1e-12));
  // Linear between rows: half-way between g = 0.6 and 0.7 at a tabulated ν.
  CHECK(fastnorm::kalker_coefficients(0.65, 0.25).c11 == Approx((3.72 + 3.81) / 2).epsilon(1e-12));
  // Between the columns of ν, between the neighbouring columns' values (monotone here).
  const auto between = fastnorm::kalker_coefficients(0.5, 0.28);
  CHECK(between.c11 > 3.62);
  CHECK(between.c11 < 4.83);
  SECTION("Kalker's asymptotes take over below g = 0.1 near the table's first row") {
    // The asymptotes are the limits g → 0; at g = 0.1 they are within 6 % of the table
    // (measured: C23 of ellipses wide across at ν = 0.5 the largest gap, −6.0 %).
    for (double nu : {0.0, 0.25, 0.5}) {
      for (bool along_x : {false, true}) {
        const double g = 0.1;
        const auto table = fastnorm::kalker_coefficients(along_x ? 1 / g : g, nu);
        const auto asymptote = fastnorm::kalker_coefficients(along_x ? 1 / (g - 1e-9) : g - 1e-9, nu);
        INFO("nu " << nu << (along_x ? ", b/a = 0.1" : ", a/b = 0.1") << ": table " << table.c11 << " " << table.c22
                   << " " << table.c23 << ", asymptote " << asymptote.c11 << " " << asymptote.c22 << " "
                   << asymptote.c23);
        CHECK(std::abs(asymptote.c11 / table.c11 - 1) < 0.065);
        CHECK(std::abs(asymptote.c22 / table.c22 - 1) < 0.065);
        CHECK(std::abs(asymptote.c23 / table.c23 - 1) < 0.065);
      }
    }
  }
  CHECK_THROWS_WITH(fastnorm::kalker_coefficients(0.0, 0.28), Contains("a_over_b"));
  CHECK_THROWS_WITH(fastnorm::kalker_coefficients(std::nan(""), 0.28), Contains("a_over_b"));
  CHECK_THROWS_WITH(fastnorm::kalker_coefficients(1.0, 0.6), Contains("poisson_ratio"));
  CHECK_THROWS_WITH(fastnorm::kalker_coefficients(1.0, -0.1), Contains("poisson_ratio"));
}

TEST_CASE("At vanishing creepage the exact path gives Kalker's linear theory", "[tangential]") {
  // Fx = −G c² C11 ξ, Fy = −G c² (C22 η + c C23 φ) (docs/tangential.md Eq. (T9)), within 3 %
  // on a 40 × 40 grid (CONTACT: +1.5 % on 48 × 44); a/b ≈ 0.5, 1 and 2, ν = 0.28.
  for (double ratio : {0.35, 1.0, 2.83}) {
    const LinearCase hertz_case = linear_case(0.3 * ratio, 0.3, 40);
    const auto& problem = hertz_case.problem;
    for (const auto& check : linear_checks(hertz_case)) {
      const auto exact = fastnorm::solve_steady_rolling(problem.grid, problem.material, problem.normal, 0.3, check.creepage);
      REQUIRE(exact.ok());
      const double force = check.longitudinal ? exact.force_x : exact.force_y;
      INFO("a/b = " << hertz_case.ellipse.a / hertz_case.ellipse.b << ", " << check.name << ": exact " << force
                    << " N, linear theory " << check.expected << " N (" << exact.slip_elements << " slip elements)");
      CHECK(std::abs(force / check.expected - 1) <= 0.03);
    }
  }
}

TEST_CASE("FASTSIM with Kalker's flexibilities tends to the linear theory as the grid is refined", "[tangential]") {
  // In full adhesion FASTSIM's traction grows by dx·w/L from element to element, a whole
  // step already at a strip's first element: an excess over the linear theory that shrinks
  // with the element size, measured 4.3 %, 1.3 % and 0.75 % with 40, 80 and 160 elements
  // across the grid (docs/tangential.md §9); CONTACT's FASTSIM has the same.
  for (double ratio : {0.35, 1.0, 2.83}) {
    std::vector<double> excess;
    for (Eigen::Index elements : {40, 80, 160}) {
      const LinearCase hertz_case = linear_case(0.3 * ratio, 0.3, elements, false);  // on Hertz's pressure
      const auto flexibility = fastnorm::kalker_flexibility(hertz_case.ellipse, hertz_case.problem.material);
      double largest = 0;
      for (const auto& check : linear_checks(hertz_case)) {
        const auto answer = fastnorm::solve_fastsim(hertz_case.problem.grid, hertz_case.problem.normal, 0.3,
                                                    check.creepage, flexibility);
        REQUIRE(answer.ok());
        const double force = check.longitudinal ? answer.force_x : answer.force_y;
        largest = std::max(largest, std::abs(force / check.expected - 1));
      }
      excess.push_back(largest);
    }
    INFO("a/b ~ " << std::pow(ratio, 2.0 / 3) << ": largest excess over the linear theory on 40, 80, 160 elements: "
                  << excess[0] << ", " << excess[1] << ", " << excess[2]);
    CHECK(excess[0] <= 0.05);
    CHECK(excess[1] < excess[0]);
    CHECK(excess[2] < excess[1]);
    CHECK(excess[2] <= 0.01);
  }
}

TEST_CASE("FASTSIM gives CONTACT's simplified-theory results", "[tangential][peer]") {
  const auto rows = peer_rows();
  if (rows.empty()) return fastnorm::test::reference_data_missing("peer-tangential/hertz.tsv");
  const double mm = 1e-3;
  std::map<std::string, fastnorm::Flexibility<>> series_flexibility;  // a series prints them on its first row
  int checked = 0;
  for (const auto& row : rows) {
    const std::string variant = row.at("variant");
    if (variant != "parabolic+fastsim" && variant != "elliptic+fastsim") continue;
    const std::string series = row.at("source") + " " + variant;
    if (row.at("flx1_mm3_N").empty()) {
      REQUIRE(series_flexibility.count(series) == 1);
    } else {  // mm³/N to m/Pa = m³/N
      series_flexibility[series] = {number(row, "flx1_mm3_N") * 1e-9, number(row, "flx2_mm3_N") * 1e-9,
                                    number(row, "flx3_mm3_N") * 1e-9};
    }
    const Eigen::Index mx = std::stol(row.at("mx")), my = std::stol(row.at("my"));
    const double dx = number(row, "dx_mm") * mm, dy = number(row, "dy_mm") * mm;
    const fastnorm::Grid<> grid(mx, my, dx, dy, -static_cast<double>(mx - 1) * dx / 2, -static_cast<double>(my - 1) * dy / 2);
    const double a = number(row, "aa_mm") * mm, b = number(row, "bb_mm") * mm, fn = number(row, "fn_N"), mu = number(row, "mu");
    const auto normal = analytic_pressure(grid, a, b, fn, variant == "parabolic+fastsim");
    const auto direction = number(row, "chi_rad") == 0 ? fastnorm::RollingDirection::positive_x
                                                        : fastnorm::RollingDirection::negative_x;
    const auto answer = fastnorm::solve_fastsim(grid, normal, mu, fastnorm::test::peer_row_creepage(row),
                                                series_flexibility.at(series), direction);
    REQUIRE(answer.ok());
    const double c = std::sqrt(a * b), power = answer.frictional_power_per_speed * number(row, "veloc_mm_s") * mm;
    INFO(row.at("source") << " case " << row.at("case") << " (" << variant << ", " << mx << " x " << my << "): Fx "
                          << answer.force_x << " (CONTACT " << row.at("fx_N") << "), Fy " << answer.force_y << " ("
                          << row.at("fs_N") << "), Mz " << answer.spin_moment << " N m (" << number(row, "mn_Nmm") * mm
                          << "), adhesion " << answer.adhesion_elements << " (" << row.at("nadh") << "), slip "
                          << answer.slip_elements << " (" << row.at("nslip") << "), power " << power << " W ("
                          << row.at("fric_power_W") << ")");
    // The same discretisation: forces within 5e-4 μFn, CONTACT's four printed digits of the
    // inputs (a, b, dx, L) and of the forces (the largest difference is 2.6e-4 μFn, where
    // the input's rounding alone moves Fx by 0.5e-4 μFn); areas to an element in a thousand.
    CHECK(std::abs(answer.force_x - number(row, "fx_N")) <= 5e-4 * mu * fn);
    CHECK(std::abs(answer.force_y - number(row, "fs_N")) <= 5e-4 * mu * fn);
    CHECK(std::abs(answer.spin_moment - number(row, "mn_Nmm") * mm) <= 5e-4 * mu * fn * c);
    const double contact = number(row, "ncon");
    CHECK(std::abs(static_cast<double>(answer.adhesion_elements) - number(row, "nadh")) <= 1 + 1e-3 * contact);
    CHECK(std::abs(static_cast<double>(answer.slip_elements) - number(row, "nslip")) <= 1 + 1e-3 * contact);
    CHECK(std::abs(power + number(row, "fric_power_W")) <= 1e-3 * std::abs(number(row, "fric_power_W")) + 1e-3);
    ++checked;
  }
  CHECK(checked == 35);
}

TEST_CASE("FASTSIM keeps the problem's symmetries and saturates", "[tangential]") {
  const LinearCase hertz_case = linear_case(0.46, 0.3, 40, false);
  const auto& problem = hertz_case.problem;
  const double mu = 0.3, scale = mu * problem.normal.normal_force, c = 5e-3;
  const auto flexibility = fastnorm::kalker_flexibility(hertz_case.ellipse, problem.material);
  const auto solve = [&](const fastnorm::Creepage<>& value, fastnorm::RollingDirection direction) {
    auto answer = fastnorm::solve_fastsim(problem.grid, problem.normal, mu, value, flexibility, direction);
    REQUIRE(answer.ok());
    return answer;
  };
  const auto positive = fastnorm::RollingDirection::positive_x;
  const auto base = solve(creepage(4e-4, -3e-4, 0.4), positive);
  INFO("base: Fx " << base.force_x << " Fy " << base.force_y << " Mz " << base.spin_moment);
  REQUIRE(base.slip_elements > 0);
  REQUIRE(base.adhesion_elements > 0);
  fastnorm::test::check_mirror_and_reversal(solve, base, 1e-12 * scale, c);
  SECTION("the spin centre: a move with xi and eta transformed changes nothing only with one flexibility") {
    // With L1 = L2 = L3 the rates (T11) are w/L; with three flexibilities ξ/L1 − φ y/L3 is
    // not, and the answer depends on where the spin centre is (docs/tangential.md §9).
    auto moved = creepage(4e-4 - 0.4 * 2e-3, -3e-4 + 0.4 * -1e-3, 0.4);
    moved.spin_centre_x = -1e-3;
    moved.spin_centre_y = 2e-3;
    const fastnorm::Flexibility<> one{flexibility.longitudinal, flexibility.longitudinal, flexibility.longitudinal};
    const auto here = fastnorm::solve_fastsim(problem.grid, problem.normal, mu, creepage(4e-4, -3e-4, 0.4), one);
    const auto there = fastnorm::solve_fastsim(problem.grid, problem.normal, mu, moved, one);
    CHECK(there.force_x == Approx(here.force_x).margin(1e-9 * scale));
    CHECK(there.force_y == Approx(here.force_y).margin(1e-9 * scale));
    CHECK(there.spin_moment == Approx(here.spin_moment).margin(1e-9 * scale * c));
    const auto three = solve(moved, positive);
    CHECK(std::abs(three.force_x - base.force_x) > 1e-3 * scale);
  }
  SECTION("large creepage: full slip, |F| = mu Fn against (xi/L1, eta/L2)") {
    // FASTSIM's slip direction is its rates', which differs from w's where L1 ≠ L2.
    const double xi = 0.06, eta = -0.08, rate_x = xi / flexibility.longitudinal, rate_y = eta / flexibility.lateral;
    const auto sliding = solve(creepage(xi, eta, 0), positive);
    CHECK(sliding.adhesion_elements == 0);
    CHECK(std::hypot(sliding.force_x, sliding.force_y) == Approx(scale).epsilon(1e-3));
    CHECK(sliding.force_x / scale == Approx(-rate_x / std::hypot(rate_x, rate_y)).margin(1e-3));
    CHECK(sliding.force_y / scale == Approx(-rate_y / std::hypot(rate_x, rate_y)).margin(1e-3));
    CHECK(sliding.frictional_power_per_speed > 0);
  }
}

TEST_CASE("The equivalent ellipse has the contact area's size and shape", "[tangential]") {
  const LinearCase hertz_case = linear_case(0.46, 0.3, 40, false);
  const auto ellipse = fastnorm::equivalent_ellipse(hertz_case.problem.grid, hertz_case.problem.normal);
  // The discrete area's edges lie within an element of Hertz's.
  const auto& grid = hertz_case.problem.grid;
  CHECK(std::abs(ellipse.a - hertz_case.ellipse.a) <= grid.dx());
  CHECK(std::abs(ellipse.b - hertz_case.ellipse.b) <= grid.dy());
  const auto automatic = fastnorm::solve_fastsim(grid, hertz_case.problem.material, hertz_case.problem.normal, 0.3,
                                                 creepage(2e-4, 0, 0));
  const auto given = fastnorm::solve_fastsim(grid, hertz_case.problem.normal, 0.3, creepage(2e-4, 0, 0),
                                             fastnorm::kalker_flexibility(ellipse, hertz_case.problem.material));
  CHECK(automatic.force_x == given.force_x);
}

TEST_CASE("FASTSIM refuses bad input by name", "[tangential]") {
  const LinearCase hertz_case = linear_case(0.46, 0.3, 40, false);
  const auto& problem = hertz_case.problem;
  const fastnorm::Flexibility<> flexibility{1e-13, 1e-13, 1e-13};
  CHECK_THROWS_WITH(fastnorm::solve_fastsim(problem.grid, problem.normal, 0.0, creepage(1e-3, 0, 0), flexibility),
                    Contains("friction"));
  CHECK_THROWS_WITH(fastnorm::solve_fastsim(problem.grid, problem.normal, 0.3, creepage(0, std::nan(""), 0), flexibility),
                    Contains("creepage"));
  CHECK_THROWS_WITH(fastnorm::solve_fastsim(problem.grid, problem.normal, 0.3, creepage(1e-3, 0, 0),
                                            fastnorm::Flexibility<>{1e-13, 0, 1e-13}),
                    Contains("flexibility.lateral"));
  const fastnorm::Grid<> other(5, 5, 1e-3, 1e-3);
  CHECK_THROWS_WITH(fastnorm::solve_fastsim(other, problem.normal, 0.3, creepage(1e-3, 0, 0), flexibility),
                    Contains("normal"));
  CHECK_THROWS_WITH(fastnorm::kalker_flexibility(fastnorm::Ellipse<>{-1e-3, 1e-3}, problem.material),
                    Contains("ellipse.a"));
  // No element carrying pressure: no traction, status no_contact, from both overloads.
  fastnorm::Solution<> empty = problem.normal;
  empty.pressure.setZero();
  empty.in_contact.setConstant(false);
  empty.status = fastnorm::Status::no_contact;
  CHECK(fastnorm::solve_fastsim(problem.grid, empty, 0.3, creepage(1e-3, 0, 0), flexibility).status ==
        fastnorm::Status::no_contact);
  CHECK(fastnorm::solve_fastsim(problem.grid, problem.material, empty, 0.3, creepage(1e-3, 0, 0)).status ==
        fastnorm::Status::no_contact);
  CHECK_THROWS_WITH(fastnorm::equivalent_ellipse(problem.grid, empty), Contains("no element"));
}

TEST_CASE("FASTSIM's sensitivities to the creepages are its forces' derivatives", "[tangential]") {
  // Against central differences of the forces, in full adhesion (where they are the linear
  // theory's constant gradient), partial slip and near full slip, both rolling directions,
  // with a spin centre off the origin.
  const LinearCase hertz_case = linear_case(0.46, 0.3, 40, false);
  const auto& problem = hertz_case.problem;
  const auto flexibility = fastnorm::kalker_flexibility(hertz_case.ellipse, problem.material);
  const double mu = 0.3, c = std::sqrt(hertz_case.ellipse.a * hertz_case.ellipse.b);
  for (const auto direction : {fastnorm::RollingDirection::positive_x, fastnorm::RollingDirection::negative_x}) {
    for (const double scale : {1e-3, 0.5, 1.0, 4.0}) {
      auto base = creepage(4e-4 * scale, -3e-4 * scale, 0.4 * scale);
      base.spin_centre_x = 1e-3;
      base.spin_centre_y = -0.5e-3;
      fastnorm::TangentialSolution<> answer;
      fastnorm::CreepJacobian<double> jacobian;
      fastnorm::solve_fastsim(problem.grid, problem.normal, mu, base, flexibility, direction, answer, &jacobian);
      REQUIRE(answer.ok());
      const Eigen::Vector3d steps(1e-9, 1e-9, 1e-9 / c);
      for (int column = 0; column < 3; ++column) {
        auto forces = [&](double sign) {
          auto moved = base;
          (column == 0 ? moved.longitudinal : column == 1 ? moved.lateral : moved.spin) += sign * steps(column);
          const auto at = fastnorm::solve_fastsim(problem.grid, problem.normal, mu, moved, flexibility, direction);
          return Eigen::Vector3d(at.force_x, at.force_y, at.spin_moment);
        };
        const Eigen::Vector3d difference = (forces(1) - forces(-1)) / (2 * steps(column));
        const Eigen::Vector3d weights(1, 1, 1 / c);  // moments in force units
        INFO("scale " << scale << ", column " << column << ": analytic " << jacobian.col(column).transpose()
                      << ", differences " << difference.transpose() << ", slip " << answer.slip_elements);
        CHECK((jacobian.col(column) - difference).cwiseProduct(weights).norm() <=
              1e-5 * jacobian.col(column).cwiseProduct(weights).norm());
      }
      if (scale == 1e-3) {  // in full adhesion the forces are linear: F = J w
        const Eigen::Vector3d creepages(base.longitudinal, base.lateral, base.spin);
        CHECK(answer.slip_elements == 0);
        CHECK(jacobian.row(0).dot(creepages) == Approx(answer.force_x).epsilon(1e-9));
        CHECK(jacobian.row(1).dot(creepages) == Approx(answer.force_y).epsilon(1e-9));
        CHECK(jacobian.row(2).dot(creepages) == Approx(answer.spin_moment).epsilon(1e-9));
      }
    }
  }
}
