#pragma once
// Random smooth gaps for the property tests: a rotated quadratic (an ellipsoid's
// undeformed distance) with a waviness on top, on a square grid of random aspect ratio,
// reproducible from a seed.

#include <fastnorm/grid.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace fastnorm::test {

/// Which random gap: the seed of its generator and its m × m size.
struct GapChoice {
  std::uint32_t seed;
  Eigen::Index size;
};

struct RandomGap {
  fastnorm::Grid<> grid;
  Eigen::VectorXd unloaded;  ///< h0 (m): min h0 is 0 near the centre
  double approach;           ///< δ0 (m): h0 < δ0 on about a quarter of the grid
};

/// A gap on m × m elements: curvatures 1/R with R from 10 to 100 mm in the principal
/// directions, turned by a random angle, plus a waviness of up to 15 % of δ0 with 2 to 5
/// waves across the contact; centred within 10 % of the grid's middle; δ0 such that
/// h0 < δ0 on 15 to 35 % of the elements (about the contact area times two, as for Hertz),
/// so that the contact stays clear of the grid's edge.
inline RandomGap random_gap(std::uint32_t seed, Eigen::Index m) {
  std::mt19937 random(seed);
  auto uniform = [&](double low, double high) { return std::uniform_real_distribution<double>(low, high)(random); };
  const double dy = 1e-4, dx = dy * uniform(0.5, 2.0);
  const double half = 0.5 * static_cast<double>(m - 1);
  const fastnorm::Grid<> grid(m, m, dx, dy, -half * dx, -half * dy);
  const double curvature_1 = 1 / uniform(0.01, 0.1), curvature_2 = 1 / uniform(0.01, 0.1);
  const double angle = uniform(0, 3.14159265358979), c = std::cos(angle), s = std::sin(angle);
  const double centre_x = uniform(-0.1, 0.1) * half * dx, centre_y = uniform(-0.1, 0.1) * half * dy;
  const double waves = uniform(2, 5), phase_x = uniform(0, 6.28), phase_y = uniform(0, 6.28);
  const double contact_width_x = half * dx, contact_width_y = half * dy;  // of the overlap, roughly
  Eigen::VectorXd quadratic(grid.size()), waviness(grid.size());
  for (Eigen::Index j = 0; j < m; ++j) {
    for (Eigen::Index i = 0; i < m; ++i) {
      const double x = grid.x(i) - centre_x, y = grid.y(j) - centre_y;
      const double along = c * x + s * y, across = -s * x + c * y;
      const auto k = grid.index(i, j);
      quadratic(k) = 0.5 * (curvature_1 * along * along + curvature_2 * across * across);
      waviness(k) = std::sin(6.28318530717959 * waves * x / contact_width_x + phase_x) *
                    std::sin(6.28318530717959 * waves * y / contact_width_y + phase_y);
    }
  }
  // δ0 from the quadratic alone, then the waviness scaled to it.
  std::vector<double> sorted(quadratic.data(), quadratic.data() + quadratic.size());
  std::sort(sorted.begin(), sorted.end());
  const double fraction = uniform(0.15, 0.35);
  const double approach = sorted[static_cast<std::size_t>(fraction * static_cast<double>(sorted.size()))];
  Eigen::VectorXd unloaded = quadratic + uniform(0, 0.15) * approach * waviness;
  const double lowest = unloaded.minCoeff();
  unloaded.array() -= lowest;
  return {grid, unloaded, approach - lowest};
}

}  // namespace fastnorm::test
