// Full NORM against the closed-form Hertz solution, sphere and ellipse, steel on steel,
// on refined grids. The tolerances are the measured errors with a margin; the measured
// figures are in docs/validation.md §1 (command there).
#include <catch2/catch.hpp>
#include <cmath>
#include <fastnorm/hertz.hpp>
#include <fastnorm/norm_solver.hpp>

#include "support/complementarity.hpp"
#include "support/surfaces.hpp"

namespace {

using fastnorm::test::steel;

struct HertzErrors {
  double approach, peak_pressure, semi_axis_x, semi_axis_y, area;
};

// Solves the Hertz problem of radii (rx, ry) under `force` on an n × n grid covering
// ±1.25 semi-axes (n odd: an element sits on the first point of contact) and returns
// the relative errors against the closed form.
HertzErrors hertz_errors(double rx, double ry, double force, int n) {
  const auto hertz = fastnorm::hertz_from_force(rx, ry, steel.combined_modulus(), force);
  const fastnorm::Grid<> grid = fastnorm::hertz_grid(hertz, n, 1.25);
  const double dx = grid.dx(), dy = grid.dy();
  const fastnorm::NormSolver<> solver(grid, steel);
  const Eigen::VectorXd h = fastnorm::hertz_undeformed_distance(grid, rx, ry);
  const auto solution = solver.solve(h, fastnorm::Loading<>::force(force));
  REQUIRE(solution.status == fastnorm::Status::converged);
  fastnorm::test::require_complementarity(solver.influence(), h, solution);

  // Semi-axes from the second moments of the contact elements: for a uniform ellipse
  // the mean of x² is a²/4; an element of width dx adds dx²/12 of its own.
  double sum_x2 = 0, sum_y2 = 0;
  for (Eigen::Index k = 0; k < grid.size(); ++k) {
    if (!solution.in_contact(k)) continue;
    sum_x2 += grid.x_of(k) * grid.x_of(k) + dx * dx / 12;
    sum_y2 += grid.y_of(k) * grid.y_of(k) + dy * dy / 12;
  }
  const double count = static_cast<double>(solution.contact_count());
  const double pi = 3.14159265358979323846;
  return {std::abs(solution.approach / hertz.approach - 1),
          std::abs(solution.pressure.maxCoeff() / hertz.max_pressure - 1),
          std::abs(2 * std::sqrt(sum_x2 / count) / hertz.semi_axis_x - 1),
          std::abs(2 * std::sqrt(sum_y2 / count) / hertz.semi_axis_y - 1),
          std::abs(count * dx * dy / (pi * hertz.semi_axis_x * hertz.semi_axis_y) - 1)};
}

void check_refinement(double rx, double ry, double force, const HertzErrors& finest_bound) {
  HertzErrors previous{1, 1, 1, 1, 1}, coarsest = previous;
  for (int n : {21, 41, 81}) {
    const HertzErrors e = hertz_errors(rx, ry, force, n);
    INFO("n = " << n << ": approach " << e.approach << ", p0 " << e.peak_pressure << ", a " << e.semi_axis_x
                << ", b " << e.semi_axis_y << ", area " << e.area);
    // Approach and peak pressure converge steadily with the grid.
    CHECK(e.approach < previous.approach);
    CHECK(e.peak_pressure < previous.peak_pressure);
    // The contact outline converges with oscillations (edge elements switch on and off):
    // the finest grid beats the coarsest.
    if (n == 21) coarsest = e;
    previous = e;
    if (n == 81) {
      CHECK(e.approach <= finest_bound.approach);
      CHECK(e.peak_pressure <= finest_bound.peak_pressure);
      CHECK(e.semi_axis_x <= finest_bound.semi_axis_x);
      CHECK(e.semi_axis_y <= finest_bound.semi_axis_y);
      CHECK(e.area <= finest_bound.area);
      CHECK(e.semi_axis_x < coarsest.semi_axis_x);
      CHECK(e.semi_axis_y < coarsest.semi_axis_y);
      CHECK(e.area < coarsest.area);
    }
  }
}

}  // namespace

// Bounds on the 81 × 81 grid: about twice the measured errors (approach 4.6e-5, peak
// pressure 3.5e-5, semi-axes 2.4e-3, area 4.6e-3 for both shapes; docs/validation.md §1).
const HertzErrors finest_bound{1e-4, 1e-4, 5e-3, 5e-3, 1e-2};

TEST_CASE("NORM converges to Hertz for a sphere on a plane", "[norm][hertz]") {
  check_refinement(0.3, 0.3, 5e4, finest_bound);
}

TEST_CASE("NORM converges to Hertz for an ellipsoidal contact", "[norm][hertz]") {
  check_refinement(0.46, 0.3, 1e5, finest_bound);
}

TEST_CASE("The Hertz ellipse pressure closes the gap (independent of NORM)", "[norm][hertz]") {
  // Displacements of the closed-form pressure, by the influence table, make
  // h − δ + u vanish inside the ellipse up to the discretisation error.
  const double rx = 0.46, ry = 0.3;
  const auto hertz = fastnorm::hertz_from_force(rx, ry, steel.combined_modulus(), 1e5);
  const fastnorm::Grid<> grid = fastnorm::hertz_grid(hertz, 81, 1.25);
  const fastnorm::InfluenceTable<> table(grid, steel);
  Eigen::VectorXd pressure(grid.size());
  for (Eigen::Index k = 0; k < grid.size(); ++k) pressure(k) = hertz.pressure(grid.x_of(k), grid.y_of(k));
  const Eigen::VectorXd gap = (fastnorm::hertz_undeformed_distance(grid, rx, ry).array() - hertz.approach).matrix() +
                              table.displacement(pressure);
  double worst_inside = 0;
  for (Eigen::Index k = 0; k < grid.size(); ++k) {
    const double x = grid.x_of(k) / hertz.semi_axis_x, y = grid.y_of(k) / hertz.semi_axis_y;
    if (x * x + y * y < 0.8 * 0.8) worst_inside = std::max(worst_inside, std::abs(gap(k)));
  }
  // Measured: 1.4e-4 of δ on 81 × 81.
  INFO("max |h - delta + u| / delta inside 0.8 of the ellipse = " << worst_inside / hertz.approach);
  CHECK(worst_inside <= 5e-4 * hertz.approach);
}
