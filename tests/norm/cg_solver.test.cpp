// The FFT conjugate-gradient solver against NORM, the exact solution of the same discrete
// problem: the same contact set and the same force on every problem both solve
// (docs/performance.md §2). Its agreement with CONTACT is in peer_cases.test.cpp.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <tuple>
#include <fastnorm/cg_solver.hpp>
#include <fastnorm/hertz.hpp>
#include <fastnorm/norm_solver.hpp>

#include "support/complementarity.hpp"
#include "support/signorini.hpp"
#include "support/surfaces.hpp"

using Catch::Matchers::Contains;

namespace {

using fastnorm::test::steel;
using fastnorm::test::two_bumps_grid;

/// CG's answer against NORM's on the same h and loading.
void require_same_as_norm(const Eigen::VectorXd& h, const fastnorm::Loading<>& loading) {
  const auto& grid = two_bumps_grid;
  const auto exact = fastnorm::NormSolver<>(grid, steel).solve(h, loading);
  const fastnorm::CgSolver<> cg(grid, steel);
  const auto iterative = cg.solve(h, loading);
  REQUIRE(exact.status == fastnorm::Status::converged);
  REQUIRE(iterative.status == fastnorm::Status::converged);
  const double peak = exact.pressure.maxCoeff();
  INFO("force " << iterative.normal_force / exact.normal_force - 1 << ", pressure "
                << (iterative.pressure - exact.pressure).cwiseAbs().maxCoeff() / peak << ", iterations "
                << iterative.iterations);
  CHECK(std::abs(iterative.normal_force / exact.normal_force - 1) < 1e-8);
  CHECK((iterative.pressure - exact.pressure).cwiseAbs().maxCoeff() < 1e-6 * peak);
  CHECK((iterative.in_contact == exact.in_contact).all());
  CHECK(std::abs(iterative.approach - exact.approach) <= 1e-9 * h.cwiseAbs().maxCoeff());
  fastnorm::test::require_complementarity(cg.influence(), h, iterative);
}

}  // namespace

TEST_CASE("CG equals NORM on a two-patch contact, approach and force control", "[norm][cg]") {
  const auto& grid = two_bumps_grid;
  const Eigen::VectorXd loaded = fastnorm::test::two_bumps(grid, 3e-5);
  SECTION("approach control") { require_same_as_norm(loaded, fastnorm::Loading<>::approach()); }
  SECTION("force control from the unloaded surfaces") {
    require_same_as_norm(fastnorm::test::two_bumps(grid, 0.0), fastnorm::Loading<>::force(2e4));
  }
  SECTION("a light load that touches one bump only") {
    require_same_as_norm(fastnorm::test::two_bumps(grid, 0.0), fastnorm::Loading<>::force(50));
  }
}

TEST_CASE("CG equals NORM on a Hertz contact", "[norm][cg]") {
  const auto hertz = fastnorm::hertz_from_force(0.3, 0.2, steel.combined_modulus(), 5e4);
  const auto hertz_grid = fastnorm::hertz_grid(hertz, 31);
  const Eigen::VectorXd h = fastnorm::hertz_undeformed_distance(hertz_grid, 0.3, 0.2);
  const auto exact = fastnorm::NormSolver<>(hertz_grid, steel).solve(h, fastnorm::Loading<>::force(5e4));
  const auto iterative = fastnorm::CgSolver<>(hertz_grid, steel).solve(h, fastnorm::Loading<>::force(5e4));
  REQUIRE(iterative.status == fastnorm::Status::converged);
  CHECK((iterative.in_contact == exact.in_contact).all());
  CHECK(iterative.approach == Approx(exact.approach).epsilon(1e-9));
  CHECK((iterative.pressure - exact.pressure).cwiseAbs().maxCoeff() < 1e-6 * exact.pressure.maxCoeff());
}

TEST_CASE("CG stops when the complementarity error is below its tolerance", "[norm][cg]") {
  const auto& grid = two_bumps_grid;
  const Eigen::VectorXd h = fastnorm::test::two_bumps(grid, 3e-5);
  int previous_iterations = 0;
  for (double tolerance : {1e-3, 1e-6, 1e-9, 1e-12}) {
    fastnorm::CgOptions<> options;
    options.tolerance = tolerance;
    const fastnorm::CgSolver<> cg(grid, steel, options);
    for (const auto& loading : {fastnorm::Loading<>::approach(), fastnorm::Loading<>::force(2e4)}) {
      const auto solution = cg.solve(h, loading);
      REQUIRE(solution.status == fastnorm::Status::converged);
      const double error = fastnorm::test::complementarity_error(cg.influence(), h, solution);
      INFO("tolerance " << tolerance << ": error " << error << " after " << solution.iterations << " iterations");
      CHECK(error <= tolerance * (1 + 1e-6));
      if (loading.control == fastnorm::Control::approach) {
        CHECK(solution.iterations >= previous_iterations);
        previous_iterations = solution.iterations;
      }
    }
  }
}

TEST_CASE("CG reports no contact, the iteration limit and bad input", "[norm][cg]") {
  const auto& grid = two_bumps_grid;
  const fastnorm::CgSolver<> cg(grid, steel);
  const Eigen::VectorXd apart = fastnorm::test::two_bumps(grid, -1e-4);
  const auto none = cg.solve(apart, fastnorm::Loading<>::approach());
  CHECK(none.status == fastnorm::Status::no_contact);
  CHECK(none.pressure.isZero());
  CHECK(none.contact_count() == 0);

  fastnorm::CgOptions<> few;
  few.max_iterations = 2;
  const auto stopped = fastnorm::CgSolver<>(grid, steel, few).solve(fastnorm::test::two_bumps(grid, 3e-5),
                                                                    fastnorm::Loading<>::approach());
  CHECK(stopped.status == fastnorm::Status::iteration_limit);
  CHECK(stopped.iterations == 2);
  CHECK_THAT(stopped.message, Contains("complementarity error"));
  CHECK(stopped.pressure.minCoeff() >= 0);

  Eigen::VectorXd nan_h = apart;
  nan_h(3) = std::nan("");
  CHECK_THROWS_WITH(cg.solve(nan_h, fastnorm::Loading<>::approach()), Contains("undeformed_distance[3]"));
  CHECK_THROWS_WITH(cg.solve(apart.head(4), fastnorm::Loading<>::approach()), Contains("undeformed_distance"));
  fastnorm::CgOptions<> bad;
  bad.tolerance = 0;
  CHECK_THROWS_WITH(fastnorm::CgSolver<>(grid, steel, bad), Contains("tolerance"));
  bad.tolerance = 1e-9;
  bad.max_iterations = 0;
  CHECK_THROWS_WITH(fastnorm::CgSolver<>(grid, steel, bad), Contains("max_iterations"));
}

TEST_CASE("CG runs in single precision with its default tolerance", "[norm][cg]") {
  // 1e-9 is below float's resolution; the default is 32 ε of the scalar type.
  CHECK(fastnorm::CgOptions<float>().tolerance == Approx(32 * std::numeric_limits<float>::epsilon()));
  CHECK(fastnorm::CgOptions<double>().tolerance == 1e-9);
  auto hertz_problem = [](auto scalar, Eigen::Index n) {
    using Scalar = decltype(scalar);
    const fastnorm::Material<Scalar> material(Scalar(2.1e11), Scalar(0.3));
    const auto hertz = fastnorm::hertz_from_force(Scalar(0.3), Scalar(0.3), material.combined_modulus(), Scalar(5e4));
    const auto hertz_grid = fastnorm::hertz_grid(hertz, n);
    return std::make_tuple(hertz_grid, material, fastnorm::hertz_undeformed_distance(hertz_grid, Scalar(0.3), Scalar(0.3)));
  };
  for (Eigen::Index n : {20, 61}) {
    const auto [grid_f, steel_f, h_f] = hertz_problem(0.0f, n);
    const auto [grid_d, steel_d, h_d] = hertz_problem(0.0, n);
    const auto exact = fastnorm::NormSolver<>(grid_d, steel_d).solve(h_d, fastnorm::Loading<>::force(5e4));
    const fastnorm::CgSolver<float> cg(grid_f, steel_f);
    for (const auto& loading : {fastnorm::Loading<float>::force(5e4f), fastnorm::Loading<float>::approach()}) {
      const bool force_control = loading.control == fastnorm::Control::force;
      const Eigen::VectorXf h = force_control ? h_f : Eigen::VectorXf(h_f.array() - static_cast<float>(exact.approach));
      const auto single = cg.solve(h, loading);
      INFO(n << "x" << n << (force_control ? " force" : " approach") << " control: " << single.iterations
             << " iterations, residual " << single.residual);
      REQUIRE(single.status == fastnorm::Status::converged);
      CHECK(single.residual <= cg.options().tolerance);
      CHECK(static_cast<double>(single.normal_force) == Approx(exact.normal_force).epsilon(1e-4));
      CHECK((single.in_contact != exact.in_contact).count() <= 4);  // edge elements within float's reach
    }
  }
}

TEST_CASE("CG's iterations hardly grow with the grid", "[norm][cg]") {
  // The preconditioner makes the count nearly independent of N (docs/performance.md §9):
  // the Hertz sphere at 20² and 100² (25 times the elements), both controls.
  const auto hertz = fastnorm::hertz_from_force(0.3, 0.3, steel.combined_modulus(), 5e4);
  for (const auto& loading : {fastnorm::Loading<>::force(5e4), fastnorm::Loading<>::approach()}) {
    int iterations[2] = {0, 0};
    for (int s = 0; s < 2; ++s) {
      const auto hertz_grid = fastnorm::hertz_grid(hertz, s == 0 ? 20 : 100);
      Eigen::VectorXd h = fastnorm::hertz_undeformed_distance(hertz_grid, 0.3, 0.3);
      if (loading.control == fastnorm::Control::approach) h.array() -= hertz.approach;
      const auto solution = fastnorm::CgSolver<>(hertz_grid, steel).solve(h, loading);
      REQUIRE(solution.status == fastnorm::Status::converged);
      iterations[s] = solution.iterations;
    }
    INFO("iterations 20x20: " << iterations[0] << ", 100x100: " << iterations[1]);
    CHECK(iterations[0] <= 12);
    CHECK(iterations[1] <= 12);
  }
}
