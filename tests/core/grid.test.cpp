#include <catch2/catch.hpp>
#include <fastnorm/grid.hpp>

#include <limits>

using Catch::Matchers::Contains;

TEST_CASE("Grid numbers elements with x fastest and places their centres", "[grid]") {
  const fastnorm::Grid<> grid(4, 3, 0.5, 0.25, -1.0, 2.0);
  CHECK(grid.size() == 12);
  CHECK(grid.index(1, 2) == 9);
  CHECK(grid.i_of(9) == 1);
  CHECK(grid.j_of(9) == 2);
  CHECK(grid.x_of(9) == Approx(-0.5));
  CHECK(grid.y_of(9) == Approx(2.5));
  CHECK(grid.element_area() == Approx(0.125));
}

TEST_CASE("Grid rejects bad sizes naming the argument", "[grid]") {
  using G = fastnorm::Grid<>;
  CHECK_THROWS_WITH(G(0, 3, 1.0, 1.0), Contains("mx"));
  CHECK_THROWS_WITH(G(3, -1, 1.0, 1.0), Contains("my"));
  CHECK_THROWS_WITH(G(3, 3, 0.0, 1.0), Contains("dx"));
  CHECK_THROWS_WITH(G(3, 3, 1.0, -2.0), Contains("dy"));
  CHECK_THROWS_WITH(G(3, 3, 1.0, std::nan("")), Contains("dy"));
  CHECK_THROWS_WITH(G(3, 3, 1.0, 1.0, std::numeric_limits<double>::infinity()), Contains("x0"));
  CHECK_THROWS_AS(G(3, 3, 1.0, 1.0, 0.0, std::numeric_limits<double>::quiet_NaN()), fastnorm::invalid_argument);
  // Sizes whose area or extent the arithmetic cannot carry (found by tests/fuzz/solvers:
  // dx = 3e209, dy = 7.5e199 made the force 0 * inf = NaN).
  CHECK_THROWS_WITH(G(1, 1, 3.3e209, 7.5e199), Contains("element area"));
  CHECK_THROWS_WITH(G(1, 1, 1e-200, 1e-200), Contains("element area"));
  CHECK_THROWS_WITH(G(4, 4, 1e308, 1.0, 1e308), Contains("mx*dx"));
  CHECK_NOTHROW(G(4, 4, 1e-150, 1e-150));
}
