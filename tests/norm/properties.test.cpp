// Properties of NORM and CG on random smooth gaps (support/random_gaps.hpp), 20² to 60²
// elements, both controls: the Signorini conditions from an independent product C p, a
// force that grows with the approach (and an approach that grows with the force), force
// control inverting approach control, and mirror symmetry of the answer.
#include <catch2/catch.hpp>
#include <fastnorm/cg_solver.hpp>
#include <fastnorm/norm_solver.hpp>

#include <cmath>

#include "support/random_gaps.hpp"
#include "support/signorini.hpp"
#include "support/surfaces.hpp"

namespace {

using fastnorm::test::GapChoice;

using fastnorm::test::steel;

/// h with its elements reflected: i → mx−1−i (in x) or j → my−1−j (in y).
Eigen::VectorXd mirrored(const fastnorm::Grid<>& grid, const Eigen::VectorXd& values, bool in_x) {
  Eigen::VectorXd result(values.size());
  for (Eigen::Index j = 0; j < grid.my(); ++j) {
    for (Eigen::Index i = 0; i < grid.mx(); ++i) {
      result(grid.index(in_x ? grid.mx() - 1 - i : i, in_x ? j : grid.my() - 1 - j)) = values(grid.index(i, j));
    }
  }
  return result;
}

/// NORM's force at the gap's approach δ0: forces up to it keep the contact inside the grid.
double force_at_approach(const fastnorm::NormSolver<>& norm, const fastnorm::test::RandomGap& gap) {
  const auto solution = norm.solve((gap.unloaded.array() - gap.approach).matrix(), fastnorm::Loading<>::approach());
  REQUIRE(solution.status == fastnorm::Status::converged);
  return solution.normal_force;
}

}  // namespace

TEST_CASE("NORM and CG satisfy the Signorini conditions on random gaps in both controls", "[norm][cg][properties]") {
  const auto problem = GENERATE(GapChoice{1, 20}, GapChoice{2, 20}, GapChoice{3, 30}, GapChoice{4, 30},
                                GapChoice{5, 40}, GapChoice{10, 40}, GapChoice{11, 50}, GapChoice{12, 50},
                                GapChoice{13, 60}, GapChoice{14, 60});
  const auto gap = fastnorm::test::random_gap(problem.seed, problem.size);
  const Eigen::VectorXd loaded = (gap.unloaded.array() - gap.approach).matrix();
  const fastnorm::NormSolver<> norm(gap.grid, steel);
  const fastnorm::CgSolver<> cg(gap.grid, steel);
  const auto& table = norm.influence();
  INFO("seed " << problem.seed << ", " << problem.size << "^2 elements");

  const auto exact = norm.solve(loaded, fastnorm::Loading<>::approach());
  REQUIRE(exact.status == fastnorm::Status::converged);
  CHECK_FALSE(exact.at_edge);
  CHECK(fastnorm::test::complementarity_error(table, loaded, exact) <= 1e-9);
  const auto iterative = cg.solve(loaded, fastnorm::Loading<>::approach());
  REQUIRE(iterative.status == fastnorm::Status::converged);
  CHECK(fastnorm::test::complementarity_error(table, loaded, iterative) <= cg.options().tolerance * (1 + 1e-6));

  // Force control with NORM's force on the unloaded gap finds the same approach.
  const auto force = fastnorm::Loading<>::force(exact.normal_force);
  const auto exact_force = norm.solve(gap.unloaded, force);
  const auto iterative_force = cg.solve(gap.unloaded, force);
  REQUIRE(exact_force.status == fastnorm::Status::converged);
  REQUIRE(iterative_force.status == fastnorm::Status::converged);
  CHECK(fastnorm::test::complementarity_error(table, gap.unloaded, exact_force) <= 1e-9);
  CHECK(fastnorm::test::complementarity_error(table, gap.unloaded, iterative_force) <=
        cg.options().tolerance * (1 + 1e-6));
  INFO("approach " << gap.approach << " m; NORM " << exact_force.approach << ", CG " << iterative_force.approach);
  CHECK(std::abs(exact_force.approach - gap.approach) <= 1e-9 * gap.approach);
  CHECK(std::abs(iterative_force.approach - gap.approach) <= 1e-6 * gap.approach);
  CHECK((exact_force.in_contact == exact.in_contact).all());
}

TEST_CASE("The force grows with the approach, and the approach with the force", "[norm][cg][properties]") {
  const auto problem = GENERATE(GapChoice{6, 20}, GapChoice{7, 40}, GapChoice{15, 60});
  const auto gap = fastnorm::test::random_gap(problem.seed, problem.size);
  const fastnorm::NormSolver<> norm(gap.grid, steel);
  const fastnorm::CgSolver<> cg(gap.grid, steel);
  INFO("seed " << problem.seed << ", " << problem.size << "^2 elements");
  const double largest_force = force_at_approach(norm, gap);
  double norm_force = 0, cg_force = 0, norm_approach = -1, cg_approach = -1;
  for (double scale : {0.1, 0.3, 0.5, 0.7, 0.9, 1.1}) {
    const Eigen::VectorXd loaded = (gap.unloaded.array() - scale * gap.approach).matrix();
    const auto exact = norm.solve(loaded, fastnorm::Loading<>::approach());
    const auto iterative = cg.solve(loaded, fastnorm::Loading<>::approach());
    REQUIRE(exact.status == fastnorm::Status::converged);
    REQUIRE(iterative.status == fastnorm::Status::converged);
    INFO("approach " << scale << " x " << gap.approach << " m: forces " << exact.normal_force << ", "
                     << iterative.normal_force << " N");
    CHECK(exact.normal_force > norm_force);
    CHECK(iterative.normal_force > cg_force);
    norm_force = exact.normal_force;
    cg_force = iterative.normal_force;

    // Force control with forces in the same ratios: the approach grows.
    const auto force = fastnorm::Loading<>::force(scale / 1.1 * largest_force);
    const auto exact_force = norm.solve(gap.unloaded, force);
    const auto iterative_force = cg.solve(gap.unloaded, force);
    REQUIRE(exact_force.status == fastnorm::Status::converged);
    REQUIRE(iterative_force.status == fastnorm::Status::converged);
    CHECK(exact_force.approach > norm_approach);
    CHECK(iterative_force.approach > cg_approach);
    norm_approach = exact_force.approach;
    cg_approach = iterative_force.approach;
  }
}

TEST_CASE("A mirrored gap gives the mirrored pressure", "[norm][cg][properties]") {
  const auto problem = GENERATE(GapChoice{8, 20}, GapChoice{9, 30}, GapChoice{16, 60});
  const bool in_x = GENERATE(true, false);
  const auto control = GENERATE(fastnorm::Control::approach, fastnorm::Control::force);
  const auto gap = fastnorm::test::random_gap(problem.seed, problem.size);
  const Eigen::VectorXd h = control == fastnorm::Control::approach
                                ? Eigen::VectorXd((gap.unloaded.array() - gap.approach).matrix())
                                : gap.unloaded;
  const fastnorm::NormSolver<> norm(gap.grid, steel);
  const auto loading = control == fastnorm::Control::approach ? fastnorm::Loading<>::approach()
                                                              : fastnorm::Loading<>::force(force_at_approach(norm, gap));
  const fastnorm::CgSolver<> cg(gap.grid, steel);
  INFO("seed " << problem.seed << ", mirrored in " << (in_x ? "x" : "y"));
  const auto exact = norm.solve(h, loading), exact_mirrored = norm.solve(mirrored(gap.grid, h, in_x), loading);
  const auto iterative = cg.solve(h, loading), iterative_mirrored = cg.solve(mirrored(gap.grid, h, in_x), loading);
  REQUIRE(exact.status == fastnorm::Status::converged);
  REQUIRE(exact_mirrored.status == fastnorm::Status::converged);
  REQUIRE(iterative.status == fastnorm::Status::converged);
  REQUIRE(iterative_mirrored.status == fastnorm::Status::converged);
  const double peak = exact.pressure.maxCoeff();
  const double norm_difference =
      (mirrored(gap.grid, exact.pressure, in_x) - exact_mirrored.pressure).cwiseAbs().maxCoeff() / peak;
  const double cg_difference =
      (mirrored(gap.grid, iterative.pressure, in_x) - iterative_mirrored.pressure).cwiseAbs().maxCoeff() / peak;
  INFO("largest pressure difference / peak: NORM " << norm_difference << ", CG " << cg_difference);
  CHECK(norm_difference <= 1e-10);
  CHECK(cg_difference <= 1e-6);  // CG's answers each within 1e-6 of NORM's (cg_solver.test.cpp)
  CHECK(std::abs(exact_mirrored.approach - exact.approach) <= 1e-12 * std::abs(exact.approach) + 1e-20);
}
