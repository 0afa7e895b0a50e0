#include <catch2/catch.hpp>
#include <fastnorm/strips.hpp>

TEST_CASE("Strips split into segments at holes and at strip ends", "[strips]") {
  const fastnorm::Grid<> grid(6, 3, 1e-3, 2e-3, -2.5e-3, 0.0);
  // Strip 0: i = 1..3; strip 1: i = 0, then 2..5 (a hole at 1); strip 2: i = 0..1.
  // Element 11 (i = 5, j = 1) and 12 (i = 0, j = 2) are consecutive numbers but not a run.
  const std::vector<Eigen::Index> set{1, 2, 3, 6, 8, 9, 10, 11, 12, 13};
  const auto segments = fastnorm::segment_strips(grid, set);
  REQUIRE(segments.size() == 4);
  CHECK(segments[0] == fastnorm::Segment{0, 1, 3, 0});
  CHECK(segments[1] == fastnorm::Segment{1, 0, 1, 3});
  CHECK(segments[2] == fastnorm::Segment{1, 2, 4, 4});
  CHECK(segments[3] == fastnorm::Segment{2, 0, 2, 8});
  CHECK(segments[2].set_position == 4);
  CHECK(segments[2].last() == 5);
  CHECK(segments[0].centre(grid) == Approx(-0.5e-3));
  CHECK(segments[0].half_length(grid) == Approx(1.5e-3));

  CHECK_THROWS_AS(fastnorm::segment_strips(grid, {3, 2}), fastnorm::invalid_argument);
  CHECK_THROWS_AS(fastnorm::segment_strips(grid, {18}), fastnorm::invalid_argument);
  CHECK(fastnorm::segment_strips(grid, {}).empty());
}

TEST_CASE("Local coordinates of a segment's element centres", "[strips]") {
  // Element centres at x_c + (m − (n−1)/2)·dx over L = n·dx/2.
  const Eigen::VectorXd xi3 = fastnorm::segment_coordinates<double>(3);
  CHECK(xi3(0) == Approx(-2.0 / 3));
  CHECK(xi3(1) == 0);
  CHECK(xi3(2) == Approx(2.0 / 3));
  const Eigen::VectorXd xi4 = fastnorm::segment_coordinates<double>(4);
  CHECK(xi4(0) == Approx(-0.75));
  CHECK(xi4(3) == Approx(0.75));
  CHECK(fastnorm::segment_coordinates<double>(1)(0) == 0);
}
