#pragma once
// Test problems shared by the solver tests.

#include <algorithm>
#include <cmath>
#include <fastnorm/grid.hpp>
#include <fastnorm/hertz.hpp>
#include <fastnorm/material.hpp>
#include <fastnorm/solution.hpp>

namespace fastnorm::test {

/// The material of most tests: steel on steel, E 210 GPa, ν 0.3.
inline const fastnorm::Material<> steel(2.1e11, 0.3);

/// The force-controlled Hertz problem many solver tests solve: an ellipsoid of radii 0.3 m
/// and 0.2 m on `steel` under 50 kN, on a grid of `elements` across 1.4
/// times its contact.
struct HertzEllipsoid {
  fastnorm::Grid<> grid;
  Eigen::VectorXd h;
  fastnorm::Loading<> loading;
};

inline HertzEllipsoid hertz_ellipsoid(Eigen::Index elements) {
  const double force = 5e4;
  const auto contact =
      fastnorm::hertz_from_force(0.3, 0.2, steel.combined_modulus(), force);
  const auto grid = fastnorm::hertz_grid(contact, elements, 1.4);
  return {grid, fastnorm::hertz_undeformed_distance(grid, 0.3, 0.2), fastnorm::Loading<>::force(force)};
}

/// A non-Hertzian surface: two bumps of different radii side by side and a waviness, so
/// that the contact has two patches (and approach control interpenetrates both).
inline Eigen::VectorXd two_bumps(const fastnorm::Grid<>& grid, double approach) {
  Eigen::VectorXd h(grid.size());
  for (Eigen::Index k = 0; k < grid.size(); ++k) {
    const double x = grid.x_of(k), y = grid.y_of(k);
    const double left = (x * x) / (2 * 0.3) + (y + 2.2e-3) * (y + 2.2e-3) / (2 * 0.1);
    const double right = (x * x) / (2 * 0.5) + (y - 2.0e-3) * (y - 2.0e-3) / (2 * 0.15) + 4e-6;
    h(k) = std::min(left, right) + 1e-6 * std::sin(x / 7e-4) * std::cos(y / 9e-4) - approach;
  }
  return h;
}

/// The grid the two bumps are meant for.
inline const fastnorm::Grid<> two_bumps_grid(36, 44, 0.2e-3, 0.15e-3, -3.5e-3, -3.225e-3);

}  // namespace fastnorm::test
