// Steady rolling with friction (tangential_solver.hpp, docs/tangential.md §8): against
// CONTACT's exact results on Hertzian cases, saturation, and the problem's symmetries.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <Eigen/LU>
#include <fastnorm/detail/anderson_mixing.hpp>
#include <fastnorm/case_file.hpp>
#include <fastnorm/norm_solver.hpp>
#include <fastnorm/tangential_solver.hpp>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "support/hertz_rolling.hpp"
#include "support/peer_cases.hpp"

using Catch::Matchers::Contains;

namespace {

using fastnorm::test::creepage;
using fastnorm::test::hertz_problem;
using fastnorm::test::HertzProblem;
using fastnorm::test::number;
using fastnorm::test::peer_rows;

/// A small problem for the property tests: CONTACT's tractcurv ellipse (a/b = 0.5) on a
/// 24 × 22 grid, steel-like, 106.7 kN.
const HertzProblem& small_problem() {
  static const HertzProblem problem = hertz_problem(0.8, 0.2814, 24, 22, 0.5778e-3, 1.2608e-3, 8.2e10, 0.28, 106700);
  return problem;
}

/// Solves a peer row (CONTACT's mm, N, rad/mm converted to SI) and checks forces within
/// `force_tolerance`·μFn and the spin moment within `moment_tolerance`·μFn·c, c = √(ab).
void check_peer_row(const std::map<std::string, std::string>& row, double force_tolerance, double moment_tolerance) {
  const double mm = 1e-3;
  const HertzProblem problem = fastnorm::test::peer_row_problem(row);
  REQUIRE(number(row, "chi_rad") == 0);  // the peer rows roll towards +x
  const double mu = number(row, "mu"), fn = number(row, "fn_N");
  const auto answer = fastnorm::solve_steady_rolling(problem.grid, problem.material, problem.normal, mu,
                                                     fastnorm::test::peer_row_creepage(row));
  REQUIRE(answer.ok());
  const double c = std::sqrt(number(row, "aa_mm") * number(row, "bb_mm")) * mm;
  INFO(row.at("source") << " case " << row.at("case") << ": Fx " << answer.force_x << " (CONTACT " << row.at("fx_N")
                        << "), Fy " << answer.force_y << " (" << row.at("fs_N") << "), Mz " << answer.spin_moment
                        << " N m (" << number(row, "mn_Nmm") * mm << "), adhesion " << answer.adhesion_elements << " ("
                        << row.at("nadh") << "), slip " << answer.slip_elements << " (" << row.at("nslip")
                        << "), sweeps " << answer.sweeps);
  CHECK(std::abs(answer.force_x - number(row, "fx_N")) <= force_tolerance * mu * fn);
  CHECK(std::abs(answer.force_y - number(row, "fs_N")) <= force_tolerance * mu * fn);
  CHECK(std::abs(answer.spin_moment - number(row, "mn_Nmm") * mm) <= moment_tolerance * mu * fn * c);
  // Same normal solution, same discretisation: the areas agree to a few elements.
  const double contact = number(row, "ncon");
  CHECK(std::abs(static_cast<double>(answer.adhesion_elements) - number(row, "nadh")) <= 0.005 * contact);
  CHECK(std::abs(static_cast<double>(answer.slip_elements) - number(row, "nslip")) <= 0.005 * contact);
}

std::vector<std::map<std::string, std::string>> exact_rows(const std::string& source) {
  std::vector<std::map<std::string, std::string>> selected;
  for (const auto& row : peer_rows()) {
    if (row.at("source") == source && row.at("variant") == "exact") selected.push_back(row);
  }
  return selected;
}

/// The problem in single precision: the same grid, material and NORM pressures, rounded.
struct FloatProblem {
  fastnorm::Grid<float> grid;
  fastnorm::Material<float> material;
  fastnorm::Solution<float> normal;
};

FloatProblem in_float(const HertzProblem& problem) {
  const auto& grid = problem.grid;
  const auto& material = problem.material;
  fastnorm::Solution<float> normal;
  normal.status = problem.normal.status;
  normal.pressure = problem.normal.pressure.cast<float>();
  normal.in_contact = problem.normal.in_contact;
  normal.normal_force = static_cast<float>(problem.normal.normal_force);
  return {fastnorm::Grid<float>(grid.mx(), grid.my(), static_cast<float>(grid.dx()), static_cast<float>(grid.dy()),
                                static_cast<float>(grid.x0()), static_cast<float>(grid.y0())),
          fastnorm::Material<float>(static_cast<float>(material.young_modulus(1)),
                                    static_cast<float>(material.poisson_ratio(1)),
                                    static_cast<float>(material.young_modulus(2)),
                                    static_cast<float>(material.poisson_ratio(2))),
          std::move(normal)};
}

fastnorm::Creepage<float> in_float(const fastnorm::Creepage<>& value) {
  fastnorm::Creepage<float> rounded;
  rounded.longitudinal = static_cast<float>(value.longitudinal);
  rounded.lateral = static_cast<float>(value.lateral);
  rounded.spin = static_cast<float>(value.spin);
  rounded.spin_centre_x = static_cast<float>(value.spin_centre_x);
  rounded.spin_centre_y = static_cast<float>(value.spin_centre_y);
  return rounded;
}

}  // namespace

TEST_CASE("Steady rolling gives CONTACT's exact large-spin case", "[tangential][peer]") {
  const auto rows = exact_rows("fastsim");
  if (rows.empty()) return fastnorm::test::reference_data_missing("peer-tangential/hertz.tsv");
  REQUIRE(rows.size() == 1);
  check_peer_row(rows.front(), 0.015, 0.02);
}

TEST_CASE("Steady rolling gives CONTACT's exact creep curve, across partial slip", "[tangential][peer]") {
  const auto rows = exact_rows("tractcurv");
  if (rows.empty()) return fastnorm::test::reference_data_missing("peer-tangential/hertz.tsv");
  REQUIRE(rows.size() == 30);
  // Full adhesion, a quarter, half and most of the area sliding, just saturated, far past.
  for (const int index : {0, 1, 2, 4, 7, 9, 18}) check_peer_row(rows[static_cast<std::size_t>(index)], 0.015, 0.02);
}

TEST_CASE("Steady rolling gives CONTACT's whole exact creep curve", "[tangential][peer][large]") {
  const auto rows = exact_rows("tractcurv");
  if (rows.empty()) return fastnorm::test::reference_data_missing("peer-tangential/hertz.tsv");
  for (const auto& row : rows) check_peer_row(row, 0.015, 0.02);
}

TEST_CASE("The middle of a long cylinder follows Carter's two-dimensional solution", "[tangential]") {
  const auto cylinder = fastnorm::test::long_cylinder();
  for (const double fraction : {0.25, 0.5, 0.75}) {
    const double xi = fraction * cylinder.friction * cylinder.nominal_half_width / cylinder.radius;
    const auto answer = fastnorm::solve_steady_rolling(cylinder.grid, cylinder.material, cylinder.normal,
                                                       cylinder.friction, creepage(xi, 0, 0));
    REQUIRE(answer.ok());
    const double carter = cylinder.carter(xi), strip = cylinder.middle_strip_force(answer);
    INFO("xi R/(mu a) = " << xi * cylinder.radius / (cylinder.friction * cylinder.half_width) << ": middle strip "
                          << strip << ", Carter " << carter << " (a = " << cylinder.half_width << " m)");
    CHECK(std::abs(strip - carter) <= 0.015);
  }
}

TEST_CASE("Steady rolling gives CONTACT's two-dimensional Carter example", "[tangential][peer]") {
  // CONTACT's carter2d: one row of 55 elements of 0.04 × 200 mm, h = x²/(2R), R = 500 mm,
  // Fn = 35.78 kN, ξ = −2.4e-4, μ = 0.3. On the same grid the half-space's row is as wide as
  // CONTACT's plane strain: the same approach and peak pressure, Fx within 0.015 μFn
  // (measured 0.0005), the same areas to an element.
  std::map<std::string, std::string> row;
  for (const auto& candidate : peer_rows()) {
    if (candidate.at("source") == "carter2d") row = candidate;
  }
  if (row.empty()) return fastnorm::test::reference_data_missing("peer-tangential/hertz.tsv");
  const double mm = 1e-3, mu = number(row, "mu"), fn = number(row, "fn_N");
  const HertzProblem problem = fastnorm::test::peer_row_problem(row);
  CHECK(problem.normal.approach == Approx(number(row, "approach_mm") * mm).epsilon(1e-3));
  CHECK(problem.normal.pressure.maxCoeff() == Approx(number(row, "pmax_MPa") * 1e6).epsilon(1e-3));
  const auto answer = fastnorm::solve_steady_rolling(problem.grid, problem.material, problem.normal, mu,
                                                     creepage(number(row, "cksi"), 0, 0));
  REQUIRE(answer.ok());
  INFO("Fx " << answer.force_x << " N (CONTACT " << row.at("fx_N") << "), adhesion " << answer.adhesion_elements
             << " (" << row.at("nadh") << "), slip " << answer.slip_elements << " (" << row.at("nslip") << ")");
  CHECK(std::abs(answer.force_x - number(row, "fx_N")) <= 0.015 * mu * fn);
  CHECK(std::abs(static_cast<double>(answer.adhesion_elements) - number(row, "nadh")) <= 1);
  CHECK(std::abs(static_cast<double>(answer.slip_elements) - number(row, "nslip")) <= 1);
}

TEST_CASE("Steady rolling solves the discrete problem on a wheel-rail patch across partial slip", "[tangential][peer]") {
  // CONTACT's wr_y6.0_psi0.0_right patch (814 elements in contact), (ξ, η, φ) = s·(10⁻³,
  // 5·10⁻⁴, 0.5 rad/m), μ = 0.3: the solver before 2026-11-27 stopped at its sweep limit for
  // s from 0.19 to 0.65. The answer is checked against the discrete conditions themselves,
  // the slip (T6) summed directly element by element from the influence table (not the
  // solver's differences): in adhesion s = 0 and |p| ≤ μ p_n, in slip |p| = μ p_n against s.
  const std::string path = fastnorm::test::peer_cases_dir() + "/wr_y6.0_psi0.0_right.case";
  if (!std::filesystem::is_regular_file(path)) return fastnorm::test::reference_data_missing("peer-cases/wr_y6.0_psi0.0_right.case");
  const auto stored = fastnorm::read_case_file(path);
  const auto normal = fastnorm::NormSolver<>(stored.grid, stored.material).solve(stored.undeformed_distance, stored.loading);
  REQUIRE(normal.ok());
  const fastnorm::SteadyRollingSolver<> rolling(stored.grid, stored.material);
  const auto& grid = stored.grid;
  const double mu = 0.3, shift = fastnorm::detail::spin_shift(grid, fastnorm::RollingDirection::positive_x);
  for (const double scale : {0.2, 0.5}) {
    const auto answer = rolling.solve(normal, mu, creepage(1e-3 * scale, 5e-4 * scale, 0.5 * scale));
    INFO("s = " << scale << ": " << answer.message << ", " << answer.sweeps << " sweeps, adhesion "
                << answer.adhesion_elements << ", slip " << answer.slip_elements);
    REQUIRE(answer.ok());
    CHECK(answer.adhesion_elements > 100);
    CHECK(answer.slip_elements > 20);
    const double rigid_scale = 1e-3 * scale;  // |ξ|, the size of the rigid slip
    double worst_adhesion_slip = 0, worst_bound = 0, worst_direction = 0;
    for (Eigen::Index k = 0; k < grid.size(); ++k) {
      if (answer.state(k) == fastnorm::TractionState::exterior) continue;
      const Eigen::Index i = grid.i_of(k), j = grid.j_of(k);
      double sx = 1e-3 * scale - 0.5 * scale * grid.y(j);
      double sy = 5e-4 * scale + 0.5 * scale * (grid.x(i) + shift);
      for (Eigen::Index source = 0; source < grid.size(); ++source) {
        if (answer.state(source) == fastnorm::TractionState::exterior) continue;
        const Eigen::Index di = i - grid.i_of(source), dj = j - grid.j_of(source);
        const auto here = rolling.influence().coefficients(di, dj), upstream = rolling.influence().coefficients(di + 1, dj);
        const double px = answer.traction_x(source), py = answer.traction_y(source);
        sx += ((here.xx - upstream.xx) * px + (here.xy - upstream.xy) * py) / grid.dx();
        sy += ((here.xy - upstream.xy) * px + (here.yy - upstream.yy) * py) / grid.dx();
      }
      const double bound = mu * normal.pressure(k), traction = std::hypot(answer.traction_x(k), answer.traction_y(k));
      if (answer.state(k) == fastnorm::TractionState::adhesion) {
        worst_adhesion_slip = std::max(worst_adhesion_slip, std::hypot(sx, sy) / rigid_scale);
        worst_bound = std::max(worst_bound, traction / bound - 1);
      } else {
        worst_bound = std::max(worst_bound, std::abs(traction / bound - 1));
        // p = −g s/|s|: the traction's direction against the slip's
        const double cosine = -(answer.traction_x(k) * sx + answer.traction_y(k) * sy) / (traction * std::hypot(sx, sy));
        worst_direction = std::max(worst_direction, 1 - cosine);
      }
    }
    CHECK(worst_adhesion_slip <= 1e-6);
    CHECK(worst_bound <= 1e-9);
    CHECK(worst_direction <= 1e-6);
  }
}

TEST_CASE("Large creepage saturates the traction bound against the rigid slip", "[tangential]") {
  const auto& problem = small_problem();
  const double mu = 0.3, fn = problem.normal.normal_force;
  for (const auto& [xi, eta] : std::vector<std::pair<double, double>>{{0.1, 0.0}, {0.06, -0.08}}) {
    const auto answer = fastnorm::solve_steady_rolling(problem.grid, problem.material, problem.normal, mu,
                                                       creepage(xi, eta, 0.0));
    REQUIRE(answer.ok());
    const double magnitude = std::hypot(answer.force_x, answer.force_y);
    INFO("creepage (" << xi << ", " << eta << "): |F|/(mu Fn) = " << magnitude / (mu * fn) << ", slip elements "
                      << answer.slip_elements << " of " << answer.slip_elements + answer.adhesion_elements);
    CHECK(answer.adhesion_elements == 0);
    CHECK(magnitude <= mu * fn * (1 + 1e-12));
    CHECK(magnitude >= 0.995 * mu * fn);
    // The force on body 1 opposes its rigid slip: F ≈ −μ Fn w/|w|.
    CHECK(answer.force_x / magnitude == Approx(-xi / std::hypot(xi, eta)).margin(2e-3));
    CHECK(answer.force_y / magnitude == Approx(-eta / std::hypot(xi, eta)).margin(2e-3));
    CHECK(answer.frictional_power_per_speed > 0);
  }
}

TEST_CASE("Steady rolling keeps the problem's symmetries", "[tangential]") {
  const auto& problem = small_problem();
  const double mu = 0.3, scale = mu * problem.normal.normal_force, c = 5e-3;
  const auto solve = [&](const fastnorm::Creepage<>& value, fastnorm::RollingDirection direction) {
    auto answer = fastnorm::solve_steady_rolling(problem.grid, problem.material, problem.normal, mu, value, direction);
    REQUIRE(answer.ok());
    return answer;
  };
  const auto positive = fastnorm::RollingDirection::positive_x;
  const auto base = solve(creepage(4e-4, -3e-4, 0.4), positive);
  INFO("base: Fx " << base.force_x << " Fy " << base.force_y << " Mz " << base.spin_moment << " sweeps " << base.sweeps);
  REQUIRE(base.slip_elements > 0);
  REQUIRE(base.adhesion_elements > 0);
  fastnorm::test::check_mirror_and_reversal(solve, base, 1e-6 * scale, c);
  SECTION("moving the spin centre with xi and eta transformed changes nothing") {
    // w = (xi - phi (y - y0), eta + phi (x - x0)): y0 += dy needs xi -= phi dy, x0 += dx needs eta += phi dx.
    auto moved = creepage(4e-4 - 0.4 * 2e-3, -3e-4 + 0.4 * -1e-3, 0.4);
    moved.spin_centre_x = -1e-3;
    moved.spin_centre_y = 2e-3;
    const auto answer = solve(moved, positive);
    CHECK(answer.force_x == Approx(base.force_x).margin(1e-6 * scale));
    CHECK(answer.force_y == Approx(base.force_y).margin(1e-6 * scale));
    CHECK(answer.spin_moment == Approx(base.spin_moment).margin(1e-6 * scale * c));
  }
  SECTION("continuity in the creepages") {
    const auto nearby = solve(creepage(4e-4 * (1 + 1e-4), -3e-4, 0.4), positive);
    CHECK(std::abs(nearby.force_x - base.force_x) <= 1e-3 * scale);
    CHECK(std::abs(nearby.force_y - base.force_y) <= 1e-3 * scale);
  }
}

TEST_CASE("CONTACT's stopping rule measures the root mean square of a sweep's changes", "[tangential]") {
  // TangentialStop::rms_change stops at the first sweep whose traction changes have a root
  // mean square at most tolerance times the tractions' (CONTACT's EPS). The same solve
  // limited to one sweep fewer returns the tractions that sweep started from (Anderson's
  // mixing included), so the measure can be formed from outside.
  const auto& problem = small_problem();
  fastnorm::TangentialOptions<> options;
  options.stop = fastnorm::TangentialStop::rms_change;
  options.tolerance = 1e-5;
  const fastnorm::SteadyRollingSolver<> contact_rule(problem.grid, problem.material, fastnorm::RollingDirection::positive_x,
                                                     options);
  const fastnorm::SteadyRollingSolver<> tight(problem.grid, problem.material);
  const double mu = 0.3, scale = mu * problem.normal.normal_force;
  for (const auto& value : {creepage(1e-3, 0, 0), creepage(5e-4, -3e-4, 0.4)}) {
    const auto answer = contact_rule.solve(problem.normal, mu, value);
    const auto reference = tight.solve(problem.normal, mu, value);
    REQUIRE(answer.ok());
    REQUIRE(reference.ok());
    INFO(answer.sweeps << " sweeps against " << reference.sweeps << ", adhesion " << answer.adhesion_elements << ", slip "
                       << answer.slip_elements);
    REQUIRE(answer.sweeps > 2);
    CHECK(answer.residual <= options.tolerance);
    fastnorm::TangentialOptions<> shorter = options;
    shorter.max_sweeps = answer.sweeps - 1;
    const auto before = fastnorm::SteadyRollingSolver<>(problem.grid, problem.material,
                                                        fastnorm::RollingDirection::positive_x, shorter)
                            .solve(problem.normal, mu, value);
    CHECK(before.status == fastnorm::Status::iteration_limit);
    CHECK(before.residual > options.tolerance);
    const double change = std::sqrt((answer.traction_x - before.traction_x).squaredNorm() +
                                    (answer.traction_y - before.traction_y).squaredNorm());
    const double size = std::sqrt(answer.traction_x.squaredNorm() + answer.traction_y.squaredNorm());
    CHECK(answer.residual == Approx(change / size).epsilon(1e-9));
    // Fewer sweeps than the default rule (no traction changing by 10⁻⁹ μ·max p_n), the same
    // areas, and forces within 10⁻⁶ μFn of its answer (10⁻⁷ at most on the 18 wheel–rail
    // patches of peer-cases at 7 creepage scales, docs/tangential.md §7).
    CHECK(answer.sweeps < reference.sweeps);
    CHECK(answer.adhesion_elements == reference.adhesion_elements);
    CHECK(answer.slip_elements == reference.slip_elements);
    CHECK(std::abs(answer.force_x - reference.force_x) <= 1e-6 * scale);
    CHECK(std::abs(answer.force_y - reference.force_y) <= 1e-6 * scale);
  }
}

TEST_CASE("Steady rolling in single precision converges with its defaults to CONTACT's large-spin case", "[tangential][peer]") {
  // The default tolerance is 32 ε of float (3.8e-6) where 1e-9 lies below its round-off;
  // the answer meets the double path's tolerances against CONTACT.
  const auto rows = exact_rows("fastsim");
  if (rows.empty()) return fastnorm::test::reference_data_missing("peer-tangential/hertz.tsv");
  const auto& row = rows.front();
  const double mm = 1e-3, mu = number(row, "mu"), fn = number(row, "fn_N");
  const FloatProblem problem = in_float(fastnorm::test::peer_row_problem(row));
  CHECK(fastnorm::TangentialOptions<float>().tolerance == Approx(32 * std::numeric_limits<float>::epsilon()));
  const auto answer = fastnorm::SteadyRollingSolver<float>(problem.grid, problem.material)
                          .solve(problem.normal, static_cast<float>(mu), in_float(fastnorm::test::peer_row_creepage(row)));
  INFO("Fx " << answer.force_x << " (CONTACT " << row.at("fx_N") << "), Fy " << answer.force_y << " (" << row.at("fs_N")
             << "), Mz " << answer.spin_moment << " N m, sweeps " << answer.sweeps << ", " << answer.message);
  REQUIRE(answer.ok());
  CHECK(answer.sweeps < 200);
  const double c = std::sqrt(number(row, "aa_mm") * number(row, "bb_mm")) * mm;
  CHECK(std::abs(static_cast<double>(answer.force_x) - number(row, "fx_N")) <= 0.015 * mu * fn);
  CHECK(std::abs(static_cast<double>(answer.force_y) - number(row, "fs_N")) <= 0.015 * mu * fn);
  CHECK(std::abs(static_cast<double>(answer.spin_moment) - number(row, "mn_Nmm") * mm) <= 0.02 * mu * fn * c);
}

TEST_CASE("A tolerance below the scalar's round-off never ends in a false convergence", "[tangential]") {
  // In float the sweeps' changes stagnate at round-off above 1e-8: the solve restarts more
  // relaxed, and its shorter steps must not pass for convergence (docs/tangential.md §7).
  // Either it stops at the limit, with the least changing iterate it met (before a restart),
  // or what it calls converged is the answer; both are within 10⁻⁴ μFn of double's.
  const FloatProblem problem = in_float(small_problem());
  const auto value = creepage(4e-4, -3e-4, 0.4);
  const double mu = 0.3, scale = mu * small_problem().normal.normal_force;
  const auto reference = fastnorm::solve_steady_rolling(small_problem().grid, small_problem().material,
                                                        small_problem().normal, mu, value);
  REQUIRE(reference.ok());
  fastnorm::TangentialOptions<float> options;
  options.tolerance = 1e-8f;
  const auto answer = fastnorm::SteadyRollingSolver<float>(problem.grid, problem.material,
                                                           fastnorm::RollingDirection::positive_x, options)
                          .solve(problem.normal, static_cast<float>(mu), in_float(value));
  INFO(answer.message << ", residual " << answer.residual << ", Fx " << answer.force_x << " against "
                      << reference.force_x);
  if (!answer.ok()) {
    CHECK(answer.status == fastnorm::Status::iteration_limit);
    CHECK(answer.residual > options.tolerance);
  }
  CHECK(std::abs(static_cast<double>(answer.force_x) - reference.force_x) <= 1e-4 * scale);
  CHECK(std::abs(static_cast<double>(answer.force_y) - reference.force_y) <= 1e-4 * scale);
}

TEST_CASE("Steady rolling refuses bad input by name", "[tangential]") {
  const auto& problem = small_problem();
  const auto solve = [&](double mu, const fastnorm::Creepage<>& value) {
    return fastnorm::solve_steady_rolling(problem.grid, problem.material, problem.normal, mu, value);
  };
  CHECK_THROWS_WITH(solve(0.0, creepage(1e-3, 0, 0)), Contains("friction"));
  CHECK_THROWS_WITH(solve(std::nan(""), creepage(1e-3, 0, 0)), Contains("friction"));
  CHECK_THROWS_WITH(solve(0.3, creepage(std::nan(""), 0, 0)), Contains("creepage"));
  const fastnorm::Grid<> other(5, 5, 1e-3, 1e-3);
  CHECK_THROWS_WITH(fastnorm::solve_steady_rolling(other, problem.material, problem.normal, 0.3, creepage(1e-3, 0, 0)),
                    Contains("normal"));
  fastnorm::TangentialOptions<> options;
  options.tolerance = 0;
  CHECK_THROWS_WITH(fastnorm::solve_steady_rolling(problem.grid, problem.material, problem.normal, 0.3,
                                                   creepage(1e-3, 0, 0), fastnorm::RollingDirection::positive_x,
                                                   options),
                    Contains("tolerance"));
  // A contact area in the grid's upstream column: the slip there needs one more element.
  const HertzProblem touching = hertz_problem(0.8, 0.2814, 8, 10, 1.6e-3, 2.6e-3, 8.2e10, 0.28, 106700);
  REQUIRE(touching.normal.in_contact(touching.grid.mx() - 1 + touching.grid.mx() * 5));
  CHECK_THROWS_WITH(fastnorm::solve_steady_rolling(touching.grid, touching.material, touching.normal, 0.3,
                                                   creepage(1e-3, 0, 0)),
                    Contains("upstream edge"));
}

TEST_CASE("An element's Coulomb problem is solved exactly", "[tangential]") {
  // s = r + k p: adhesion (s = 0, |p| <= g) or slip (|p| = g, p = -g s/|s|), whichever holds.
  int slipping = 0;
  for (int sample = 0; sample < 200; ++sample) {
    const double angle = 0.1 * sample, size = 0.02 * (1 + sample % 13);
    const double rx = size * std::cos(angle), ry = size * std::sin(angle);
    const double kx = 1 + 0.1 * (sample % 7), ky = 1 + 0.3 * (sample % 5), bound = 0.05;
    const auto p = fastnorm::detail::coulomb_element(rx, ry, bound, kx, ky);
    const double sx = rx + kx * p.x, sy = ry + ky * p.y, slip = std::hypot(sx, sy);
    INFO("r = (" << rx << ", " << ry << "), k = (" << kx << ", " << ky << ")");
    if (p.state == fastnorm::TractionState::adhesion) {
      CHECK(slip <= 1e-15);
      CHECK(std::hypot(p.x, p.y) <= bound);
    } else {
      ++slipping;
      CHECK(std::hypot(p.x, p.y) == Approx(bound).epsilon(1e-12));
      CHECK(p.x == Approx(-bound * sx / slip).margin(1e-12 * bound));
      CHECK(p.y == Approx(-bound * sy / slip).margin(1e-12 * bound));
      // Adhesion would have exceeded the bound.
      CHECK(std::hypot(rx / kx, ry / ky) > bound);
    }
  }
  CHECK(slipping > 20);
  CHECK(slipping < 180);
}

TEST_CASE("The rows' spectra give the steady-rolling operator's product summed directly", "[tangential]") {
  // D p on a box of the grid from each row's change spread through the spectra
  // (docs/tangential.md §7), against the sum over every source element of the D tables.
  const fastnorm::Grid<> grid(13, 9, 0.5e-3, 0.7e-3);
  const fastnorm::TangentialInfluenceTable<> influence(grid, fastnorm::Material<>(2.1e11, 0.28));
  const Eigen::Index first_column = 3, columns = 8, first_row = 1, rows = 7, mx = grid.mx(), my = grid.my();
  for (const auto direction : {fastnorm::RollingDirection::positive_x, fastnorm::RollingDirection::negative_x}) {
    const fastnorm::detail::RollingOperator<double> rolling(influence, direction);
    fastnorm::detail::RowSpectra<double> spectra(rolling, first_column, columns, rows);
    Eigen::VectorXd traction_x = Eigen::VectorXd::Zero(grid.size()), traction_y = traction_x;
    for (Eigen::Index j = first_row; j < first_row + rows; ++j) {
      for (Eigen::Index i = first_column; i < first_column + columns; ++i) {
        traction_x(i + mx * j) = std::sin(1.7 * double(i) + 0.3 * double(j * j));
        traction_y(i + mx * j) = std::cos(0.9 * double(i * j) - 0.4 * double(i));
      }
    }
    Eigen::MatrixXd elastic_spectra = Eigen::MatrixXd::Zero(spectra.spectrum_size(), rows);
    Eigen::VectorXd change(spectra.spectrum_size());
    for (Eigen::Index source = 0; source < rows; ++source) {
      const Eigen::Index j = first_row + source;
      spectra.forward_change(traction_x.data() + mx * j, traction_y.data() + mx * j, change);
      for (Eigen::Index target = 0; target < rows; ++target) spectra.add(target, source, change, elastic_spectra.col(target));
    }
    double largest = 0, worst = 0;
    for (Eigen::Index target = 0; target < rows; ++target) {
      const Eigen::Index j = first_row + target;
      Eigen::VectorXd elastic_x = Eigen::VectorXd::Zero(mx), elastic_y = elastic_x;
      spectra.inverse(elastic_spectra.col(target), elastic_x.data(), elastic_y.data());
      for (Eigen::Index i = first_column; i < first_column + columns; ++i) {
        double direct_x = 0, direct_y = 0;
        for (Eigen::Index k = 0; k < grid.size(); ++k) {
          // D(di) = C(di) − C(di + e), e the step towards the leading edge (T6).
          const Eigen::Index row = mx + i - grid.i_of(k), column = my - 1 + j - grid.j_of(k), ahead = row + rolling.shift;
          const double xx = rolling.xx(row, column) - rolling.xx(ahead, column);
          const double xy = rolling.xy(row, column) - rolling.xy(ahead, column);
          const double yy = rolling.yy(row, column) - rolling.yy(ahead, column);
          direct_x += xx * traction_x(k) + xy * traction_y(k);
          direct_y += xy * traction_x(k) + yy * traction_y(k);
        }
        largest = std::max({largest, std::abs(direct_x), std::abs(direct_y)});
        worst = std::max({worst, std::abs(elastic_x(i) - direct_x), std::abs(elastic_y(i) - direct_y)});
      }
    }
    CHECK(largest > 0);
    CHECK(worst <= 1e-12 * largest);
  }
}

TEST_CASE("Anderson mixing solves a linear fixed point as GMRES does, in dimension + 1 steps", "[tangential]") {
  // x = M x + b with M a contraction of spectral radius 0.9 in dimension 5 (independent truth:
  // (I − M)⁻¹ b by LU). With memory 5 the mixed iteration is GMRES on (I − M) x = b (Walker &
  // Ni 2011) and is exact after 6 evaluations; plain iteration is still off by 0.9⁶ of the way.
  const Eigen::Index dimension = 5;
  Eigen::MatrixXd rotation = Eigen::MatrixXd::Zero(dimension, dimension);
  for (Eigen::Index i = 0; i < dimension; ++i) rotation(i, (i + 1) % dimension) = 1;
  const Eigen::VectorXd spectrum = (Eigen::VectorXd(dimension) << 0.9, -0.7, 0.5, 0.3, -0.1).finished();
  const Eigen::MatrixXd basis = Eigen::MatrixXd::Identity(dimension, dimension) + 0.3 * rotation;
  const Eigen::MatrixXd map = basis * spectrum.asDiagonal() * basis.inverse();
  const Eigen::VectorXd offset = (Eigen::VectorXd(dimension) << 1, -2, 0.5, 3, -1).finished();
  const Eigen::VectorXd solution =
      (Eigen::MatrixXd::Identity(dimension, dimension) - map).partialPivLu().solve(offset);

  fastnorm::detail::AndersonMixing<double> mixing(dimension, dimension, dimension);
  Eigen::VectorXd mixed = Eigen::VectorXd::Zero(dimension), plain = mixed;
  for (int evaluation = 0; evaluation < 6; ++evaluation) {
    Eigen::VectorXd output = map * mixed + offset;
    const Eigen::VectorXd residual = output - mixed;
    mixing.mix(output, residual);
    mixed = output;
    plain = map * plain + offset;
  }
  CHECK((mixed - solution).norm() <= 1e-9 * solution.norm());
  CHECK((plain - solution).norm() >= 0.1 * solution.norm());

  // After a reset the history is gone: one evaluation is plain iteration again.
  mixing.reset();
  Eigen::VectorXd start = Eigen::VectorXd::Zero(dimension), output = map * start + offset;
  mixing.mix(output, output - start);
  CHECK(output.isApprox(offset));
}
