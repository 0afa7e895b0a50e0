// Solvers that remember: solve_next along a sequence of slowly changing problems gives the
// answers of cold solves (docs/performance.md §4).
#include <catch2/catch.hpp>
#include <fastnorm/any_solver.hpp>
#include <fastnorm/hertz.hpp>

#include <string>
#include <vector>
#include "support/surfaces.hpp"

namespace {

using fastnorm::test::steel;

/// A Hertz indenter (R = 0.3 m × 0.2 m) moved in steps of `step` elements in x and tilted
/// a little more each step: h_s(x, y) = h(x − s·step·dx, y) + s·step·2e-3·y − depth.
struct Sequence {
  fastnorm::Grid<> grid;
  std::vector<Eigen::VectorXd> h;
};

Sequence moving_indenter(Eigen::Index n, int steps, double depth, double step = 0.1) {
  const auto hertz = fastnorm::hertz_from_force(0.3, 0.2, steel.combined_modulus(), 5e4);
  const auto grid = fastnorm::hertz_grid(hertz, n, 1.4);
  Sequence sequence{grid, {}};
  for (int s = 0; s < steps; ++s) {
    const double shift = s * step * grid.dx(), tilt = s * step * 2e-3;
    const fastnorm::Grid<> shifted(grid.mx(), grid.my(), grid.dx(), grid.dy(), grid.x0() - shift, grid.y0());
    Eigen::VectorXd h = fastnorm::hertz_undeformed_distance(shifted, 0.3, 0.2);
    for (Eigen::Index k = 0; k < grid.size(); ++k) h(k) += tilt * grid.y_of(k) - depth;
    sequence.h.push_back(h);
  }
  return sequence;
}

/// Runs the sequence warm and cold; pressures must agree to `pressure_tolerance` of the peak.
/// What a warm start does to the iteration count: the reduced solvers follow the cold path
/// (their answer depends on it); NORM starts from the last set; CG from the last pressures,
/// which pay only when they are closer than its cold start (`any`: not checked).
enum class Iterations { same_path, no_more, fewer, any };

/// Force control on the unloaded indenter, approach control pressed in by 50 µm.
void require_warm_equals_cold(const std::string& name, double pressure_tolerance, Iterations iterations,
                              const fastnorm::Loading<>& loading, double step = 0.1) {
  const Sequence sequence =
      moving_indenter(24, 12, loading.control == fastnorm::Control::approach ? 5e-5 : 0.0, step);
  fastnorm::AnySolver<> solver(name, sequence.grid, steel);
  int warm_iterations = 0, cold_iterations = 0;
  for (std::size_t s = 0; s < sequence.h.size(); ++s) {
    const auto warm = solver.solve_next(sequence.h[s], loading);
    const auto cold = solver.solve(sequence.h[s], loading);
    REQUIRE(cold.status == fastnorm::Status::converged);
    REQUIRE(warm.status == fastnorm::Status::converged);
    const double difference = (warm.pressure - cold.pressure).cwiseAbs().maxCoeff() / cold.pressure.maxCoeff();
    INFO(name << " step " << s << ": pressure difference " << difference << ", iterations warm "
              << warm.iterations << " cold " << cold.iterations);
    CHECK((warm.in_contact == cold.in_contact).all());
    CHECK(difference <= pressure_tolerance);
    CHECK(warm.normal_force == Approx(cold.normal_force).epsilon(std::max(pressure_tolerance, 1e-14)));
    if (s > 0) {
      warm_iterations += warm.iterations;
      cold_iterations += cold.iterations;
    }
  }
  INFO(name << ": iterations after the first step, warm " << warm_iterations << ", cold " << cold_iterations);
  switch (iterations) {
    case Iterations::same_path: CHECK(warm_iterations == cold_iterations); break;
    case Iterations::no_more: CHECK(warm_iterations <= cold_iterations); break;
    case Iterations::fewer: CHECK(warm_iterations < cold_iterations); break;
    case Iterations::any: break;
  }

  // After reset() the next solve_next is a cold solve again.
  solver.reset();
  const auto again = solver.solve_next(sequence.h.front(), loading);
  const auto cold = solver.solve(sequence.h.front(), loading);
  CHECK(again.iterations == cold.iterations);
  CHECK(again.pressure == cold.pressure);
}

}  // namespace

TEST_CASE("Warm NORM gives the cold answers along a moving indenter", "[sequence][warm]") {
  // The same final set is factorised the same way: the same numbers.
  require_warm_equals_cold("norm", 0.0, Iterations::no_more, fastnorm::Loading<>::force(5e4));
  require_warm_equals_cold("norm", 0.0, Iterations::no_more, fastnorm::Loading<>::approach());
}

TEST_CASE("Warm reduced solvers give the cold answers along a moving indenter", "[sequence][warm]") {
  // Blocks copied from the previous assembly equal the recomputed ones up to the order of
  // the sums in the products: round-off.
  for (const char* name : {"elliptic", "polynomial:4", "polynomial-edge"}) {
    require_warm_equals_cold(name, 1e-12, Iterations::same_path, fastnorm::Loading<>::force(5e4));
    require_warm_equals_cold(name, 1e-12, Iterations::same_path, fastnorm::Loading<>::approach());
  }
}

TEST_CASE("Warm CG gives the cold answers along a moving indenter", "[sequence][warm][cg]") {
  // Both satisfy the Signorini conditions to 1e-9 of the depth; the pressures then agree
  // to about 1e-7 of the peak (measured 2e-8 on the peer cases).
  // Steps of a hundredth of an element, as a time loop's: the last pressures are the better
  // start. Steps of a tenth: the cold start (Hertz-like on half the overlap depth) is as
  // close on this Hertz indenter, and the warm solves take as many iterations (measured 97
  // warm, 95 cold in force control; 116 and 105 in approach control).
  for (const auto& loading : {fastnorm::Loading<>::force(5e4), fastnorm::Loading<>::approach()}) {
    require_warm_equals_cold("cg", 1e-6, Iterations::fewer, loading, 0.01);
    require_warm_equals_cold("cg", 1e-6, Iterations::any, loading, 0.1);
  }
}

TEST_CASE("A cold solve does not depend on what the solver solved before", "[sequence][warm]") {
  // solve borrows workspace storage from the solver's pool, never its sets or factors.
  const Sequence sequence = moving_indenter(20, 8, 0.0);
  for (const char* name : {"norm", "elliptic", "polynomial:4"}) {
    const fastnorm::AnySolver<> solver(name, sequence.grid, steel);
    const auto loading = fastnorm::Loading<>::force(5e4);
    const auto first = solver.solve(sequence.h.front(), loading);
    (void)solver.solve(sequence.h.back(), loading);
    const auto again = solver.solve(sequence.h.front(), loading);
    INFO(name);
    REQUIRE(first.status == fastnorm::Status::converged);
    CHECK(again.iterations == first.iterations);
    CHECK(again.pressure == first.pressure);
  }
}

TEST_CASE("A workspace's iteration limit bounds the next solves below the options' own", "[sequence][warm]") {
  // WarmStart::limit_iterations (what WheelsetContact::set_iteration_budget sets per patch):
  // a solve that needs more stops at the limit, a caller's budget, with a usable iterate
  // (Status::budget_reached: CG's projected iterate; the active-set loop's first set here,
  // whose pressures are all positive); 0 lifts it.
  const auto sequence = moving_indenter(24, 1, 2e-5);
  const auto& h = sequence.h.front();
  for (const char* name : {"norm", "cg", "elliptic"}) {
    INFO(name);
    const fastnorm::AnySolver<> solver(name, sequence.grid, steel);
    fastnorm::AnySolver<>::Workspace workspace;
    const auto free_solve = solver.solve(h, fastnorm::Loading<>::approach(), workspace);
    REQUIRE(free_solve.status == fastnorm::Status::converged);
    REQUIRE(free_solve.iterations > 1);
    workspace.forget();
    workspace.start().limit_iterations(1);
    const auto limited = solver.solve(h, fastnorm::Loading<>::approach(), workspace);
    CHECK(limited.status == fastnorm::Status::budget_reached);
    CHECK(limited.ok());
    CHECK(limited.stopped_early());
    CHECK(limited.iterations == 1);
    CHECK(limited.residual > 0);  // elements outside still interpenetrate
    CHECK(limited.normal_force > 0);
    CHECK(workspace.start().iteration_limit() == 1);  // kept for the solves after
    workspace.forget();
    workspace.start().limit_iterations(0);
    const auto again = solver.solve(h, fastnorm::Loading<>::approach(), workspace);
    CHECK(again.pressure == free_solve.pressure);
  }
  fastnorm::WarmStart<> start;
  CHECK_THROWS_WITH(start.limit_iterations(-2), Catch::Matchers::Contains("iteration limit must be >= 0"));
}

TEST_CASE("A budget's stop answers with the loop's last admissible iterate; the options' own limit does not",
          "[sequence][warm]") {
  // Status::budget_reached: the answer is the last set of the loop whose pressures were all
  // positive, with its join check's residual: NORM solves each set exactly, so the gap
  // h + C p vanishes on the answer's set and its deepest value outside, relative to the
  // depth, is the residual (recomputed here with the influence table's full product).
  // The solver's own max_iterations is a failure: the clipped last iterate, iteration_limit.
  const auto sequence = moving_indenter(24, 1, 2e-5);
  const auto& h = sequence.h.front();
  fastnorm::ActiveSetOptions<> small_start;  // the deepest elements alone: several joins
  small_start.start_depth_fraction = 0.9;
  const fastnorm::NormSolver<> solver(sequence.grid, steel, small_start);
  fastnorm::NormSolver<>::Workspace workspace;
  const auto free_solve = solver.solve(h, fastnorm::Loading<>::approach(), workspace);
  REQUIRE(free_solve.iterations >= 3);
  int budget_stops = 0;
  for (int limit = 1; limit < free_solve.iterations; ++limit) {
    INFO("limit " << limit << " of " << free_solve.iterations);
    workspace.forget();
    workspace.start().limit_iterations(limit);
    const auto stopped = solver.solve(h, fastnorm::Loading<>::approach(), workspace);
    REQUIRE(stopped.stopped_early());
    CHECK(stopped.iterations == limit);
    if (stopped.status != fastnorm::Status::budget_reached) continue;  // no admissible iterate yet
    ++budget_stops;
    const Eigen::VectorXd gap = h + solver.influence().displacement(stopped.pressure);
    const double depth = -h.minCoeff();
    double deepest_outside = 0, largest_on_set = 0;
    for (Eigen::Index k = 0; k < h.size(); ++k) {
      if (stopped.in_contact(k)) {
        CHECK(stopped.pressure(k) > 0);
        largest_on_set = std::max(largest_on_set, std::abs(gap(k)));
      } else {
        deepest_outside = std::min(deepest_outside, gap(k));
      }
    }
    CHECK(largest_on_set <= 1e-12 * depth);
    CHECK(stopped.residual == Approx(-deepest_outside / depth).epsilon(1e-9));
    CHECK(stopped.residual > 0);
  }
  CHECK(budget_stops > 0);
  fastnorm::ActiveSetOptions<> one_iteration;
  one_iteration.max_iterations = 1;
  const fastnorm::NormSolver<> impatient(sequence.grid, steel, one_iteration);
  const auto given_up = impatient.solve(h, fastnorm::Loading<>::approach());
  CHECK(given_up.status == fastnorm::Status::iteration_limit);
  CHECK_FALSE(given_up.ok());
}

TEST_CASE("An iteration cap waits for an admissible iterate; the limit does not", "[sequence][warm]") {
  // Started from nearly every interpenetrating element, NORM drops elements in its first
  // iterations. Limited to one, it stops there without an iterate whose pressures are all
  // positive (iteration_limit, not usable); capped at one, it goes on to the first such
  // iterate and answers usably; a limit below the cap's wait still bounds it.
  const auto sequence = moving_indenter(24, 1, 2e-5);
  const auto& h = sequence.h.front();
  fastnorm::ActiveSetOptions<> large_start;
  large_start.start_depth_fraction = 0.05;
  const fastnorm::NormSolver<> solver(sequence.grid, steel, large_start);
  fastnorm::NormSolver<>::Workspace workspace;
  workspace.start().limit_iterations(1);
  const auto limited = solver.solve(h, fastnorm::Loading<>::approach(), workspace);
  REQUIRE(limited.status == fastnorm::Status::iteration_limit);  // a drop first
  CHECK(limited.iterations == 1);
  workspace.forget();  // keeps the limit: lifted here
  workspace.start().limit_iterations(0);
  workspace.start().cap_iterations(1);
  CHECK(workspace.start().iteration_cap() == 1);
  const auto capped = solver.solve(h, fastnorm::Loading<>::approach(), workspace);
  CHECK(capped.ok());
  CHECK(capped.iterations > 1);
  CHECK((capped.pressure.array() >= 0).all());
  workspace.forget();
  workspace.start().cap_iterations(1);
  workspace.start().limit_iterations(1);
  CHECK(solver.solve(h, fastnorm::Loading<>::approach(), workspace).status == fastnorm::Status::iteration_limit);
  CHECK_THROWS_WITH(workspace.start().cap_iterations(-1), Catch::Matchers::Contains("iteration cap must be >= 0"));
}

TEST_CASE("A solve stopped by its iteration limit is continued by the next", "[sequence][warm]") {
  // After a solve that reached the workspace's limit, NORM and the reduced solvers leave in
  // the start the set their active-set loop would have solved next (ActiveSetWorkspace::next_set):
  // solves of one iteration each, one after the other, take the loop's own steps and end on
  // its answer, in as many iterations in all.
  for (const auto& loading : {fastnorm::Loading<>::approach(), fastnorm::Loading<>::force(5e4)}) {
    const auto sequence = moving_indenter(24, 1, loading.control == fastnorm::Control::approach ? 2e-5 : 0.0);
    const auto& h = sequence.h.front();
    for (const char* name : {"norm", "elliptic", "polynomial:4"}) {
      INFO(name << (loading.control == fastnorm::Control::approach ? ", approach control" : ", force control"));
      const fastnorm::AnySolver<> solver(name, sequence.grid, steel);
      fastnorm::AnySolver<>::Workspace workspace;
      const auto free_solve = solver.solve(h, loading, workspace);
      REQUIRE(free_solve.status == fastnorm::Status::converged);
      REQUIRE(free_solve.iterations >= 2);
      workspace.forget();
      workspace.start().limit_iterations(1);
      int spent = 0;
      fastnorm::Solution<> continued;
      do {
        continued = solver.solve(h, loading, workspace);
        spent += continued.iterations;
        if (continued.stopped_early()) CHECK_FALSE(workspace.start().contact_set().empty());
      } while (continued.stopped_early() && spent < 2 * free_solve.iterations);
      REQUIRE(continued.status == fastnorm::Status::converged);
      CHECK(spent == free_solve.iterations);
      CHECK((continued.in_contact == free_solve.in_contact).all());
      // A kept factor or assembly updated rather than computed afresh: round-off.
      CHECK((continued.pressure - free_solve.pressure).cwiseAbs().maxCoeff() <= 1e-12 * free_solve.pressure.maxCoeff());
    }
  }
}

TEST_CASE("A CG solve stopped by its iteration limit is continued by the next", "[sequence][warm][cg]") {
  // CG leaves its cut iterate's pressures as the next start: solves of two iterations
  // each, one after the other, reach the free solve's answer (to CG's tolerance, as the
  // warm solves above).
  const auto sequence = moving_indenter(24, 1, 2e-5);
  const auto& h = sequence.h.front();
  const fastnorm::AnySolver<> solver("cg", sequence.grid, steel);
  fastnorm::AnySolver<>::Workspace workspace;
  const auto free_solve = solver.solve(h, fastnorm::Loading<>::approach(), workspace);
  REQUIRE(free_solve.status == fastnorm::Status::converged);
  REQUIRE(free_solve.iterations > 4);
  workspace.forget();
  workspace.start().limit_iterations(2);
  fastnorm::Solution<> continued;
  int solves = 0;
  do {
    continued = solver.solve(h, fastnorm::Loading<>::approach(), workspace);
    if (continued.stopped_early()) CHECK(workspace.start().has_pressure());
  } while (continued.stopped_early() && ++solves < 10 * free_solve.iterations);
  REQUIRE(continued.status == fastnorm::Status::converged);
  INFO("solves of at most 2 iterations: " << solves + 1 << "; the free solve's iterations: " << free_solve.iterations);
  CHECK((continued.pressure - free_solve.pressure).cwiseAbs().maxCoeff() <= 1e-6 * free_solve.pressure.maxCoeff());
}
