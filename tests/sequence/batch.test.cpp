// solve_batch: the same answers as one solve after another, in parallel or not.
#include <catch2/catch.hpp>
#include <fastnorm/any_solver.hpp>
#include <fastnorm/batch.hpp>
#include <fastnorm/hertz.hpp>

#include <cmath>
#include <vector>
#include "support/surfaces.hpp"

using Catch::Matchers::Contains;

namespace {

using fastnorm::test::steel;

/// Hertz indenters of different depths and tilts on one grid: a small lookup table.
std::vector<Eigen::VectorXd> table_of_indenters(const fastnorm::Grid<>& grid, int count) {
  std::vector<Eigen::VectorXd> problems;
  for (int n = 0; n < count; ++n) {
    Eigen::VectorXd h = fastnorm::hertz_undeformed_distance(grid, 0.3, 0.2);
    for (Eigen::Index k = 0; k < grid.size(); ++k) h(k) += 2e-4 * n * grid.y_of(k) - 2e-6 * (n % 3);
    problems.push_back(h);
  }
  return problems;
}

}  // namespace

TEST_CASE("A batch gives the answers of solving one problem after another", "[sequence][batch]") {
  const auto hertz = fastnorm::hertz_from_force(0.3, 0.2, steel.combined_modulus(), 5e4);
  const auto grid = fastnorm::hertz_grid(hertz, 20, 1.4);
  const auto problems = table_of_indenters(grid, 9);
  INFO("solve_batch runs " << (fastnorm::batch_is_parallel() ? "with OpenMP" : "serially"));
  for (const char* name : {"norm", "elliptic", "cg"}) {
    const fastnorm::AnySolver<> solver(name, grid, steel);
    const auto by_force = fastnorm::solve_batch(solver, problems, {fastnorm::Loading<>::force(5e4)});
    std::vector<fastnorm::Loading<>> approach(problems.size(), fastnorm::Loading<>::approach());
    const auto by_approach = fastnorm::solve_batch(solver, problems, approach);
    REQUIRE(by_force.size() == problems.size());
    for (std::size_t n = 0; n < problems.size(); ++n) {
      INFO(name << " problem " << n);
      const auto force_one = solver.solve(problems[n], fastnorm::Loading<>::force(5e4));
      const auto approach_one = solver.solve(problems[n], fastnorm::Loading<>::approach());
      CHECK(by_force[n].status == force_one.status);
      CHECK(by_force[n].pressure == force_one.pressure);
      CHECK(by_force[n].approach == force_one.approach);
      CHECK(by_approach[n].status == approach_one.status);
      CHECK(by_approach[n].pressure == approach_one.pressure);
    }
  }
}

TEST_CASE("A batch rejects mismatched loadings and reports a bad problem", "[sequence][batch]") {
  const fastnorm::Grid<> grid(12, 12, 1e-4, 1e-4, -6e-4, -6e-4);
  auto problems = table_of_indenters(grid, 5);
  const fastnorm::AnySolver<> solver("elliptic", grid, steel);
  std::vector<fastnorm::Loading<>> two(2, fastnorm::Loading<>::approach());
  CHECK_THROWS_WITH(fastnorm::solve_batch(solver, problems, two), Contains("loadings must have one entry per problem"));
  problems[3](7) = std::nan("");
  CHECK_THROWS_WITH(fastnorm::solve_batch(solver, problems, {fastnorm::Loading<>::approach()}),
                    Contains("undeformed_distance[7]"));
}
