#pragma once
// Hertzian rolling problems as CONTACT's module 3 poses them, and the rows of CONTACT's
// tangential results (../shared/peer-tangential/hertz.tsv): shared by the tests of the
// exact and the simplified tangential paths.
#include <catch2/catch.hpp>

#include <fastnorm/norm_solver.hpp>
#include <fastnorm/tangential_problem.hpp>
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

}  // namespace fastnorm::test
