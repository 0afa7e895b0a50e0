// The wheelset contact model of the time loop (docs/wheel-rail.md §7): against the
// equilibrium it generalises, against full NORM on the exact h at every step of a short
// trajectory, against CONTACT's module 1 at its wheelset positions; warm starts, patch
// histories, forces and moments, bad poses.
#include <catch2/catch.hpp>
#include <fastnorm/fastnorm.hpp>

#include <Eigen/Geometry>  // cross
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>

#include "support/wheelrail_cases.hpp"

namespace wr = fastnorm::wheelrail;
using Catch::Matchers::Contains;
using fastnorm::test::coarse_contact;

namespace {

// Full NORM, cold, on the exact undeformed distance of today's function at the patch's grid.
fastnorm::Solution<double> norm_on_exact_h(const wr::Track& track, const wr::Wheelset& wheelset,
                                           const wr::WheelsetPose& pose, const wr::PatchContact& patch) {
  const auto& grid = patch.patch.grid;
  const Eigen::VectorXd h = wr::undeformed_distance(track, wheelset, pose, patch.patch.frame, grid);
  return fastnorm::NormSolver<double>(grid, fastnorm::Material<double>(2.1e11, 0.3))
      .solve(h, fastnorm::Loading<double>::approach());
}

}  // namespace

TEST_CASE("At the equilibrium pose the model gives the equilibrium's patches", "[wheelrail][contact]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  wr::EquilibriumOptions equilibrium_options;
  equilibrium_options.contact.grid.elements = 30;
  const auto equilibrium = wr::solve_equilibrium(track, wheelset, 3e-3, 0, 2e5, equilibrium_options);
  REQUIRE(equilibrium.ok());
  auto options = coarse_contact();
  options.snap_to_lattice = false;  // grids centred on the reference points, as the equilibrium's
  options.distance_everywhere = true;  // and h on every element, as the equilibrium's
  options.grid.element_length = equilibrium.patches[0].patch.grid.dx();
  options.grid.element_width = equilibrium.patches[0].patch.grid.dy();
  wr::WheelsetContact<> contact(track, wheelset, options);
  const auto& result = contact.evaluate(equilibrium.pose);
  REQUIRE(result.ok());
  std::size_t n = 0;
  for (const auto& wheel : result.wheels) {
    for (const auto& patch : wheel.patches) {
      REQUIRE(n < equilibrium.patches.size());
      const auto& expected = equilibrium.patches[n++];
      CHECK(patch.patch.frame.side == expected.patch.frame.side);
      CHECK(patch.normal_force == Approx(expected.solution.normal_force).epsilon(1e-12));
      CHECK(patch.contact_elements == expected.solution.contact_count());
      CHECK(patch.history == wr::PatchHistory::appeared);
    }
  }
  CHECK(n == equilibrium.patches.size());
  // The wheelset carries the load (z down: the rails push up, −z); the lateral force is
  // the equilibrium's Σ Fn sin δ; about the contact reference points (the equilibrium's
  // lever arms) the roll moment vanishes.
  CHECK(-result.force.z() == Approx(2e5).epsilon(1e-6));
  CHECK(result.force.y() == Approx(equilibrium.lateral_force).epsilon(1e-9));
  double roll_moment = 0;
  for (const auto& wheel : result.wheels) {
    for (const auto& patch : wheel.patches) {
      roll_moment += (patch.patch.frame.reference - wheelset.centre(result.pose)).cross(patch.force).x();
    }
  }
  CHECK(std::abs(roll_moment) <= equilibrium_options.force_tolerance * 2e5 * 0.75);
  // The model's moment acts at the pressure centroids, a fraction of a millimetre away.
  CHECK(std::abs(result.moment.x() - roll_moment) <= 2e5 * 0.5e-3);
}

TEST_CASE("Along a trajectory every patch is full NORM's on the exact h", "[wheelrail][contact]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  auto start = wr::rigid_contact_pose(track, wheelset, 2e-3, 0);
  // h exact at every element, and interpolated along rows (the default): then a patch's Fn
  // may differ from NORM's on the exact h by what h's error bound ε moves it, K·ε.
  for (const double tolerance : {0.0, wr::DistanceAccuracy{}.tolerance})
  for (const char* solver : {"norm", "cg", "elliptic", "elliptic+warm"}) {
    INFO(solver << ", h within " << tolerance << " m");
    const bool warm_reduced = std::string(solver) == "elliptic+warm";
    auto options = coarse_contact(warm_reduced ? "elliptic" : solver);
    options.distance.tolerance = tolerance;
    if (options.solver.is_reduced()) options.reduced_warm_start = warm_reduced;
    wr::WheelsetContact<> contact(track, wheelset, options);
    for (int step = 0; step < 12; ++step) {
      // 0.2 mm lateral steps, z lowered by 0.1 mm and oscillating, a little yaw.
      const wr::WheelsetPose pose{start.y + 0.2e-3 * step, start.z + 0.1e-3 + 5e-6 * std::sin(step), start.roll,
                                  1e-3 * std::cos(step)};
      const auto& result = contact.evaluate(pose);
      INFO("step " << step);
      REQUIRE(result.ok());
      for (const auto& wheel : result.wheels) {
        REQUIRE(!wheel.patches.empty());
        for (const auto& patch : wheel.patches) {
          if (step > 0) CHECK(patch.history == wr::PatchHistory::continued);
          const auto norm = norm_on_exact_h(track, wheelset, pose, patch);
          if (warm_reduced) {
            // Warm (the default), from the patch's last contact set: within the basis's
            // bound of NORM as the cold path below.
            CHECK(std::abs(patch.normal_force / norm.normal_force - 1) <= 1e-3);
          } else if (std::string(solver) == "elliptic") {
            // Started cold, the reduced solver follows its cold path: the cold solve's
            // answer on this h, whose error against NORM at 30 elements is up to 8.6e-4
            // here (5e-4 is the bound at 60 elements, docs/method.md).
            const auto cold = fastnorm::AnySolver<>(solver, patch.patch.grid, fastnorm::Material<double>(2.1e11, 0.3))
                                  .solve(patch.patch.undeformed_distance, fastnorm::Loading<double>::approach());
            CHECK(patch.normal_force == Approx(cold.normal_force).epsilon(1e-12));
            CHECK((patch.solution.in_contact == cold.in_contact).all());
            CHECK(std::abs(patch.normal_force / norm.normal_force - 1) <= 1e-3);
          } else if (tolerance == 0) {
            CHECK(std::abs(patch.normal_force / norm.normal_force - 1) <= 1e-8);
            CHECK((patch.solution.in_contact == norm.in_contact).all());
          } else {
            CHECK(std::abs(patch.normal_force - norm.normal_force) <= 1e-8 * norm.normal_force + patch.stiffness * tolerance);
          }
          CHECK(patch.stiffness > 0);
          // Force along −n with |force| = Fn.
          CHECK(patch.force.norm() == Approx(patch.normal_force).epsilon(1e-12));
          CHECK(patch.force.dot(patch.patch.frame.normal()) == Approx(-patch.normal_force).epsilon(1e-12));
        }
      }
    }
  }
}

TEST_CASE("Warm NORM starts are exact and reuse the lattice", "[wheelrail][contact]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  auto pose = wr::rigid_contact_pose(track, wheelset, 3e-3, 0);
  pose.z += 0.1e-3;
  wr::WheelsetContact<> contact(track, wheelset, coarse_contact());
  const fastnorm::Material<double> steel(2.1e11, 0.3);
  std::array<wr::PatchFrame, 2> first{};
  for (int step = 0; step < 8; ++step) {
    pose.y += 1e-6;  // the vehicle-dynamics step: a small motion
    const auto& result = contact.evaluate(pose);
    for (std::size_t w = 0; w < 2; ++w) {
      REQUIRE(result.wheels[w].patches.size() == 1);
      const auto& patch = result.wheels[w].patches[0];
      fastnorm::NormSolver<double> norm(patch.patch.grid, steel);
      fastnorm::NormSolver<double>::Workspace workspace;
      const auto cold = norm.solve(patch.patch.undeformed_distance, fastnorm::Loading<double>::approach(), workspace);
      CHECK(patch.normal_force == Approx(cold.normal_force).epsilon(1e-12));
      CHECK((patch.solution.in_contact == cold.in_contact).all());
      CHECK(patch.stiffness == Approx(norm.normal_stiffness(cold, workspace)).epsilon(1e-10));
      // The grid's frame moves only by whole elements from the first step's.
      if (step == 0) first[w] = patch.patch.frame;
      const Eigen::Vector3d moved = patch.patch.frame.reference - first[w].reference;
      CHECK(std::abs(std::remainder(moved.x(), contact.element_length())) <= 1e-12);
      CHECK(std::abs(std::remainder(moved.dot(first[w].lateral_axis()), contact.element_width())) <= 1e-9);
    }
  }
}

TEST_CASE("Reduced warm starts begin at the patch's last contact set", "[wheelrail][contact]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  auto pose = wr::rigid_contact_pose(track, wheelset, 3e-3, 0);
  pose.z += 0.1e-3;
  SECTION("defaults: warm but for the edge-enriched elliptic basis, NORM and CG warm") {
    for (const char* name : {"norm", "cg", "elliptic", "polynomial:4", "polynomial-edge:4:1"}) {
      CHECK(coarse_contact(name).starts_warm());
    }
    CHECK(!coarse_contact("elliptic-edge:1").starts_warm());
    auto options = coarse_contact("elliptic-edge:1");
    options.reduced_warm_start = true;
    CHECK(options.starts_warm());
    options = coarse_contact("polynomial-edge:4:1");
    options.reduced_warm_start = false;
    CHECK(!options.starts_warm());
  }
  SECTION("the same pose again: the last set is stable at once, in the same box and the same answer") {
    auto options = coarse_contact("elliptic");
    options.reduced_warm_start = true;
    wr::WheelsetContact<> contact(track, wheelset, options);
    std::array<double, 2> force{};
    std::array<Eigen::Index, 2> count{};
    const auto& first = contact.evaluate(pose);
    for (std::size_t w = 0; w < 2; ++w) {
      REQUIRE(first.wheels[w].patches.size() == 1);
      REQUIRE(first.wheels[w].patches[0].solution.status == fastnorm::Status::converged);
      REQUIRE(first.wheels[w].patches[0].solution.iterations > 1);
      force[w] = first.wheels[w].patches[0].normal_force;
      count[w] = first.wheels[w].patches[0].contact_elements;
    }
    for (int call = 0; call < 3; ++call) {  // a box kept for several calls keeps its start fresh
      const auto& again = contact.evaluate(pose);
      for (std::size_t w = 0; w < 2; ++w) {
        const auto& patch = again.wheels[w].patches[0];
        CHECK(patch.solution.status == fastnorm::Status::converged);
        CHECK(patch.solution.iterations == 1);
        CHECK(patch.normal_force == Approx(force[w]).epsilon(1e-12));
        CHECK(patch.contact_elements == count[w]);
      }
    }
  }
}

namespace {

// CONTACT centres each grid on its contact reference point: the model without the lattice.
void compare_fixed_pose_with_contact(Eigen::Index elements, double pmax_tolerance) {
  const auto files = fastnorm::test::wheelrail_peer_cases();
  const wr::Track track;
  const wr::Wheelset wheelset;
  auto options = coarse_contact();
  options.grid.elements = elements;
  options.snap_to_lattice = false;
  wr::WheelsetContact<> contact(track, wheelset, options);
  double worst_offset = 0, worst_pmax = 0;
  for (const auto& path : files) {
    const auto setup = fastnorm::test::read_wheelrail_case(path);
    const auto problem = fastnorm::read_case_file<double>(path);
    INFO(std::filesystem::path(path).filename().string());
    const wr::WheelsetPose pose{setup.y_mm * 1e-3, setup.z_mm * 1e-3, setup.roll, setup.yaw};
    contact.reset();
    const auto& wheel = contact.evaluate(pose).wheel(setup.side);
    REQUIRE(wheel.patches.size() == 1);
    const auto& patch = wheel.patches[0];
    REQUIRE(patch.ok());
    // At a fixed pose Fn is as sensitive as the stiffness says: the approach offset that
    // explains the force difference is held to the z tolerance of the single-wheel test
    // (2e-4 mm: CONTACT prints z to 1e-4 mm, and the grids differ).
    const double offset = (patch.normal_force - problem.result->normal_force) / patch.stiffness;
    const double pmax = patch.max_pressure / problem.result->pressure.maxCoeff() - 1;
    INFO("Fn " << patch.normal_force / problem.result->normal_force - 1 << ", approach offset " << offset * 1e3
               << " mm, pmax " << pmax);
    CHECK(std::abs(offset) <= 2e-7);
    CHECK(std::abs(patch.centre.y() * 1e3 - setup.ycp) <= 0.01);
    CHECK(std::abs(patch.contact_angle - std::abs(setup.deltcp)) <= 2e-4);
    CHECK(std::abs(pmax) <= pmax_tolerance);
    worst_offset = std::max(worst_offset, std::abs(offset));
    worst_pmax = std::max(worst_pmax, std::abs(pmax));
  }
  WARN(elements << " elements at CONTACT's wheelset positions: max approach offset " << worst_offset * 1e3
                << " mm, max |pmax/pmax_CONTACT - 1| " << worst_pmax);
}

}  // namespace

TEST_CASE("At CONTACT's wheelset positions the model gives CONTACT's patches", "[wheelrail][contact][peer]") {
  // pmax is sampled at element centres of grids other than CONTACT's (its DX, DS differ from
  // ours): measured 4.8 % at 30 elements, 2.0 % at 60.
  compare_fixed_pose_with_contact(30, 0.05);
}

TEST_CASE("At CONTACT's wheelset positions, on CONTACT's 60 elements", "[wheelrail][contact][peer][large]") {
  compare_fixed_pose_with_contact(60, 0.025);
}

TEST_CASE("The model rejects bad poses and options by name", "[wheelrail][contact]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  wr::WheelsetContact<> contact(track, wheelset, coarse_contact());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(contact.evaluate({0, nan, 0, 0}), Contains("z"));
  CHECK_THROWS_WITH(contact.evaluate({0.05, 0, 0, 0}), Contains("y"));
  CHECK_THROWS_WITH(contact.evaluate({0, 0, 0, std::numeric_limits<double>::infinity()}), Contains("yaw"));
  auto options = coarse_contact();
  options.grid.element_length = 1e-4;  // without element_width
  CHECK_THROWS_WITH(wr::WheelsetContact<>(track, wheelset, options), Contains("element_width"));
  // Lifted off: no patches, zero force, no error.
  const auto& lifted = contact.evaluate({0, -0.01, 0, 0});
  CHECK(lifted.ok());
  CHECK(lifted.wheels[0].patches.empty());
  CHECK(lifted.force.norm() == 0);
}
