#pragma once
// Hertzian rolling problems as CONTACT's module 3 poses them, and the rows of CONTACT's
// tangential results (../shared/peer-tangential/hertz.tsv): shared by the tests of the
// exact and the simplified tangential paths.
#include <catch2/catch.hpp>

#include <fastnorm/fastsim.hpp>
#include <fastnorm/hertz.hpp>
#include <fastnorm/kalker_coefficients.hpp>
#include <fastnorm/norm_solver.hpp>
#include <fastnorm/tangential_problem.hpp>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "support/peer_cases.hpp"

namespace fastnorm::test {

/// A Hertzian problem as CONTACT's module 3 poses it: h = A1 x² + B1 y² on an mx × my grid
/// centred on the origin, normal force Fn, one material.
struct HertzProblem {
  fastnorm::Grid<> grid;
  fastnorm::Material<> material;
  fastnorm::Solution<> normal;
};

inline HertzProblem hertz_problem(double a1, double b1, Eigen::Index mx, Eigen::Index my, double dx, double dy,
                           double shear_modulus, double poisson_ratio, double normal_force) {
  const fastnorm::Grid<> grid(mx, my, dx, dy, -static_cast<double>(mx - 1) * dx / 2,
                              -static_cast<double>(my - 1) * dy / 2);
  const fastnorm::Material<> material(2 * shear_modulus * (1 + poisson_ratio), poisson_ratio);
  Eigen::VectorXd h(grid.size());
  for (Eigen::Index k = 0; k < grid.size(); ++k) {
    const double x = grid.x(grid.i_of(k)), y = grid.y(grid.j_of(k));
    h(k) = a1 * x * x + b1 * y * y;
  }
  auto normal = fastnorm::NormSolver<>(grid, material).solve(h, fastnorm::Loading<>::force(normal_force));
  REQUIRE(normal.ok());
  return {grid, material, std::move(normal)};
}

inline fastnorm::Creepage<> creepage(double xi, double eta, double phi) {
  fastnorm::Creepage<> value;
  value.longitudinal = xi;
  value.lateral = eta;
  value.spin = phi;
  return value;
}

/// The rows of ../shared/peer-tangential/hertz.tsv as column name → text.
inline std::vector<std::map<std::string, std::string>> peer_rows() {
  std::vector<std::map<std::string, std::string>> rows;
  const std::string path = fastnorm::test::peer_tangential_file();
  if (path.empty()) return rows;
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> columns;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields;
    std::stringstream stream(line);
    for (std::string field; std::getline(stream, field, '\t');) fields.push_back(field);
    if (columns.empty()) {
      columns = fields;
      continue;
    }
    std::map<std::string, std::string> row;
    for (std::size_t c = 0; c < columns.size() && c < fields.size(); ++c) row[columns[c]] = fields[c];
    rows.push_back(row);
  }
  return rows;
}

inline double number(const std::map<std::string, std::string>& row, const std::string& column) {
  return std::stod(row.at(column));
}

/// CONTACT's normal problem of a peer row (module 3: h = A1 x² + B1 y², its grid, material
/// and Fn; CONTACT's mm and N/mm² converted to SI), solved by NORM.
inline HertzProblem peer_row_problem(const std::map<std::string, std::string>& row) {
  const double mm = 1e-3;
  return hertz_problem(number(row, "a1_per_mm") / mm, number(row, "b1_per_mm") / mm, std::stol(row.at("mx")),
                       std::stol(row.at("my")), number(row, "dx_mm") * mm, number(row, "dy_mm") * mm,
                       number(row, "g_MPa") * 1e6, number(row, "nu"), number(row, "fn_N"));
}

/// The creepages of a peer row in SI (φ from rad/mm to rad/m).
inline fastnorm::Creepage<> peer_row_creepage(const std::map<std::string, std::string>& row) {
  return creepage(number(row, "cksi"), number(row, "ceta"), number(row, "cphi_per_mm") / 1e-3);
}

/// The two symmetries every steady-rolling solver keeps, as sections of the calling test:
/// the left/right mirror, (ξ, −η, −φ) gives (Fx, −Fy, −Mz) and the same areas, and the
/// reversed rolling direction, (−ξ, η, −φ) towards −x gives (−Fx, Fy, −Mz). `solve(creepage,
/// direction)` is the solver; `base` its answer at (4e-4, −3e-4, 0.4 rad/m) towards +x;
/// forces within `margin`, moments within `margin`·c.
template <typename Solve>
void check_mirror_and_reversal(const Solve& solve, const fastnorm::TangentialSolution<>& base, double margin, double c) {
  SECTION("left/right mirror: (xi, -eta, -phi) gives (Fx, -Fy, -Mz)") {
    const auto mirrored = solve(creepage(4e-4, 3e-4, -0.4), fastnorm::RollingDirection::positive_x);
    CHECK(mirrored.force_x == Approx(base.force_x).margin(margin));
    CHECK(mirrored.force_y == Approx(-base.force_y).margin(margin));
    CHECK(mirrored.spin_moment == Approx(-base.spin_moment).margin(margin * c));
    CHECK(mirrored.adhesion_elements == base.adhesion_elements);
  }
  SECTION("reversed rolling direction: (-xi, eta, -phi) rolling towards -x gives (-Fx, Fy, -Mz)") {
    const auto reversed = solve(creepage(-4e-4, -3e-4, -0.4), fastnorm::RollingDirection::negative_x);
    CHECK(reversed.force_x == Approx(-base.force_x).margin(margin));
    CHECK(reversed.force_y == Approx(base.force_y).margin(margin));
    CHECK(reversed.spin_moment == Approx(-base.spin_moment).margin(margin * c));
    CHECK(reversed.adhesion_elements == base.adhesion_elements);
  }
}

/// CONTACT's traction bound of a simplified-theory row: on the Hertz ellipse of the row's
/// semi-axes, parabolic p = 2Fn/(πab)(1 − x²/a² − y²/b²) or elliptic (Hertz's).
inline fastnorm::Solution<> analytic_pressure(const fastnorm::Grid<>& grid, double a, double b, double fn, bool parabolic) {
  fastnorm::Solution<> normal;
  normal.status = fastnorm::Status::converged;
  normal.pressure = Eigen::VectorXd::Zero(grid.size());
  normal.in_contact = fastnorm::Solution<>::Mask::Constant(grid.size(), false);
  for (Eigen::Index k = 0; k < grid.size(); ++k) {
    const double x = grid.x(grid.i_of(k)), y = grid.y(grid.j_of(k));
    const double inside = 1 - x * x / (a * a) - y * y / (b * b);
    if (inside <= 0) continue;
    normal.in_contact(k) = true;
    normal.pressure(k) = parabolic ? 2 * fn / (fastnorm::pi<double> * a * b) * inside
                                   : 3 * fn / (2 * fastnorm::pi<double> * a * b) * std::sqrt(inside);
  }
  normal.normal_force = normal.pressure.sum() * grid.element_area();
  return normal;
}

/// A steel Hertzian contact of relative radii R_x, R_y under 80 kN on an n × n grid that
/// covers ±1.1 times the semi-axes: its NORM solution, or Hertz's pressure, and Hertz's
/// ellipse.
struct LinearCase {
  HertzProblem problem;
  fastnorm::Ellipse<> ellipse;
};

inline LinearCase linear_case(double radius_x, double radius_y, Eigen::Index elements, bool solve_normal = true) {
  const double shear_modulus = 8.2e10, nu = 0.28, fn = 80e3;
  const fastnorm::Material<> material(2 * shear_modulus * (1 + nu), nu);
  const auto hertz = fastnorm::hertz_from_force(radius_x, radius_y, material.combined_modulus(), fn);
  const double a = hertz.semi_axis_x, b = hertz.semi_axis_y;
  const double dx = 2.2 * a / static_cast<double>(elements), dy = 2.2 * b / static_cast<double>(elements);
  if (solve_normal) {
    return {hertz_problem(1 / (2 * radius_x), 1 / (2 * radius_y), elements, elements, dx, dy, shear_modulus, nu, fn),
            {a, b}};
  }
  const double first_x = -static_cast<double>(elements - 1) * dx / 2, first_y = -static_cast<double>(elements - 1) * dy / 2;
  const fastnorm::Grid<> grid(elements, elements, dx, dy, first_x, first_y);
  return {{grid, material, analytic_pressure(grid, a, b, fn, false)}, {a, b}};
}

/// The linear theory's forces (T9) for ξ, η and φ alone, each 1e-6 (φ c for the spin).
struct LinearCheck {
  const char* name;
  fastnorm::Creepage<> creepage;
  double expected;    ///< N
  bool longitudinal;  ///< Fx, else Fy
};

inline std::vector<LinearCheck> linear_checks(const LinearCase& hertz_case) {
  const auto& material = hertz_case.problem.material;
  const double a = hertz_case.ellipse.a, b = hertz_case.ellipse.b, c = std::sqrt(a * b), creep = 1e-6;
  const double scale = material.combined_shear_modulus() * c * c * creep;
  const auto kalker = fastnorm::kalker_coefficients(a / b, material.combined_poisson_ratio());
  return {{"xi", creepage(creep, 0, 0), -scale * kalker.c11, true},
          {"eta", creepage(0, creep, 0), -scale * kalker.c22, false},
          {"phi", creepage(0, 0, creep / c), -scale * kalker.c23, false}};
}

/// A cylinder R = 0.5 m pressed on a flat over 40 mm, about 40 contact half-widths, so that
/// its middle strip is in plane strain (48 × 41 elements, μ = 0.3). There, with identical
/// bodies, Carter's solution is independent of the elastic constants:
/// Fx/(μFn) = −[1 − (1 − ξR/(μa))²] per unit length, a the strip's own half-width,
/// 4 R P'/(π E*) = a² for its load P' per metre (the ends of a flat-ended cylinder carry more,
/// so a is a little less than the mean's).
struct LongCylinder {
  fastnorm::Grid<> grid;
  fastnorm::Material<> material;
  fastnorm::Solution<> normal;
  double radius = 0.5, nominal_half_width = 1e-3, friction = 0.3;
  double strip_load = 0, half_width = 0;  ///< the middle strip's (N/m, m)

  double strip_sum(const Eigen::VectorXd& values) const {
    return values.segment(grid.my() / 2 * grid.mx(), grid.mx()).sum() * grid.dx();
  }
  /// Carter's Fx/(μFn) at ξ, and the middle strip's −Σp_x/(μ P').
  double carter(double xi) const { return 1 - std::pow(1 - xi * radius / (friction * half_width), 2); }
  double middle_strip_force(const fastnorm::TangentialSolution<>& answer) const {
    return -strip_sum(answer.traction_x) / (friction * strip_load);
  }
};

inline LongCylinder long_cylinder() {
  const auto material = fastnorm::Material<>::steel();
  const double radius = 0.5, nominal_half_width = 1e-3, length = 40e-3;
  const Eigen::Index mx = 48, my = 41;
  const double dx = 3.2 * nominal_half_width / static_cast<double>(mx), dy = length / static_cast<double>(my - 2);
  const fastnorm::Grid<> grid(mx, my, dx, dy, -static_cast<double>(mx - 1) * dx / 2, -static_cast<double>(my - 1) * dy / 2);
  Eigen::VectorXd h(grid.size());
  for (Eigen::Index k = 0; k < grid.size(); ++k) {
    const double x = grid.x(grid.i_of(k)), y = grid.y(grid.j_of(k));
    h(k) = std::abs(y) > length / 2 ? 1.0 : x * x / (2 * radius);
  }
  const double line_load = fastnorm::pi<double> * material.combined_modulus() * nominal_half_width * nominal_half_width /
                           (4 * radius);
  auto normal = fastnorm::NormSolver<>(grid, material).solve(h, fastnorm::Loading<>::force(line_load * length));
  REQUIRE(normal.ok());
  LongCylinder cylinder{grid, material, std::move(normal)};
  cylinder.strip_load = cylinder.strip_sum(cylinder.normal.pressure);
  cylinder.half_width = std::sqrt(4 * radius * cylinder.strip_load / (fastnorm::pi<double> * material.combined_modulus()));
  return cylinder;
}

}  // namespace fastnorm::test
