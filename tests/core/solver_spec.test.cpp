// The solver spec: one grammar, canonical names, validation, and options that reach the
// solver through AnySolver.
#include <catch2/catch.hpp>
#include <fastnorm/hertz.hpp>
#include <fastnorm/solvers.hpp>

#include "support/surfaces.hpp"

using Catch::Matchers::Contains;
using Spec = fastnorm::SolverSpec<>;

TEST_CASE("Solver names parse to specs and back", "[core][spec]") {
  for (const char* name : {"norm", "cg", "elliptic", "polynomial:4", "polynomial:0", "polynomial:30", "elliptic-edge:1",
                           "elliptic-edge:3", "polynomial-edge:4:1", "polynomial-edge:6:2"}) {
    CHECK(Spec::parse(name).name() == name);
  }
  CHECK(Spec::parse("polynomial").name() == "polynomial:4");
  CHECK(Spec::parse("polynomial-edge:7").name() == "polynomial-edge:7:1");
  CHECK(Spec::parse("elliptic-edge").name() == "elliptic-edge:1");
  CHECK(Spec().name() == "norm");
  CHECK(Spec::parse("polynomial:6").grade == 6);
  CHECK(Spec::parse("polynomial-edge:5:2").edge_elements == 2);
  CHECK(Spec::parse("elliptic").is_reduced());
  CHECK_FALSE(Spec::parse("cg").is_reduced());
}

TEST_CASE("Bad solver names and fields are rejected by name", "[core][spec]") {
  CHECK_THROWS_WITH(Spec::parse(""), Contains("unknown solver ''"));
  CHECK_THROWS_WITH(Spec::parse("multigrid"), Contains(Spec::grammar));
  CHECK_THROWS_WITH(Spec::parse("polynomial:+4"), Contains("grade G must be a whole number"));
  CHECK_THROWS_WITH(Spec::parse("polynomial:"), Contains("grade G must be a whole number"));
  CHECK_THROWS_WITH(Spec::parse("polynomial:99999999999"), Contains("whole number"));
  CHECK_THROWS_WITH(Spec::parse("polynomial-edge:4:x"), Contains("edge elements K"));
  CHECK_THROWS_WITH(Spec::parse("norm:1"), Contains("too many"));
  CHECK_THROWS_WITH(Spec::parse("polynomial-edge:4:1:1"), Contains("too many"));
  Spec spec;
  spec.grade = -1;
  CHECK_THROWS_WITH(spec.validate(), Contains("grade"));
  spec = Spec();
  spec.cg.tolerance = 0;
  CHECK_THROWS_WITH(spec.validate(), Contains("tolerance"));
  spec = Spec();
  spec.active_set.max_iterations = 0;
  const fastnorm::Grid<> grid(4, 4, 1e-4, 1e-4);
  CHECK_THROWS_WITH(fastnorm::AnySolver<>(spec, grid, fastnorm::Material<>(2.1e11, 0.3)), Contains("max_iterations"));
}

TEST_CASE("Every option of a spec reaches its solver", "[core][spec]") {
  using fastnorm::test::steel;
  const auto [grid, h, loading] = fastnorm::test::hertz_ellipsoid(16);

  auto cg = Spec::parse("cg");
  cg.cg.max_iterations = 2;
  CHECK(fastnorm::AnySolver<>(cg, grid, steel).solve(h, loading).status == fastnorm::Status::iteration_limit);
  cg.cg.max_iterations = 5000;
  cg.cg.tolerance = 1e-3;
  const auto loose = fastnorm::AnySolver<>(cg, grid, steel).solve(h, loading);
  CHECK(loose.residual <= 1e-3);
  CHECK(loose.residual > 1e-9);

  auto norm = Spec::parse("norm");
  norm.active_set.max_iterations = 1;
  norm.active_set.start_depth_fraction = 1;
  CHECK(fastnorm::AnySolver<>(norm, grid, steel).solve(h, loading).status == fastnorm::Status::iteration_limit);

  auto elliptic = Spec::parse("elliptic");
  elliptic.table_budget_bytes = 0;
  const fastnorm::AnySolver<> untabled(elliptic, grid, steel);
  const fastnorm::AnySolver<> tabled("elliptic", grid, steel);
  CHECK(untabled.solve(h, loading).normal_force == Approx(tabled.solve(h, loading).normal_force).epsilon(1e-12));
  CHECK(untabled.spec().table_budget_bytes == 0);
}

TEST_CASE("A tolerance is set for the kinds it applies to and refused for the others", "[core][spec]") {
  auto cg = Spec::parse("cg");
  cg.set_cg_tolerance(1e-4);
  CHECK(cg.cg.tolerance == 1e-4);
  CHECK_THROWS_WITH(cg.set_cg_tolerance(0), Contains("tolerance must be positive"));
  CHECK_THROWS_WITH(cg.set_gap_tolerance(1e-3), Contains("'cg' stops by its tolerance"));
  CHECK_FALSE(cg.active_set.gap_tolerance);  // a refused setting leaves the spec as it was
  for (const char* name : {"norm", "elliptic", "polynomial-edge:4:1"}) {
    INFO(name);
    auto spec = Spec::parse(name);
    spec.set_gap_tolerance(1e-3);
    REQUIRE(spec.active_set.gap_tolerance);
    CHECK(*spec.active_set.gap_tolerance == 1e-3);
    CHECK(spec.active_set.join_tolerance(spec.kind == Spec::Kind::norm) == 1e-3);
    CHECK_THROWS_WITH(spec.set_gap_tolerance(-1), Contains("gap_tolerance must be finite and >= 0"));
    CHECK(*spec.active_set.gap_tolerance == 1e-3);
    const double before = spec.cg.tolerance;
    CHECK_THROWS_WITH(spec.set_cg_tolerance(1e-6), Contains("is an active-set solver, whose join tolerance is gap_tolerance"));
    CHECK(spec.cg.tolerance == before);
  }
}
