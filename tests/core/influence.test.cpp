#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fastnorm/influence.hpp>
#include <vector>

#include "support/kernel_quadrature.hpp"
#include "support/surfaces.hpp"

namespace {

using fastnorm::test::Real;
using fastnorm::test::pi_long;

// C(di·dx, dj·dy) by quadrature: (1/(π E*)) ∫∫ dA / r over the rectangle of the source element.
Real quadrature_coefficient(int di, int dj, Real dx, Real dy, Real combined_modulus, bool near) {
  const Real integral =
      fastnorm::test::element_integral(fastnorm::test::PointKernel::inverse_distance, di, dj, dx, dy, near);
  return integral / (pi_long * combined_modulus);
}

}  // namespace

TEST_CASE("Influence coefficients agree with numerical quadrature of 1/r", "[influence]") {
  const double combined_modulus = 1.153846153846e11;
  struct Shape {
    double dx, dy;
  };
  const Shape shape = GENERATE(Shape{1e-3, 1e-3}, Shape{1e-3, 3e-3}, Shape{2e-3, 0.5e-3});
  const fastnorm::Grid<> grid(60, 60, shape.dx, shape.dy);
  const fastnorm::InfluenceTable<> table(grid, fastnorm::Material<>(2.1e11, 0.3));
  REQUIRE(table.combined_modulus() == Approx(combined_modulus).epsilon(1e-12));

  SECTION("near offsets, the self term included") {
    for (auto [di, dj] : std::vector<std::pair<int, int>>{{0, 0}, {1, 0}, {0, 1}, {1, 1}, {2, 1}, {1, 3}}) {
      const Real expected = quadrature_coefficient(di, dj, Real(shape.dx), Real(shape.dy), Real(table.combined_modulus()), true);
      INFO("dx=" << shape.dx << " dy=" << shape.dy << " offset (" << di << "," << dj << ")");
      CHECK(std::abs(table.at_offset(di, dj) / static_cast<double>(expected) - 1) <= 1e-9);
    }
  }
  SECTION("far offsets") {
    for (auto [di, dj] : std::vector<std::pair<int, int>>{{4, 3}, {10, 0}, {0, 17}, {25, 9}, {59, 59}}) {
      const Real expected = quadrature_coefficient(di, dj, Real(shape.dx), Real(shape.dy), Real(table.combined_modulus()), false);
      INFO("dx=" << shape.dx << " dy=" << shape.dy << " offset (" << di << "," << dj << ")");
      CHECK(std::abs(table.at_offset(di, dj) / static_cast<double>(expected) - 1) <= 1e-9);
    }
  }
}

TEST_CASE("Self term has its closed form", "[influence]") {
  const double e_star = 1e11, a = 0.5e-3, b = 1.5e-3, pi_d = 3.14159265358979323846;
  const double rectangle = 4 * (a * std::asinh(b / a) + b * std::asinh(a / b)) / (pi_d * e_star);
  CHECK(fastnorm::love_coefficient(0.0, 0.0, a, b, e_star) == Approx(rectangle).epsilon(1e-14));
  const double square = 8 * a * std::log(1 + std::sqrt(2.0)) / (pi_d * e_star);
  CHECK(fastnorm::love_coefficient(0.0, 0.0, a, a, e_star) == Approx(square).epsilon(1e-14));
}

TEST_CASE("Kernel is even in x and y and the table symmetric", "[influence]") {
  const double a = 0.3e-3, b = 0.45e-3, e_star = 1.15e11;
  for (double x : {0.0, 0.2e-3, 1.7e-3, 9e-3}) {
    for (double y : {0.0, 0.4e-3, 3.3e-3}) {
      const double c = fastnorm::love_coefficient(x, y, a, b, e_star);
      CHECK(fastnorm::love_coefficient(-x, y, a, b, e_star) == Approx(c).epsilon(1e-15));
      CHECK(fastnorm::love_coefficient(x, -y, a, b, e_star) == Approx(c).epsilon(1e-15));
      CHECK(fastnorm::love_coefficient(-x, -y, a, b, e_star) == Approx(c).epsilon(1e-15));
    }
  }
  const fastnorm::Grid<> grid(7, 5, 2 * a, 2 * b);
  const fastnorm::InfluenceTable<> table(grid, fastnorm::Material<>(2.1e11, 0.3));
  for (Eigen::Index k = 0; k < grid.size(); ++k) {
    for (Eigen::Index l = 0; l < grid.size(); ++l) CHECK(table(k, l) == table(l, k));
  }
}

TEST_CASE("Along every line parallel to x the table falls off from di = 0", "[influence]") {
  // The join check's bound (detail/active_set_loop.hpp) takes max_i C(i, dj) = C(0, dj):
  // the displacement of a uniformly loaded rectangle decreases with |x| on every line y =
  // const, on square, long and wide elements, near and far.
  struct Shape {
    double dx, dy;
  };
  for (const Shape shape : {Shape{1e-3, 1e-3}, Shape{0.2e-3, 1.5e-3}, Shape{2e-3, 0.1e-3}}) {
    const fastnorm::Grid<> grid(90, 70, shape.dx, shape.dy);
    const fastnorm::InfluenceTable<> table(grid, fastnorm::Material<>(2.1e11, 0.3));
    for (Eigen::Index dj = 0; dj < grid.my(); ++dj) {
      INFO("dx " << shape.dx << ", dy " << shape.dy << ", dj " << dj);
      bool falls = true, even = true;
      for (Eigen::Index di = 1; di < grid.mx(); ++di) {
        falls = falls && table.at_offset(di, dj) <= table.at_offset(di - 1, dj);
        even = even && table.at_offset(-di, dj) == table.at_offset(di, dj);
      }
      CHECK(falls);
      CHECK(even);
    }
  }
}

TEST_CASE("Far field tends to dx·dy / (π E* r)", "[influence]") {
  const double dx = 1e-3, dy = 2e-3, e_star = 1e11, pi_d = 3.14159265358979323846;
  double previous_error = 1;
  for (double distance : {10e-3, 30e-3, 100e-3, 300e-3}) {
    const double x = distance * 0.6, y = distance * 0.8;
    const double point_load = dx * dy / (pi_d * e_star * distance);
    const double error = std::abs(fastnorm::love_coefficient(x, y, dx / 2, dy / 2, e_star) / point_load - 1);
    INFO("r = " << distance << " relative difference " << error);
    // The first correction is of order (size / r)²: a factor ≈ 9–11 per step of 3 in r.
    CHECK(error < 0.1 * (dy / distance) * (dy / distance) * 10);
    CHECK(error < previous_error / 8);
    previous_error = error;
  }
}

TEST_CASE("Dense blocks and displacements read the same table", "[influence]") {
  const fastnorm::Grid<> grid(9, 6, 0.4e-3, 0.6e-3);
  const fastnorm::InfluenceTable<> table(grid, fastnorm::Material<>(2.1e11, 0.3));
  const std::vector<Eigen::Index> set{0, 4, 13, 22, 40, 53};
  const Eigen::MatrixXd block = table.dense_block(set);
  Eigen::VectorXd pressure(static_cast<Eigen::Index>(set.size()));
  for (std::size_t r = 0; r < set.size(); ++r) {
    pressure(static_cast<Eigen::Index>(r)) = 1e8 * (1.0 + static_cast<double>(r));
    for (std::size_t c = 0; c < set.size(); ++c) {
      CHECK(block(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) == table(set[r], set[c]));
    }
  }
  const Eigen::VectorXd by_block = block * pressure;
  const Eigen::VectorXd by_sum = table.displacement(set, set, pressure);
  CHECK((by_block - by_sum).cwiseAbs().maxCoeff() <= 1e-14 * by_block.cwiseAbs().maxCoeff());
  // Targets in any order, in place: the same displacements, reordered.
  const std::vector<Eigen::Index> shuffled{53, 4, 40, 0, 22, 13};
  Eigen::VectorXd in_place(static_cast<Eigen::Index>(shuffled.size()));
  table.displacement(shuffled, set, pressure, in_place);
  for (std::size_t t = 0; t < shuffled.size(); ++t) {
    const auto r = static_cast<Eigen::Index>(std::find(set.begin(), set.end(), shuffled[t]) - set.begin());
    CHECK(in_place(static_cast<Eigen::Index>(t)) == Approx(by_block(r)).epsilon(1e-14));
  }
  Eigen::VectorXd wrong_size(2);
  CHECK_THROWS_WITH(table.displacement(shuffled, set, pressure, wrong_size), Catch::Matchers::Contains("result"));

  Eigen::VectorXd full = Eigen::VectorXd::Zero(grid.size());
  for (std::size_t r = 0; r < set.size(); ++r) full(set[r]) = pressure(static_cast<Eigen::Index>(r));
  const Eigen::VectorXd everywhere = table.displacement(full);
  for (std::size_t r = 0; r < set.size(); ++r) {
    CHECK(everywhere(set[r]) == Approx(by_block(static_cast<Eigen::Index>(r))).epsilon(1e-14));
  }
  CHECK_THROWS_WITH(table.displacement(Eigen::VectorXd::Zero(3)), Catch::Matchers::Contains("pressure"));
}

TEST_CASE("A table read from a larger one is the table built anew, to the last bit", "[influence]") {
  using fastnorm::test::steel;
  const fastnorm::InfluenceTable<> larger(fastnorm::Grid<>(16, 12, 0.4e-3, 0.6e-3), steel);
  // Another origin, fewer elements either way: every coefficient, block and displacement is
  // the fresh table's, and add_displacement reads the same columns.
  const fastnorm::Grid<> grid(9, 6, 0.4e-3, 0.6e-3, -1e-3, 2e-3);
  const fastnorm::InfluenceTable<> read(larger, grid);
  const fastnorm::InfluenceTable<> fresh(grid, steel);
  CHECK(read.grid().mx() == 9);
  CHECK(read.combined_modulus() == fresh.combined_modulus());
  CHECK(read.table() == fresh.table());
  for (Eigen::Index di = -8; di <= 8; ++di) {
    for (Eigen::Index dj = -5; dj <= 5; ++dj) CHECK(read.at_offset(di, dj) == fresh.at_offset(di, dj));
  }
  Eigen::VectorXd by_read = Eigen::VectorXd::Zero(grid.size()), by_fresh = by_read;
  read.add_displacement(23, 1e8, by_read);
  fresh.add_displacement(23, 1e8, by_fresh);
  CHECK(by_read == by_fresh);
  CHECK(larger.covers(grid));
  CHECK_FALSE(larger.covers(fastnorm::Grid<>(17, 12, 0.4e-3, 0.6e-3)));
  CHECK_FALSE(larger.covers(fastnorm::Grid<>(16, 13, 0.4e-3, 0.6e-3)));
  CHECK_FALSE(larger.covers(fastnorm::Grid<>(9, 6, 0.41e-3, 0.6e-3)));
  CHECK_THROWS_WITH(fastnorm::InfluenceTable<>(larger, fastnorm::Grid<>(17, 12, 0.4e-3, 0.6e-3)),
                    Catch::Matchers::Contains("cover grid"));
}

TEMPLATE_TEST_CASE("Kernel in float, double and long double", "[influence]", float, double, long double) {
  const fastnorm::Grid<TestType> grid(30, 20, TestType(0.3e-3), TestType(0.45e-3));
  const fastnorm::InfluenceTable<TestType> table(grid, fastnorm::Material<TestType>(TestType(2.1e11), TestType(0.3)));
  const fastnorm::InfluenceTable<double> reference(
      fastnorm::Grid<>(30, 20, static_cast<double>(TestType(0.3e-3)), static_cast<double>(TestType(0.45e-3))),
      fastnorm::Material<>(static_cast<double>(TestType(2.1e11)), static_cast<double>(TestType(0.3))));
  // Evaluated in at least double precision, rounded once to TestType.
  const double tolerance = std::is_same_v<TestType, float> ? 1e-6 : 1e-13;
  for (auto [di, dj] : std::vector<std::pair<int, int>>{{0, 0}, {1, 2}, {29, 19}}) {
    CHECK(static_cast<double>(table.at_offset(di, dj)) ==
          Approx(reference.at_offset(di, dj)).epsilon(tolerance));
  }
}
