// The normal stiffness dFn/dδ of every solver (docs/norm.md §4) against the derivative of
// the same discrete model by central differences, and against Hertz theory.
#include <catch2/catch.hpp>
#include <fastnorm/fastnorm.hpp>
#include <string>

#include "support/surfaces.hpp"

namespace {

using Vector = Eigen::VectorXd;

// dFn/dδ of `solver` by central differences of cold solves at approach ±step: on a fixed
// contact set Fn is linear in δ, so this is exact when the set does not change.
double difference_stiffness(const fastnorm::AnySolver<>& solver, const Vector& h, double step) {
  const auto plus = solver.solve(h.array() - step, fastnorm::Loading<>::approach());
  const auto minus = solver.solve(h.array() + step, fastnorm::Loading<>::approach());
  REQUIRE(plus.ok());
  REQUIRE(minus.ok());
  CHECK((plus.in_contact == minus.in_contact).all());
  return (plus.normal_force - minus.normal_force) / (2 * step);
}

}  // namespace

TEST_CASE("normal stiffness is the derivative of the discrete model", "[stiffness]") {
  using fastnorm::test::steel;
  const auto& grid = fastnorm::test::two_bumps_grid;
  const Vector h = fastnorm::test::two_bumps(grid, 0.02e-3);
  for (const char* name : {"norm", "cg", "elliptic", "polynomial:4", "polynomial-edge:4:1"}) {
    INFO(name);
    fastnorm::AnySolver<> solver(name, grid, steel);
    fastnorm::AnySolver<>::Workspace workspace;
    const auto solution = solver.solve(h, fastnorm::Loading<>::approach(), workspace);
    REQUIRE(solution.ok());
    const double stiffness = solver.normal_stiffness(solution, workspace);
    const double expected = difference_stiffness(solver, h, 1e-13);
    CHECK(stiffness > 0);
    // Round-off of Fn (~1e-16·Fn) over the step gives ~1e-8 relative here; CG's own tolerance 1e-9.
    CHECK(stiffness == Approx(expected).epsilon(name == std::string("cg") ? 1e-6 : 1e-7));
  }
}

TEST_CASE("normal stiffness of a Hertz contact is 3/2 Fn/δ", "[stiffness]") {
  using fastnorm::test::steel;
  const auto hertz = fastnorm::hertz_from_force(0.3, 0.3, steel.combined_modulus(), 5e4);
  const auto grid = fastnorm::hertz_grid(hertz, 40);
  const Vector h = fastnorm::hertz_undeformed_distance(grid, 0.3, 0.3).array() - hertz.approach;
  fastnorm::NormSolver<> norm(grid, steel);
  fastnorm::NormSolver<>::Workspace workspace;
  const auto solution = norm.solve(h, fastnorm::Loading<>::approach(), workspace);
  REQUIRE(solution.ok());
  // F = (4/3) E* √R δ^(3/2): dF/dδ = (3/2) F/δ. The discrete contact edge moves in steps, so
  // the discrete stiffness (the set held fixed) agrees to the discretisation error only.
  CHECK(norm.normal_stiffness(solution, workspace) == Approx(1.5 * 5e4 / hertz.approach).epsilon(0.05));
  // No contact: no stiffness.
  const auto apart = norm.solve(h.array() + 1.0, fastnorm::Loading<>::approach(), workspace);
  CHECK(norm.normal_stiffness(apart, workspace) == 0);
}
