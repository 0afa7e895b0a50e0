// No allocation inside the solve loop (docs/performance.md §3): once a solver has met its
// largest problem, a solve allocates only its result, however many active-set iterations
// it takes, and nothing when the previous result is recycled; the wheelset contact model
// allocates nothing per step. The heap allocations of this test executable's own code are counted through
// the linker's --wrap of malloc (Eigen's allocator) and of operator new (the containers').
#include <catch2/catch.hpp>

#if defined(FASTNORM_COUNT_MALLOC)

#include <fastnorm/any_solver.hpp>
#include <fastnorm/detail/in_place_cholesky.hpp>
#include <fastnorm/hertz.hpp>
#include <fastnorm/wheelrail.hpp>

#include <cstddef>
#include <numeric>
#include <string>
#include <vector>

#include "bench/trajectory.hpp"
#include "support/allocation_counter.hpp"
#include "support/surfaces.hpp"

namespace {

using fastnorm::test::steel;

template <typename Call>
long allocations_of(const Call& call) {
  const long before = fastnorm_example::allocation_count();
  call();
  return fastnorm_example::allocation_count() - before;
}

/// A Hertz indenter, tilted by `tilt` (rad), so two problems take different active sets.
Eigen::VectorXd indenter(const fastnorm::Grid<>& grid, double tilt) {
  Eigen::VectorXd h = fastnorm::hertz_undeformed_distance(grid, 0.3, 0.2);
  for (Eigen::Index k = 0; k < grid.size(); ++k) h(k) += tilt * grid.y_of(k) - 4e-5;
  return h;
}

// A Solution's own storage: pressure, in_contact and its message ("contact set stable" is
// past std::string's small-string buffer; the counter replaces operator new, so it sees the
// allocations libstdc++ makes too).
constexpr long result_allocations = 3;

/// The time loop's model with `solver` on coarse patches (20 elements across).
fastnorm::wheelrail::WheelsetContactOptions coarse_model(const char* solver) {
  fastnorm::wheelrail::WheelsetContactOptions options;
  options.solver = fastnorm::SolverSpec<>::parse(solver);
  options.grid.elements = 20;
  return options;
}

}  // namespace

TEST_CASE("Solvers in a repeated sequence allocate only their results", "[sequence][allocation]") {
  const auto hertz = fastnorm::hertz_from_force(0.3, 0.2, steel.combined_modulus(), 5e4);
  // Small enough that NORM's dense blocks stay below 128 KB: past that, Eigen's blocked
  // Cholesky takes its packing buffers from the heap (docs/performance.md §3).
  const auto grid = fastnorm::hertz_grid(hertz, 16, 1.4);
  const Eigen::VectorXd first = indenter(grid, 0.0), second = indenter(grid, 4e-4);
  Eigen::VectorXd kept;
  REQUIRE(allocations_of([&] { kept.resize(10); }) == 1);  // the counter sees Eigen's allocations
  std::string text;
  REQUIRE(allocations_of([&] { text.assign(40, 'x'); }) == 1);  // and those libstdc++'s own code makes

  for (const char* name : {"norm", "cg", "elliptic", "polynomial:4"}) {
    for (const auto& loading : {fastnorm::Loading<>::approach(), fastnorm::Loading<>::force(5e4)}) {
      auto spec = fastnorm::SolverSpec<>::parse(name);
      spec.active_set.start_depth_fraction = 1;  // Kalker's start: elements leave over several iterations
      // (CG's pooled and sequence workspaces each hold their own FFT plans and vectors.)
      fastnorm::AnySolver<> solver(spec, grid, steel);
      // A round: both problems warm and cold. The first rounds grow the storage to the
      // largest set, build the tables, and let every recycled assembly hold the largest
      // system; from then on a round allocates only its four results.
      std::vector<fastnorm::Solution<>> results(4);
      auto round = [&] {
        results[0] = solver.solve_next(first, loading);
        results[1] = solver.solve_next(second, loading);
        results[2] = solver.solve(first, loading);
        results[3] = solver.solve(second, loading);
      };
      for (int warm_up = 0; warm_up < 3; ++warm_up) round();
      const long allocations = allocations_of(round);
      INFO(name << (loading.control == fastnorm::Control::force ? " force" : " approach"));
      int iterations = 0;
      for (const auto& result : results) {
        REQUIRE(result.status == fastnorm::Status::converged);
        iterations += result.iterations;
      }
      CHECK(iterations >= 8);  // the loop ran: on average two iterations a call or more
      CHECK(allocations <= 4 * result_allocations);
    }
  }
}

TEST_CASE("With the last result recycled, a repeated sequence allocates nothing", "[sequence][allocation]") {
  const auto hertz = fastnorm::hertz_from_force(0.3, 0.2, steel.combined_modulus(), 5e4);
  const auto grid = fastnorm::hertz_grid(hertz, 16, 1.4);
  const Eigen::VectorXd first = indenter(grid, 0.0), second = indenter(grid, 4e-4);
  for (const char* name : {"norm", "cg", "elliptic", "polynomial:4"}) {
    fastnorm::AnySolver<> solver(name, grid, steel);
    fastnorm::AnyWorkspace<> workspace;
    fastnorm::Solution<> result;
    auto round = [&] {
      for (const Eigen::VectorXd* h : {&first, &second}) {
        workspace.recycle(std::move(result));
        result = solver.solve(*h, fastnorm::Loading<>::approach(), workspace);
      }
    };
    for (int warm_up = 0; warm_up < 3; ++warm_up) round();
    const long allocations = allocations_of(round);
    INFO(name);
    REQUIRE(result.status == fastnorm::Status::converged);
    CHECK(result.contact_count() > 0);
    CHECK(allocations == 0);
  }
}

TEST_CASE("A cleared answer has room for the solvers' longest fixed message", "[sequence][allocation]") {
  // A recycled answer that first meets a longer ending than before (a cycle, a budget)
  // would otherwise allocate for its message inside a time step.
  fastnorm::Solution<> answer;
  answer.clear(4);
  const long allocations =
      allocations_of([&] { answer.message = "stopped by the iteration budget; the next solve goes on from here"; });
  CHECK(allocations == 0);
  CHECK(answer.message.capacity() >= fastnorm::Solution<>::message_capacity);
}

TEST_CASE("A reduced solver's workspace keeps its storage when it moves to another grid's solver",
          "[sequence][allocation]") {
  // What a time-loop model does when a patch changes its grid size and takes a spare
  // workspace of another size (WheelsetContact; docs/performance.md §8): the Galerkin
  // assemblies of the other solver are forgotten but their storage serves the new one.
  const fastnorm::Grid<> large(40, 40, 2.5e-4, 2.5e-4, -4.875e-3, -4.875e-3);
  const fastnorm::Grid<> small(32, 32, 2.5e-4, 2.5e-4, -3.875e-3, -3.875e-3);
  const fastnorm::ReducedSolver<fastnorm::EllipticBasis> on_large(large, steel);
  const auto on_small = on_large.for_grid(small);
  REQUIRE(on_large.build_tables());  // shared by both: no table is built inside a solve
  const auto loading = fastnorm::Loading<>::approach();
  fastnorm::ReducedWorkspace<> moving, other;
  for (const double tilt : {0.0, 1e-3}) on_large.solve(indenter(large, tilt), loading, moving);
  const Eigen::VectorXd h_small = indenter(small, 0.0);
  // A result of the small grid's size to recycle, so that the answer allocates nothing either.
  moving.recycle(on_small.solve(h_small, loading, other));
  fastnorm::Solution<> moved;
  const long allocations = allocations_of([&] { moved = on_small.solve(h_small, loading, moving); });
  REQUIRE(moved.status == fastnorm::Status::converged);
  CHECK(moved.contact_count() > 0);
  CHECK(allocations == 0);
  // And it answers as a workspace that never met the large grid, to the last bit.
  fastnorm::ReducedWorkspace<> fresh;
  CHECK(on_small.solve(h_small, loading, fresh).pressure == moved.pressure);
}

TEST_CASE("A factor update past Eigen's stack limit allocates nothing", "[sequence][allocation]") {
  // A polynomial basis' Galerkin system keeps the factor of ≈ 100–250 leading unknowns and
  // updates the rest (detail/in_place_cholesky.hpp); Eigen's triangular solve and rank
  // update of blocks that large pack them on the heap (about 4 200 allocations over the
  // benchmark trajectory with polynomial-edge:4:1, docs/performance.md §8). In tiles they do not.
  const Eigen::Index n = 300, kept = 200;
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(n, n);
  const Eigen::MatrixXd matrix = b * b.transpose() + Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd leading = Eigen::LLT<Eigen::MatrixXd>(matrix.topLeftCorner(kept, kept)).matrixL();
  fastnorm::detail::InPlaceCholesky<double> cholesky;
  cholesky.resize(n);
  cholesky.matrix() = matrix;
  cholesky.matrix().topLeftCorner(kept, kept) = leading;
  bool factored = false;
  CHECK(allocations_of([&] { factored = cholesky.factorise_from(kept); }) == 0);
  CHECK(factored);
}

TEST_CASE("The wheelset contact model allocates nothing per step after warm-up", "[sequence][allocation]") {
  namespace wr = fastnorm::wheelrail;
  const wr::Track track;
  const wr::Wheelset wheelset;
  // The first 60 ms of the trajectory benchmark, geometry included.
  const auto poses = fastnorm_bench::trajectory_poses(track, wheelset, 60);
  wr::WheelsetContact<> contact(track, wheelset, coarse_model("cg"));
  for (std::size_t step = 0; step < 20; ++step) contact.evaluate(poses[step]);
  double force = 0;
  const long allocations = allocations_of([&] {
    for (std::size_t step = 20; step < poses.size(); ++step) {
      const auto& result = contact.evaluate(poses[step]);
      REQUIRE(result.ok());
      force += result.wheels[0].normal_force + result.wheels[1].normal_force;
    }
  });
  CHECK(force > 0);
  CHECK(allocations == 0);
}

TEST_CASE("A model warmed up by trial steps allocates nothing from its first step and answers as a fresh one",
          "[sequence][allocation]") {
  // docs/wheel-rail.md §9, "Warming up": the poses evaluated between history() and restore()
  // leave the model's history as it was, and the storage their sizes took with the model.
  namespace wr = fastnorm::wheelrail;
  const wr::Track track;
  const wr::Wheelset wheelset;
  const auto poses = fastnorm_bench::trajectory_poses(track, wheelset, 60);
  for (const char* solver : {"elliptic", "cg"}) {
    INFO(solver);
    wr::WheelsetContact<> fresh(track, wheelset, coarse_model(solver)), warmed(track, wheelset, coarse_model(solver));
    {
      wr::WheelsetContact<>::History start;
      warmed.history(start);
      for (std::size_t step = 0; step < poses.size(); step += 2) warmed.evaluate(poses[step]);  // every other pose
      warmed.restore(start);
    }
    std::vector<double> fresh_forces, warmed_forces;
    const auto normal_force = [](const wr::WheelsetContactResult& result) {
      return result.wheels[0].normal_force + result.wheels[1].normal_force;
    };
    for (const auto& pose : poses) fresh_forces.push_back(normal_force(fresh.evaluate(pose)));
    warmed_forces.reserve(poses.size());
    const long allocations = allocations_of([&] {
      for (const auto& pose : poses) {
        const auto& result = warmed.evaluate(pose);
        REQUIRE(result.ok());
        warmed_forces.push_back(normal_force(result));
      }
    });
    CHECK(allocations == 0);
    CHECK(warmed_forces == fresh_forces);  // bit for bit
    CHECK(fresh_forces.front() > 0);
  }
}

TEST_CASE("Creep forces in the time loop allocate nothing per step after warm-up", "[sequence][allocation]") {
  namespace wr = fastnorm::wheelrail;
  const wr::Track track;
  const wr::Wheelset wheelset;
  // The first 60 ms of the trajectory benchmark, with its velocities.
  const auto poses = fastnorm_bench::trajectory_poses(track, wheelset, 60);
  const auto velocities = fastnorm_bench::trajectory_velocities(wheelset, poses);
  auto options = coarse_model("cg");
  options.creep.friction = 0.3;
  wr::WheelsetContact<> contact(track, wheelset, options);
  for (std::size_t step = 0; step < 20; ++step) contact.evaluate(poses[step], velocities[step]);
  double creep = 0;
  const long allocations = allocations_of([&] {
    for (std::size_t step = 20; step < poses.size(); ++step) {
      const auto& result = contact.evaluate(poses[step], velocities[step]);
      REQUIRE(result.ok());
      creep += std::abs(result.wheels[0].patches[0].traction.force_y);
    }
  });
  CHECK(creep > 0);
  CHECK(allocations == 0);
}

TEST_CASE("Steps cut short by an iteration budget allocate nothing either", "[sequence][allocation]") {
  // A budget makes cut solves routine (docs/wheel-rail.md §9): their answers' messages and
  // the step status naming them are written into storage the model keeps.
  namespace wr = fastnorm::wheelrail;
  const wr::Track track;
  const wr::Wheelset wheelset;
  const auto poses = fastnorm_bench::trajectory_poses(track, wheelset, 60);
  wr::WheelsetContact<> contact(track, wheelset, coarse_model("elliptic"));
  contact.set_iteration_budget(1);
  // A budgeted patch's sets differ from pass to pass (each step goes on from the last), so
  // its storage reaches its largest sizes later than a free model's: measured, 4
  // allocations in the third pass (assemblies larger than any before), none in the fifth.
  for (int pass = 0; pass < 4; ++pass) {
    for (const auto& pose : poses) contact.evaluate(pose);
  }
  int cut_steps = 0;
  const long allocations = allocations_of([&] {
    for (const auto& pose : poses) cut_steps += contact.evaluate(pose).ok() ? 0 : 1;
  });
  CHECK(cut_steps > 0);
  CHECK(allocations == 0);
}

TEST_CASE("Patches that appear, merge and vanish keep their storage: a repeated sweep allocates nothing",
          "[sequence][allocation]") {
  namespace wr = fastnorm::wheelrail;
  // A lateral sweep towards the flange and back on rails canted 1:20, where S1002 meets
  // UIC60 at two points from y ≈ 5.5 mm: the right wheel's flange-root patch appears beside
  // the tread patch, the two merge and split, and the count of patches rises and drops.
  wr::TrackLayout layout;
  layout.cant = 0.05;
  const wr::Track track(wr::uic60_rail(), layout);
  const wr::Wheelset wheelset;
  std::vector<wr::WheelsetPose> sweep;
  for (int k = 0; k <= 60; ++k) {
    const double y = 4e-3 + 3e-3 * (k <= 30 ? k : 60 - k) / 30.0;
    auto pose = wr::rigid_contact_pose(track, wheelset, y, 0);
    pose.z += 0.05e-3;
    sweep.push_back(pose);
  }
  wr::WheelsetContact<> contact(track, wheelset, coarse_model("cg"));
  std::vector<std::size_t> counts;
  for (const auto& pose : sweep) counts.push_back(contact.evaluate(pose).wheel(wr::Side::right).patches.size());
  int rises = 0, drops = 0;
  for (std::size_t k = 1; k < counts.size(); ++k) {
    rises += counts[k] > counts[k - 1];
    drops += counts[k] < counts[k - 1];
  }
  INFO("right wheel patch counts rose " << rises << " and dropped " << drops << " times");
  REQUIRE(rises >= 1);
  REQUIRE(drops >= 1);
  // A second pass meets the same grid sizes and patch counts, but may still add a spare to a
  // pool (its patches hand storage back in another order than the first pass built it:
  // measured, 2 allocations at one step); from the third pass on, nothing is allocated.
  for (const auto& pose : sweep) contact.evaluate(pose);
  std::size_t again = 0;
  const long allocations = allocations_of([&] {
    for (const auto& pose : sweep) {
      const auto& result = contact.evaluate(pose);
      REQUIRE(result.ok());
      again += result.wheel(wr::Side::right).patches.size();
    }
  });
  CHECK(again == std::accumulate(counts.begin(), counts.end(), std::size_t{0}));
  CHECK(allocations == 0);
}

TEST_CASE("The search's regions keep room for every sample: a longer region allocates nothing",
          "[sequence][allocation]") {
  // contact_regions gives a region slot room for all the sampler's samples when it is first
  // used (docs/wheel-rail.md §9, "Warming up"): after a shallow pose, a pose pressed three
  // times deeper, whose region holds more than twice the samples (more than a vector grown
  // by doubling would have room for), grows nothing.
  namespace wr = fastnorm::wheelrail;
  const wr::Track track;
  const wr::Wheelset wheelset;
  const wr::SearchOptions search;
  wr::GapSampler sampler;
  std::vector<wr::ContactRegion> regions;
  const auto pressed = [&](double depth) {
    auto pose = wr::rigid_contact_pose(track, wheelset, 1e-3, 0);
    pose.z += depth;
    return pose;
  };
  const wr::WheelsetPose shallow = pressed(0.02e-3), deep = pressed(0.06e-3);
  // The sampler meets both poses first, with regions of its own (its storage is not under
  // test); the slot under test is then first used by the shallow pose alone.
  {
    std::vector<wr::ContactRegion> met;
    for (const auto& pose : {shallow, deep}) {
      wr::contact_regions(track, wheelset, wr::Side::right, pose, search, sampler, met);
    }
  }
  REQUIRE(wr::contact_regions(track, wheelset, wr::Side::right, shallow, search, sampler, regions) == 1);
  const std::size_t shallow_slices = regions[0].slices.size();
  std::size_t count = 0;
  const long allocations = allocations_of(
      [&] { count = wr::contact_regions(track, wheelset, wr::Side::right, deep, search, sampler, regions); });
  REQUIRE(count == 1);
  INFO("slices: shallow " << shallow_slices << ", deep " << regions[0].slices.size());
  CHECK(regions[0].slices.size() > 2 * shallow_slices);
  CHECK(allocations == 0);
}

TEST_CASE("Trial steps restored allocate nothing after warm-up: no storage piles up", "[sequence][allocation]") {
  // An integrator's trial steps (docs/wheel-rail.md §9): at every step the history taken
  // into one History kept from step to step, a trial pose evaluated, the history restored,
  // the step evaluated. Until 2026-12-04 every restore handed the patches' workspaces to
  // their solvers' spares and cloned the saved ones: the spares grew by a few workspaces a
  // step (1.8 GB after 350 steps of the benchmark trajectory, 60 elements).
  namespace wr = fastnorm::wheelrail;
  const wr::Track track;
  const wr::Wheelset wheelset;
  const auto poses = fastnorm_bench::trajectory_poses(track, wheelset, 60);
  for (const char* solver : {"elliptic", "cg"}) {
    INFO(solver);
    wr::WheelsetContact<> contact(track, wheelset, coarse_model(solver));
    wr::WheelsetContact<>::History saved;
    double force = 0;
    const auto steps = [&] {
      for (const auto& pose : poses) {
        contact.history(saved);
        auto trial = pose;  // another box for some patches
        trial.y += 0.3e-3;
        trial.z += 0.02e-3;
        contact.evaluate(trial);
        contact.restore(saved);
        const auto& result = contact.evaluate(pose);
        REQUIRE(result.ok());
        force += result.wheels[0].normal_force + result.wheels[1].normal_force;
      }
    };
    // The model and the History meet their largest sizes over the first passes (measured,
    // elliptic: 60 allocations in the second pass, 1 in the third, none from the fourth).
    for (int pass = 0; pass < 3; ++pass) steps();
    CHECK(allocations_of(steps) == 0);
    CHECK(force > 0);
  }
}

#else

TEST_CASE("Solvers in a repeated sequence allocate only their results", "[sequence][allocation]") {
  WARN("allocation counting needs the GNU linker's --wrap; not counted in this build");
}

#endif
