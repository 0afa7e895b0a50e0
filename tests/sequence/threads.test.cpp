// `solve(h, loading)` is const and thread-safe (docs/architecture.md §2): threads sharing
// one solver object get the answers of one call after another, bit for bit; so do copies of
// a wheelset model, which share their solvers' tables. CI also runs this under
// ThreadSanitizer (.ci/run), which reports any unsynchronised access.
#include <catch2/catch.hpp>
#include <fastnorm/any_solver.hpp>
#include <fastnorm/hertz.hpp>
#include <fastnorm/wheelrail.hpp>

#include <cstddef>
#include <thread>
#include <vector>

#include "support/surfaces.hpp"
#include "support/wheelrail_cases.hpp"

TEST_CASE("Threads sharing one solver get the answers of serial calls", "[sequence][threads]") {
  using fastnorm::test::steel;
  const auto hertz = fastnorm::hertz_from_force(0.3, 0.2, steel.combined_modulus(), 5e4);
  const auto grid = fastnorm::hertz_grid(hertz, 16, 1.4);
  std::vector<Eigen::VectorXd> problems;
  for (int n = 0; n < 8; ++n) {  // tilted indenters of different depths
    Eigen::VectorXd h = fastnorm::hertz_undeformed_distance(grid, 0.3, 0.2);
    for (Eigen::Index k = 0; k < grid.size(); ++k) h(k) += 2e-4 * n * grid.y_of(k) - 2e-6 * (n % 3);
    problems.push_back(h);
  }
  const std::size_t thread_count = 4;
  for (const char* name : {"norm", "cg", "elliptic", "polynomial-edge:4:1"}) {
    const fastnorm::AnySolver<> solver(name, grid, steel);
    for (const auto loading : {fastnorm::Loading<>::approach(), fastnorm::Loading<>::force(5e4)}) {
      std::vector<fastnorm::Solution<>> serial;
      for (const auto& h : problems) serial.push_back(solver.solve(h, loading));
      // Every thread solves every problem, starting at a different one.
      std::vector<std::vector<fastnorm::Solution<>>> parallel(thread_count);
      std::vector<std::thread> threads;
      for (std::size_t t = 0; t < thread_count; ++t) {
        threads.emplace_back([&, t] {
          for (std::size_t n = 0; n < problems.size(); ++n) {
            parallel[t].push_back(solver.solve(problems[(n + t) % problems.size()], loading));
          }
        });
      }
      for (auto& thread : threads) thread.join();
      for (std::size_t t = 0; t < thread_count; ++t) {
        for (std::size_t n = 0; n < problems.size(); ++n) {
          const auto& expected = serial[(n + t) % problems.size()];
          const auto& got = parallel[t][n];
          INFO(name << ", thread " << t << ", problem " << (n + t) % problems.size());
          REQUIRE(got.status == expected.status);
          CHECK(got.pressure == expected.pressure);
          CHECK(got.approach == expected.approach);
          CHECK(got.iterations == expected.iterations);
        }
      }
    }
  }
}

// Copies of one wheelset model share its solvers' tables (docs/wheel-rail.md §9, "Models of
// a vehicle"): each stepped on a thread of its own answers as a copy stepped alone.
TEST_CASE("Copies of a wheelset model on threads of their own answer as serial steps", "[sequence][threads]") {
  namespace wr = fastnorm::wheelrail;
  const wr::WheelsetContact<> original(wr::Track(), wr::Wheelset(), fastnorm::test::coarse_contact("elliptic", 16));
  std::vector<wr::WheelsetPose> poses;
  for (const double y : {-4e-3, -1e-3, 0.0, 2e-3, 4e-3, 4.4e-3}) {
    auto pose = wr::rigid_contact_pose(original.track(), original.wheelset(), y, 1e-3);
    pose.z += 0.1e-3;
    poses.push_back(pose);
  }
  std::vector<Eigen::Vector3d> serial;
  {
    auto alone = original;
    for (const auto& pose : poses) serial.push_back(alone.evaluate(pose).force);
  }
  const std::size_t thread_count = 3;
  std::vector<wr::WheelsetContact<>> copies(thread_count, original);
  std::vector<std::vector<Eigen::Vector3d>> parallel(thread_count);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < thread_count; ++t) {
    threads.emplace_back([&, t] {
      for (const auto& pose : poses) parallel[t].push_back(copies[t].evaluate(pose).force);
    });
  }
  for (auto& thread : threads) thread.join();
  for (std::size_t t = 0; t < thread_count; ++t) {
    INFO("thread " << t);
    CHECK(parallel[t] == serial);
  }
}
