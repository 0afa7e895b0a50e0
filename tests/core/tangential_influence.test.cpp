// Tangential influence coefficients (tangential_influence.hpp, docs/tangential.md §4):
// against numerical quadrature of Cerruti's point-load solution, its far field, the normal
// table, and their symmetries.
#include <catch2/catch.hpp>

#include <cmath>
#include <fastnorm/influence.hpp>
#include <fastnorm/tangential_influence.hpp>
#include <utility>
#include <vector>

#include "support/kernel_quadrature.hpp"

namespace {

using fastnorm::test::PointKernel;
using fastnorm::test::Real;

// The coefficients by quadrature: xx = ∫∫ [(1 − ν)/r + ν x²/r³] / (π G), and so on.
fastnorm::TangentialCoefficients<Real> quadrature_coefficients(int di, int dj, Real dx, Real dy, Real shear_modulus,
                                                               Real poisson_ratio, bool near) {
  const auto integral = [&](PointKernel kernel) {
    return fastnorm::test::element_integral(kernel, di, dj, dx, dy, near);
  };
  const Real scale = fastnorm::test::pi_long * shear_modulus, inverse = integral(PointKernel::inverse_distance);
  return {((1 - poisson_ratio) * inverse + poisson_ratio * integral(PointKernel::xx)) / scale,
          poisson_ratio * integral(PointKernel::xy) / scale,
          ((1 - poisson_ratio) * inverse + poisson_ratio * integral(PointKernel::yy)) / scale};
}

}  // namespace

TEST_CASE("Tangential coefficients agree with numerical quadrature of Cerruti's solution", "[influence][tangential]") {
  struct Shape {
    double dx, dy;
  };
  const Shape shape = GENERATE(Shape{1e-3, 1e-3}, Shape{1e-3, 3e-3}, Shape{2e-3, 0.5e-3});
  const fastnorm::Grid<> grid(60, 60, shape.dx, shape.dy);
  const auto material = fastnorm::Material<>::steel();
  const fastnorm::TangentialInfluenceTable<> table(grid, material);
  REQUIRE(table.shear_modulus() == Approx(2.1e11 / 2.6).epsilon(1e-14));
  REQUIRE(table.poisson_ratio() == Approx(0.3).epsilon(1e-14));
  const auto check = [&](int di, int dj, bool near) {
    const auto expected = quadrature_coefficients(di, dj, Real(shape.dx), Real(shape.dy), Real(table.shear_modulus()),
                                                  Real(table.poisson_ratio()), near);
    const auto actual = table.at_offset(di, dj);
    INFO("dx=" << shape.dx << " dy=" << shape.dy << " offset (" << di << "," << dj << "): xx " << actual.xx << " vs "
               << static_cast<double>(expected.xx) << ", xy " << actual.xy << " vs " << static_cast<double>(expected.xy)
               << ", yy " << actual.yy << " vs " << static_cast<double>(expected.yy));
    CHECK(std::abs(actual.xx / static_cast<double>(expected.xx) - 1) <= 1e-9);
    CHECK(std::abs(actual.yy / static_cast<double>(expected.yy) - 1) <= 1e-9);
    // xy vanishes on the axes: measured against the size of the diagonal terms.
    CHECK(std::abs(actual.xy - static_cast<double>(expected.xy)) <= 1e-9 * static_cast<double>(expected.xx));
  };
  SECTION("near offsets, the self term included") {
    for (auto [di, dj] : std::vector<std::pair<int, int>>{{0, 0}, {1, 0}, {0, 1}, {1, 1}, {-1, 1}, {2, -1}, {1, 3}}) {
      check(di, dj, true);
    }
  }
  SECTION("far offsets") {
    for (auto [di, dj] : std::vector<std::pair<int, int>>{{4, 3}, {-4, 3}, {10, 0}, {0, 17}, {25, -9}, {59, 59}}) {
      check(di, dj, false);
    }
  }
}

TEST_CASE("Tangential coefficients: symmetries and the self term", "[influence][tangential]") {
  const double a = 0.3e-3, b = 0.45e-3, g = 8e10, nu = 0.28;
  for (double x : {0.0, 0.2e-3, 1.7e-3, 9e-3}) {
    for (double y : {0.0, 0.4e-3, 3.3e-3}) {
      const auto c = fastnorm::cerruti_coefficients(x, y, a, b, g, nu);
      const auto mirrored_x = fastnorm::cerruti_coefficients(-x, y, a, b, g, nu);
      const auto mirrored_y = fastnorm::cerruti_coefficients(x, -y, a, b, g, nu);
      // xx and yy even in x and y, xy odd in each.
      CHECK(mirrored_x.xx == Approx(c.xx).epsilon(1e-15));
      CHECK(mirrored_y.yy == Approx(c.yy).epsilon(1e-15));
      CHECK(mirrored_x.xy == Approx(-c.xy).margin(1e-15 * c.xx));
      CHECK(mirrored_y.xy == Approx(-c.xy).margin(1e-15 * c.xx));
      // Exchanging the axes exchanges xx and yy.
      const auto transposed = fastnorm::cerruti_coefficients(y, x, b, a, g, nu);
      CHECK(transposed.xx == Approx(c.yy).epsilon(1e-14));
      CHECK(transposed.yy == Approx(c.xx).epsilon(1e-14));
      CHECK(transposed.xy == Approx(c.xy).margin(1e-14 * c.xx));
    }
  }
  // On a square the self term has no preferred direction: xx = yy = (1 − ν/2)·I/(π G),
  // I = 8a·ln(1 + √2), since ∫∫ x²/r³ = ∫∫ y²/r³ = I/2 there.
  const double pi_d = 3.14159265358979323846, square = 8 * a * std::log(1 + std::sqrt(2.0));
  const auto self = fastnorm::cerruti_coefficients(0.0, 0.0, a, a, g, nu);
  CHECK(self.xx == Approx((1 - nu / 2) * square / (pi_d * g)).epsilon(1e-14));
  CHECK(self.yy == Approx(self.xx).epsilon(1e-15));
  CHECK(self.xy == 0);
  // An element longer in x resists a traction along x less than one along y (the
  // ν x²/r³ term weighs the long direction): xx > yy.
  const auto long_x = fastnorm::cerruti_coefficients(0.0, 0.0, 3 * a, a, g, nu);
  CHECK(long_x.xx > long_x.yy);
}

TEST_CASE("Tangential far field tends to Cerruti's point load", "[influence][tangential]") {
  const double dx = 1e-3, dy = 2e-3, g = 8e10, nu = 0.3, pi_d = 3.14159265358979323846;
  double previous_error = 1;
  for (double distance : {10e-3, 30e-3, 100e-3, 300e-3}) {
    const double x = distance * 0.6, y = distance * 0.8, r3 = distance * distance * distance;
    const double area = dx * dy / (pi_d * g);
    const double xx = area * ((1 - nu) / distance + nu * x * x / r3), xy = area * nu * x * y / r3,
                 yy = area * ((1 - nu) / distance + nu * y * y / r3);
    const auto c = fastnorm::cerruti_coefficients(x, y, dx / 2, dy / 2, g, nu);
    const double error = std::max({std::abs(c.xx / xx - 1), std::abs(c.xy / xy - 1), std::abs(c.yy / yy - 1)});
    INFO("r = " << distance << " largest relative difference " << error);
    // The first correction is of order (size / r)².
    CHECK(error < (dy / distance) * (dy / distance));
    CHECK(error < previous_error / 8);
    previous_error = error;
  }
}

TEST_CASE("Tangential tables agree with the normal table and their own closed form", "[influence][tangential]") {
  // xx + yy = [(2 − ν) I] / (π G) and the normal C = I / (π E*) = (1 − ν) I / (π G).
  const fastnorm::Grid<> grid(12, 9, 0.4e-3, 0.7e-3);
  const fastnorm::Material<> material(2.1e11, 0.3, 1.9e11, 0.27);
  const fastnorm::TangentialInfluenceTable<> tangential(grid, material);
  const fastnorm::InfluenceTable<> normal(grid, material);
  const double nu = tangential.poisson_ratio();
  for (Eigen::Index dj = -8; dj <= 8; ++dj) {
    for (Eigen::Index di = -11; di <= 11; ++di) {
      const auto c = tangential.at_offset(di, dj);
      INFO("offset (" << di << "," << dj << ")");
      CHECK((c.xx + c.yy) * (1 - nu) / (2 - nu) == Approx(normal.at_offset(di, dj)).epsilon(1e-13));
      const auto direct = fastnorm::cerruti_coefficients(static_cast<double>(di) * grid.dx(),
                                                         static_cast<double>(dj) * grid.dy(), grid.dx() / 2,
                                                         grid.dy() / 2, tangential.shear_modulus(), nu);
      // The table holds the values at |di|, |dj| with the signs of the symmetries; the
      // closed form at a negative offset rounds its cancelling terms differently (docs/kernel.md
      // §1, precision): a few digits at these distances.
      CHECK(c.xx == Approx(direct.xx).epsilon(1e-12));
      CHECK(c.xy == Approx(direct.xy).margin(1e-12 * direct.xx));
      CHECK(c.yy == Approx(direct.yy).epsilon(1e-12));
    }
  }
  // coefficients(di, dj): the table's own values within it, the closed form one element past.
  const auto inside = tangential.coefficients(3, -2), stored = tangential.at_offset(3, -2);
  CHECK((inside.xx == stored.xx && inside.xy == stored.xy && inside.yy == stored.yy));
  const Eigen::Index past = grid.mx();
  const auto beyond = tangential.coefficients(-past, 4);
  const auto closed = fastnorm::cerruti_coefficients(-static_cast<double>(past) * grid.dx(), 4 * grid.dy(), grid.dx() / 2,
                                                     grid.dy() / 2, tangential.shear_modulus(), nu);
  CHECK((beyond.xx == closed.xx && beyond.xy == closed.xy && beyond.yy == closed.yy));
}

TEST_CASE("Kalker's combined constants of two bodies", "[influence][tangential][material]") {
  const fastnorm::Material<> same(2.1e11, 0.3);
  CHECK(same.shear_modulus() == Approx(2.1e11 / 2.6).epsilon(1e-15));
  CHECK(same.combined_shear_modulus() == Approx(same.shear_modulus()).epsilon(1e-15));
  CHECK(same.combined_poisson_ratio() == Approx(0.3).epsilon(1e-15));
  CHECK(same.difference_parameter() == 0);
  // Steel on a softer, less compressible body: the constants by hand, and (1 − ν)/G = 1/E*.
  const fastnorm::Material<> pair(2.1e11, 0.3, 0.7e11, 0.33);
  const double g1 = 2.1e11 / 2.6, g2 = 0.7e11 / 2.66, g = 2 / (1 / g1 + 1 / g2);
  CHECK(pair.combined_shear_modulus() == Approx(g).epsilon(1e-14));
  CHECK(pair.combined_poisson_ratio() == Approx(g * (0.3 / g1 + 0.33 / g2) / 2).epsilon(1e-14));
  CHECK((1 - pair.combined_poisson_ratio()) / pair.combined_shear_modulus() ==
        Approx(1 / pair.combined_modulus()).epsilon(1e-14));
  CHECK(pair.difference_parameter() == Approx(g / 4 * (0.4 / g1 - 0.34 / g2)).epsilon(1e-14));
}
