// Explicit solver state (docs/architecture.md §2): solve(h, loading, workspace) is the one
// call that works; solve, solve_next and reset are conveniences over it, and a workspace's
// starting set can be set by hand, checked, and moved between solvers.
#include <catch2/catch.hpp>
#include <fastnorm/hertz.hpp>
#include <fastnorm/solvers.hpp>

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "support/surfaces.hpp"

using Catch::Matchers::Contains;

namespace {

using fastnorm::test::steel;

struct Problem {
  fastnorm::Grid<> grid;
  Eigen::VectorXd h;
};

/// A Hertz indenter on a 20 × 20 grid, tilted by `tilt` (rad).
Problem indenter(double tilt) {
  const auto hertz = fastnorm::hertz_from_force(0.3, 0.2, steel.combined_modulus(), 5e4);
  const auto grid = fastnorm::hertz_grid(hertz, 20, 1.4);
  Eigen::VectorXd h = fastnorm::hertz_undeformed_distance(grid, 0.3, 0.2);
  for (Eigen::Index k = 0; k < grid.size(); ++k) h(k) += tilt * grid.y_of(k);
  return {grid, h};
}

const char* const every_solver[] = {"norm", "cg", "elliptic", "polynomial:4", "polynomial-edge"};

}  // namespace

TEST_CASE("A default Solution claims nothing", "[sequence][workspace]") {
  const fastnorm::Solution<> nothing;
  CHECK(nothing.status == fastnorm::Status::not_solved);
  CHECK_FALSE(nothing.ok());
  CHECK(std::string(fastnorm::to_string(nothing.status)) == "not solved");
}

TEST_CASE("solve with a workspace is what solve and solve_next do", "[sequence][workspace]") {
  const Problem problem = indenter(0);
  const auto loading = fastnorm::Loading<>::force(5e4);
  for (const char* name : every_solver) {
    INFO(name);
    fastnorm::AnySolver<> solver(name, problem.grid, steel);
    fastnorm::AnySolver<>::Workspace workspace;
    const auto explicit_cold = solver.solve(problem.h, loading, workspace);
    const auto convenience = solver.solve(problem.h, loading);
    CHECK(explicit_cold.pressure == convenience.pressure);
    CHECK(explicit_cold.iterations == convenience.iterations);
    const auto explicit_warm = solver.solve(problem.h, loading, workspace);
    (void)solver.solve_next(problem.h, loading);
    const auto warm = solver.solve_next(problem.h, loading);
    CHECK(explicit_warm.pressure == warm.pressure);
    CHECK(explicit_warm.iterations == warm.iterations);
  }
}

TEST_CASE("Every solver reports the residual it computed", "[sequence][workspace]") {
  const Problem problem = indenter(2e-4);
  // Each active-set solver at its own join tolerance, and the reduced ones also at NORM's.
  const std::optional<double> tolerances[] = {std::nullopt, 1000 * std::numeric_limits<double>::epsilon()};
  for (const auto& loading : {fastnorm::Loading<>::approach(), fastnorm::Loading<>::force(5e4)}) {
    Eigen::VectorXd h = problem.h;
    if (loading.control == fastnorm::Control::approach) h.array() -= 5e-5;
    for (const char* name : every_solver) for (const auto& tolerance : tolerances) {
      auto spec = fastnorm::SolverSpec<>::parse(name);
      if (tolerance && !spec.is_reduced()) continue;
      spec.active_set.gap_tolerance = tolerance;
      INFO(name << (tolerance ? " at NORM's join tolerance" : ""));
      const fastnorm::AnySolver<> solver(spec, problem.grid, steel);
      const auto solution = solver.solve(h, loading);
      REQUIRE(solution.status == fastnorm::Status::converged);
      CHECK(solution.residual >= 0);
      if (std::string(name) == "cg") {
        // The complementarity error of Eq. (P1), recomputed here from the pressures.
        const auto& influence = solver.grid();
        const fastnorm::InfluenceTable<> table(influence, steel);
        const Eigen::VectorXd gap = h.array() - solution.approach + table.displacement(solution.pressure).array();
        double error = 0;
        for (Eigen::Index k = 0; k < gap.size(); ++k) {
          error = std::max(error, solution.pressure(k) > 0 ? std::abs(gap(k)) : -gap(k));
        }
        const double depth = solution.approach - h.minCoeff();
        CHECK(solution.residual <= 1e-9);
        CHECK(solution.residual == Approx(error / depth).margin(1e-11));
      } else {
        // The join check lets no element in deeper than τ · max|h|: the tolerance set, else
        // 1000 ε for NORM and 3e-5 for the reduced solvers (ActiveSetOptions::join_tolerance).
        const double tau = spec.active_set.join_tolerance(!spec.is_reduced());
        CHECK(solution.residual * (solution.approach - h.minCoeff()) <= tau * h.cwiseAbs().maxCoeff());
      }
    }
  }
}

TEST_CASE("A starting set set by hand gives the same answer, sooner", "[sequence][workspace]") {
  const Problem problem = indenter(3e-4);
  const auto loading = fastnorm::Loading<>::force(5e4);
  for (const char* name : {"norm", "cg"}) {
    INFO(name);
    const fastnorm::AnySolver<> solver(name, problem.grid, steel);
    const auto cold = solver.solve(problem.h, loading);
    fastnorm::AnySolver<>::Workspace workspace;
    std::vector<Eigen::Index> set;
    for (Eigen::Index k = 0; k < cold.in_contact.size(); ++k) {
      if (cold.in_contact(k)) set.push_back(k);
    }
    workspace.start().set_contact_set(set);
    CHECK_FALSE(workspace.start().has_pressure());
    const auto started = solver.solve(problem.h, loading, workspace);
    CHECK((started.in_contact == cold.in_contact).all());
    CHECK(started.normal_force == Approx(cold.normal_force).epsilon(1e-12));
    CHECK((started.pressure - cold.pressure).cwiseAbs().maxCoeff() <= 1e-6 * cold.pressure.maxCoeff());
    CHECK(started.iterations < cold.iterations);
    // The workspace now holds the contact set of the answer (and CG its pressures).
    CHECK(workspace.start().contact_set() == set);
    CHECK(workspace.start().has_pressure() == (std::string(name) == "cg"));
  }
}

TEST_CASE("A bad starting set is rejected by name", "[sequence][workspace]") {
  const Problem problem = indenter(0);
  for (const char* name : every_solver) {
    INFO(name);
    const fastnorm::AnySolver<> solver(name, problem.grid, steel);
    fastnorm::AnySolver<>::Workspace workspace;
    workspace.start().set_contact_set({3, 2});
    CHECK_THROWS_WITH(solver.solve(problem.h, fastnorm::Loading<>::approach(), workspace), Contains("sorted"));
    workspace.start().set_contact_set({problem.grid.size()});
    CHECK_THROWS_WITH(solver.solve(problem.h, fastnorm::Loading<>::approach(), workspace), Contains("contact_set[0]"));
    workspace.forget();
    CHECK(solver.solve(problem.h, fastnorm::Loading<>::force(5e4), workspace).ok());
  }
}

TEST_CASE("A workspace moves between solvers and grids", "[sequence][workspace]") {
  const Problem fine = indenter(0);
  const auto [coarse_grid, coarse_h, loading] = fastnorm::test::hertz_ellipsoid(12);
  fastnorm::AnySolver<>::Workspace workspace;
  for (const char* name : every_solver) {
    INFO(name);
    const fastnorm::AnySolver<> on_fine(name, fine.grid, steel), on_coarse(name, coarse_grid, steel);
    // One workspace, alternately on two grids and from solver kind to kind: every answer is
    // the cold one (what belonged to another solver is never used).
    for (int round = 0; round < 2; ++round) {
      workspace.forget();
      const auto a = on_fine.solve(fine.h, loading, workspace);
      workspace.forget();
      const auto b = on_coarse.solve(coarse_h, loading, workspace);
      CHECK(a.pressure == on_fine.solve(fine.h, loading).pressure);
      CHECK(b.pressure == on_coarse.solve(coarse_h, loading).pressure);
    }
  }
}

TEST_CASE("A copied solver goes on from the same point, independently", "[sequence][workspace]") {
  const Problem first = indenter(0), second = indenter(4e-4);
  const auto loading = fastnorm::Loading<>::force(5e4);
  for (const char* name : every_solver) {
    INFO(name);
    fastnorm::AnySolver<> original(name, first.grid, steel);
    (void)original.solve_next(first.h, loading);
    fastnorm::AnySolver<> copy = original;
    const auto from_copy = copy.solve_next(second.h, loading);
    const auto from_original = original.solve_next(second.h, loading);
    CHECK(from_copy.pressure == from_original.pressure);
    CHECK(from_copy.iterations == from_original.iterations);
    CHECK(copy.workspace().start().contact_set() == original.workspace().start().contact_set());
  }
}
