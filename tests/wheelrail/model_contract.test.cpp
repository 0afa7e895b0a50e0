// The wheel–rail model as a library type (issue 31): a real solver parameter (every solver
// type instantiates the model and the equilibrium, and gives AnySolver's answer bit for
// bit), ownership that cannot dangle (the model owns its track and wheelset; the contact
// search knows a track by its id, not its address), and a step status that names the
// wheel and patch that failed.
#include <catch2/catch.hpp>
#include <fastnorm/fastnorm.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "support/wheelrail_cases.hpp"

namespace wr = fastnorm::wheelrail;
using Catch::Matchers::Contains;

namespace {

// The options of the models here, on 20 elements a patch: the tests build many models.
wr::WheelsetContactOptions model_options(const char* solver) { return fastnorm::test::coarse_contact(solver, 20); }

// Both wheels at y = 4 mm pressed 0.1 mm into their rails: a tread and a flange-root patch.
wr::WheelsetPose pressed_pose() {
  auto pose = wr::rigid_contact_pose(wr::Track(), wr::Wheelset(), 4e-3, 2e-3);
  pose.z += 0.1e-3;
  return pose;
}

// Whether a patch solve of `step` stopped at its iteration limit or cap.
bool any_stopped_early(const wr::WheelsetContactResult& step) {
  for (const auto& wheel : step.wheels) {
    for (const auto& patch : wheel.patches) {
      if (patch.solution.stopped_early()) return true;
    }
  }
  return false;
}

// Every patch of `got` ends as the same patch of `expected`: status, contact set and force
// to round-off (a kept factor updated rather than computed afresh; check_same_patches below
// is bit for bit).
void check_same_sets(const wr::WheelsetContactResult& got, const wr::WheelsetContactResult& expected) {
  for (std::size_t w = 0; w < 2; ++w) {
    REQUIRE(got.wheels[w].patches.size() == expected.wheels[w].patches.size());
    for (std::size_t k = 0; k < got.wheels[w].patches.size(); ++k) {
      const auto& a = got.wheels[w].patches[k].solution, &b = expected.wheels[w].patches[k].solution;
      CHECK(a.status == b.status);
      CHECK((a.in_contact == b.in_contact).all());
      CHECK(a.normal_force == Approx(b.normal_force).epsilon(1e-12));
    }
  }
}

// Σ N cos δ over `patches`, added to `vertical`: the vertical force the rails carry (N), as
// the equilibrium sums it.
double vertical_force(const std::vector<wr::PatchContact>& patches, double vertical = 0) {
  for (const auto& patch : patches) vertical += patch.normal_force * std::cos(patch.patch.frame.inclination);
  return vertical;
}

double vertical_force(const wr::WheelsetContactResult& result) {
  return vertical_force(result.wheels[1].patches, vertical_force(result.wheels[0].patches));
}

void check_same_patches(const wr::WheelsetContactResult& named, const wr::WheelsetContactResult& any) {
  for (std::size_t w = 0; w < 2; ++w) {
    REQUIRE(named.wheels[w].patches.size() == any.wheels[w].patches.size());
    for (std::size_t k = 0; k < named.wheels[w].patches.size(); ++k) {
      const auto& a = named.wheels[w].patches[k];
      const auto& b = any.wheels[w].patches[k];
      CHECK(a.solution.status == b.solution.status);
      CHECK(a.solution.pressure == b.solution.pressure);  // bit for bit: the same code runs
      CHECK(a.normal_force == b.normal_force);
      CHECK(a.stiffness == b.stiffness);
    }
  }
  CHECK(named.force == any.force);
}

// A model and an equilibrium of solver type `Solver` against AnySolver of the same spec.
template <typename Solver>
void check_solver_type(const char* name) {
  INFO(name);
  const wr::Track track;
  const wr::Wheelset wheelset;
  const auto options = model_options(name);
  wr::WheelsetContact<Solver> named(track, wheelset, options);
  wr::WheelsetContact<> any(track, wheelset, options);
  const auto pose = pressed_pose();
  const auto& named_result = named.evaluate(pose);
  const auto& any_result = any.evaluate(pose);
  REQUIRE(named_result.ok());
  REQUIRE(named_result.wheel(wr::Side::right).patches.size() >= 1);
  check_same_patches(named_result, any_result);

  wr::EquilibriumOptions equilibrium_options;
  equilibrium_options.contact = options;
  const auto named_equilibrium = wr::solve_equilibrium<Solver>(track, wheelset, 3e-3, 0, 2e5, equilibrium_options);
  const auto any_equilibrium = wr::solve_equilibrium(track, wheelset, 3e-3, 0, 2e5, equilibrium_options);
  REQUIRE(named_equilibrium.ok());
  CHECK(named_equilibrium.pose.z == any_equilibrium.pose.z);
  CHECK(named_equilibrium.pose.roll == any_equilibrium.pose.roll);
  CHECK(named_equilibrium.iterations == any_equilibrium.iterations);
}

}  // namespace

TEST_CASE("Every solver type instantiates the model and the equilibrium, with AnySolver's answers",
          "[wheelrail][model]") {
  check_solver_type<fastnorm::NormSolver<>>("norm");
  check_solver_type<fastnorm::CgSolver<>>("cg");
  check_solver_type<fastnorm::ReducedSolver<fastnorm::EllipticBasis>>("elliptic");
  check_solver_type<fastnorm::ReducedSolver<fastnorm::PolynomialBasis>>("polynomial:3");
  check_solver_type<fastnorm::ReducedSolver<fastnorm::EllipticEdgeBasis>>("elliptic-edge:1");
  check_solver_type<fastnorm::ReducedSolver<fastnorm::PolynomialEdgeBasis>>("polynomial-edge:4:2");
}

TEST_CASE("A solver spec of another kind than the model's solver type is refused by name", "[wheelrail][model]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  using Norm = fastnorm::NormSolver<>;
  using Elliptic = fastnorm::ReducedSolver<fastnorm::EllipticBasis>;
  CHECK_THROWS_WITH(wr::WheelsetContact<Norm>(track, wheelset, model_options("cg")),
                    Contains("WheelsetContactOptions: solver is 'cg'"));
  CHECK_THROWS_WITH(wr::WheelsetContact<Elliptic>(track, wheelset, model_options("polynomial")),
                    Contains("WheelsetContactOptions: solver is 'polynomial:4'"));
  wr::EquilibriumOptions options;
  options.contact = model_options("elliptic");
  CHECK_THROWS_WITH(wr::solve_equilibrium<Norm>(track, wheelset, 0, 0, 2e5, options),
                    Contains("EquilibriumOptions: contact.solver is 'elliptic'"));
  CHECK_THROWS_WITH(fastnorm::make_solver<Norm>(fastnorm::SolverSpec<>::parse("cg"),
                                                fastnorm::Grid<>(4, 4, 1e-3, 1e-3), fastnorm::Material<>::steel()),
                    Contains("solver spec is 'cg'"));
}

TEST_CASE("The model owns its track and wheelset: built from temporaries, moved, it evaluates alike",
          "[wheelrail][model]") {
  const auto pose = pressed_pose();
  // Temporaries: with references kept, this evaluate would read freed objects (ASan in CI).
  wr::WheelsetContact<fastnorm::NormSolver<>> from_temporaries{wr::Track(), wr::Wheelset(), model_options("norm")};
  const wr::Track track;
  const wr::Wheelset wheelset;
  wr::WheelsetContact<fastnorm::NormSolver<>> reference(track, wheelset, model_options("norm"));
  const auto expected = reference.evaluate(pose);
  check_same_patches(from_temporaries.evaluate(pose), expected);
  // A moved model goes on from where it was: its search continues, its answers are the same.
  auto moved = std::move(from_temporaries);
  check_same_patches(moved.evaluate(pose), reference.evaluate(pose));
}

TEST_CASE("The contact search knows a track by its id, not by its address", "[wheelrail][model]") {
  const wr::Wheelset wheelset;
  const wr::SearchOptions search;
  const wr::Track standard;
  wr::TrackLayout wide;
  wide.gauge = 1.445;
  const wr::Track other(wr::uic60_rail(), wide);
  CHECK(standard.id() != other.id());
  CHECK(wr::Track(standard).id() == standard.id());  // a copy is the same track
  // One storage, two tracks in turn: the same address, different ids.
  std::optional<wr::Track> storage;
  storage.emplace(standard);
  const wr::Track* first = &*storage;
  auto pose = wr::rigid_contact_pose(standard, wheelset, 2e-3, 0, search);
  pose.z += 0.1e-3;
  wr::GapSampler continued;
  std::vector<wr::ContactRegion> regions;
  wr::contact_regions(*storage, wheelset, wr::Side::right, pose, search, continued, regions);
  storage.emplace(other);
  REQUIRE(&*storage == first);
  const std::size_t count = wr::contact_regions(*storage, wheelset, wr::Side::right, pose, search, continued, regions);
  const auto fresh = wr::contact_regions(other, wheelset, wr::Side::right, pose, search);
  REQUIRE(count == fresh.size());
  for (std::size_t k = 0; k < count; ++k) {
    CHECK(regions[k].centre == fresh[k].centre);
    CHECK(regions[k].slices.size() == fresh[k].slices.size());
  }
}

TEST_CASE("The equilibrium of a given model is that model's own", "[wheelrail][model]") {
  wr::WheelsetContact<fastnorm::NormSolver<>> model(wr::Track(), wr::Wheelset(), model_options("norm"));
  const double load = 2e5;
  const auto found = wr::solve_equilibrium(model, 3e-3, 1e-3, load);
  REQUIRE(found.ok());
  // The model's element sizes, not sizes chosen at the pose: the patches are on its lattice.
  for (const auto& patch : found.patches) {
    CHECK(patch.patch.grid.dx() == model.element_length());
    CHECK(patch.patch.grid.dy() == model.element_width());
  }
  // Evaluated again at the pose found, the model carries the load to the force tolerance.
  const auto& again = model.evaluate(found.pose);
  REQUIRE(again.ok());
  const double vertical = vertical_force(again);
  CHECK(std::abs(vertical - load) <= wr::EquilibriumOptions().force_tolerance * load);
  // A model without stiffness cannot drive Newton.
  auto options = model_options("norm");
  options.stiffness = false;
  wr::WheelsetContact<fastnorm::NormSolver<>> stiff_less(wr::Track(), wr::Wheelset(), options);
  CHECK_THROWS_WITH(wr::solve_equilibrium(stiff_less, 3e-3, 0, load), Contains("stiffness must be on"));
  // A model whose solves stop short (a cap, a budget) has them lifted for the search, whose
  // Newton needs converged forces, and put back after: the equilibrium is the free model's.
  auto capped_options = model_options("elliptic");
  capped_options.warm_solve_iterations = 1;
  wr::WheelsetContact<> capped(wr::Track(), wr::Wheelset(), capped_options);
  capped.set_iteration_budget(2);
  wr::WheelsetContact<> free_model(wr::Track(), wr::Wheelset(), model_options("elliptic"));
  const auto capped_found = wr::solve_equilibrium(capped, 3e-3, 0, load);
  const auto free_found = wr::solve_equilibrium(free_model, 3e-3, 0, load);
  REQUIRE(free_found.ok());
  CHECK(capped_found.ok());
  CHECK(capped_found.pose.z == free_found.pose.z);
  CHECK(capped_found.pose.roll == free_found.pose.roll);
  CHECK(capped.options().warm_solve_iterations == 1);
  CHECK(capped.iteration_budget() == 2);
  CHECK_THROWS_WITH(capped.set_warm_solve_iterations(-1), Contains("iterations must be >= 0"));
  // The search's own models take no cap.
  wr::EquilibriumOptions capped_search;
  capped_search.contact.warm_solve_iterations = 2;
  CHECK_THROWS_WITH(wr::solve_equilibrium(wr::Track(), wr::Wheelset(), 3e-3, 0, load, capped_search),
                    Contains("contact.warm_solve_iterations must be 0"));
}

TEST_CASE("The step status names the wheel and patch that failed, and why", "[wheelrail][model]") {
  CHECK(wr::StepStatus().code == wr::StepStatus::Code::not_solved);
  CHECK_FALSE(wr::WheelsetContactResult().ok());
  const auto pose = pressed_pose();
  wr::WheelsetContact<> good(wr::Track(), wr::Wheelset(), model_options("norm"));
  const auto& fine = good.evaluate(pose);
  CHECK(fine.ok());
  CHECK(fine.status.patch == -1);
  CHECK(fine.status.message.empty());
  // One active-set iteration cannot reach NORM's contact set: every patch ends at the
  // iteration limit, and the first failure is the left wheel's first patch.
  auto options = model_options("norm");
  options.solver.active_set.max_iterations = 1;
  wr::WheelsetContact<fastnorm::NormSolver<>> starved(wr::Track(), wr::Wheelset(), options);
  const auto& result = starved.evaluate(pose);
  REQUIRE_FALSE(result.ok());
  CHECK(result.status.code == wr::StepStatus::Code::patch_failed);
  CHECK(result.status.side == wr::Side::left);
  CHECK(result.status.patch == 0);
  CHECK(result.status.solver_status == fastnorm::Status::iteration_limit);
  CHECK_THAT(result.status.message, Contains("left wheel, patch 0 of") && Contains("iteration limit"));
  CHECK(result.wheel(wr::Side::right).status.side == wr::Side::right);
  CHECK_FALSE(result.wheel(wr::Side::right).ok());
  // The single-wheel mode reports its wheel's status.
  CHECK(starved.evaluate(pose, wr::Side::right).status.side == wr::Side::right);
}

TEST_CASE("A step spends at most its iteration budget, and reports what it spent", "[wheelrail][model]") {
  // issue 27 item 6 (qpOASES' nWSR): the budget is shared by the step's patch solves in
  // order; an ample one changes nothing, a tight one ends solves at the iteration limit.
  const auto pose = pressed_pose();
  for (const char* name : {"norm", "cg", "elliptic"}) {
    INFO(name);
    wr::WheelsetContact<> free_model(wr::Track(), wr::Wheelset(), model_options(name));
    wr::WheelsetContact<> ample(wr::Track(), wr::Wheelset(), model_options(name));
    ample.set_iteration_budget(100000);
    CHECK(ample.iteration_budget() == 100000);
    for (int step = 0; step < 3; ++step) {
      auto moved = pose;
      moved.y += 20e-6 * step;
      const auto& expected = free_model.evaluate(moved);
      const auto& got = ample.evaluate(moved);
      REQUIRE(got.ok());
      int spent = 0, patches = 0;
      for (std::size_t w = 0; w < 2; ++w) {
        int wheel_spent = 0;
        REQUIRE(got.wheels[w].patches.size() == expected.wheels[w].patches.size());
        for (std::size_t k = 0; k < got.wheels[w].patches.size(); ++k) {
          CHECK(got.wheels[w].patches[k].solution.pressure == expected.wheels[w].patches[k].solution.pressure);
          wheel_spent += got.wheels[w].patches[k].solution.iterations;
          ++patches;
        }
        CHECK(got.wheels[w].iterations == wheel_spent);
        spent += wheel_spent;
      }
      CHECK(got.iterations == spent);
      CHECK(spent >= patches);
    }
  }
  // Cold, an elliptic solve needs more than one set here; a budget of 1 gives every patch
  // solve a single iteration. A stop at an iterate whose pressures are all positive is the
  // budget's (budget_reached, usable); one after a drop, before any such iterate, is a
  // failure (iteration_limit), and the step status names the first.
  wr::WheelsetContact<> tight(wr::Track(), wr::Wheelset(), model_options("elliptic"));
  tight.set_iteration_budget(1);
  const auto& result = tight.evaluate(pose);
  int patches = 0;
  std::optional<std::pair<wr::Side, int>> first_failed;
  for (std::size_t w = 0; w < 2; ++w) {
    for (std::size_t k = 0; k < result.wheels[w].patches.size(); ++k, ++patches) {
      const auto& solution = result.wheels[w].patches[k].solution;
      CHECK(solution.iterations == 1);
      CHECK(solution.stopped_early());
      if (!first_failed && !solution.ok()) first_failed = std::make_pair(result.wheels[w].side, static_cast<int>(k));
      if (solution.status == fastnorm::Status::budget_reached) {
        CHECK(result.wheels[w].patches[k].normal_force > 0);
        CHECK(std::isfinite(result.wheels[w].patches[k].stiffness));  // usable: stiffness as for any answer
      }
    }
  }
  CHECK(result.iterations == patches);
  CHECK(result.ok() == !first_failed.has_value());
  if (first_failed) {
    CHECK(result.status.code == wr::StepStatus::Code::patch_failed);
    CHECK(result.status.side == first_failed->first);
    CHECK(result.status.patch == first_failed->second);
    CHECK(result.status.solver_status == fastnorm::Status::iteration_limit);
  }
  // A budgeted patch goes on from where its loop stopped (the joins it found included),
  // so that at a pose held fixed the budgeted model reaches the free model's answer within
  // a few steps; it would repeat its one set forever if it started each step from its answer.
  wr::WheelsetContact<> free_model(wr::Track(), wr::Wheelset(), model_options("elliptic"));
  const auto& free_result = free_model.evaluate(pose);
  REQUIRE(free_result.ok());
  int free_iterations = 0;
  for (const auto& wheel : free_result.wheels) {
    for (const auto& patch : wheel.patches) free_iterations = std::max(free_iterations, patch.solution.iterations);
  }
  for (int step = 1; step < 4 * free_iterations && any_stopped_early(tight.evaluate(pose)); ++step) {
  }
  const auto& settled = tight.evaluate(pose);
  REQUIRE(settled.ok());
  REQUIRE_FALSE(any_stopped_early(settled));
  check_same_sets(settled, free_result);
  // The budget is the next step's too; 0 lifts it.
  tight.set_iteration_budget(0);
  CHECK(tight.evaluate(pose).ok());
  CHECK_THROWS_WITH(tight.set_iteration_budget(-1), Contains("iterations must be >= 0"));
}

TEST_CASE("A per-solve cap bounds warm solves only, and a capped model follows NORM within its basis",
          "[wheelrail][model]") {
  // WheelsetContactOptions::warm_solve_iterations: the first evaluate is cold and runs to
  // convergence (the free model's answer); later, warm solves stop after the cap at their
  // first settled iterate (budget_reached: pressures all positive, gaps violated by at most
  // IterationStop::settled_residual of the deepest interpenetration), so every step is
  // usable and none trails a jump; held at a pose, the model converges there, as near NORM
  // as the free model or a cold one (a reduced basis's final set depends on the path of its
  // sets, so not always the free model's set to the bit).
  const auto pose = pressed_pose();
  auto options = model_options("elliptic");
  options.warm_solve_iterations = 1;
  wr::WheelsetContact<> capped(wr::Track(), wr::Wheelset(), options);
  wr::WheelsetContact<> free_model(wr::Track(), wr::Wheelset(), model_options("elliptic"));
  wr::WheelsetContact<> norm(wr::Track(), wr::Wheelset(), model_options("norm"));  // the same grids
  // Both models' answers converged, and the same.
  const auto same_answers = [](const wr::WheelsetContactResult& got, const wr::WheelsetContactResult& expected) {
    for (const auto& wheel : expected.wheels) {
      for (const auto& patch : wheel.patches) CHECK(patch.solution.status == fastnorm::Status::converged);
    }
    check_same_sets(got, expected);
  };
  // Every answer usable; one stopped at the cap is settled. Whether any patch stopped.
  const auto usable_and_settled = [](const wr::WheelsetContactResult& result) {
    REQUIRE(result.ok());
    bool any_stopped = false;
    for (const auto& wheel : result.wheels) {
      for (const auto& patch : wheel.patches) {
        const auto status = patch.solution.status;
        CHECK((status == fastnorm::Status::budget_reached || status == fastnorm::Status::converged));
        CHECK(std::isfinite(patch.stiffness));
        if (status == fastnorm::Status::budget_reached) {
          CHECK(patch.solution.residual <= fastnorm::IterationStop::settled_residual);
          any_stopped = true;
        }
      }
    }
    return any_stopped;
  };
  const auto& first = capped.evaluate(pose);
  REQUIRE(first.ok());
  same_answers(first, free_model.evaluate(pose));
  // Steps of 20 µm (a fraction of an element): the sets move a little, and solves stop at
  // the cap; then a jump of several elements, which no solve may leave unsettled.
  auto moved = pose;
  int stopped = 0;
  for (int step = 0; step < 30; ++step) {
    moved.y += 20e-6;
    stopped += usable_and_settled(capped.evaluate(moved)) ? 1 : 0;
    norm.evaluate(moved);
    free_model.evaluate(moved);
  }
  CHECK(stopped > 0);
  moved.y += 0.3e-3;
  usable_and_settled(capped.evaluate(moved));
  // Held at the last pose, the model settles: once no solve stops at the cap, the next step
  // is converged (one iteration: the set holds), and no farther from NORM than the free
  // model along the same poses or a cold one (item 4's rule of issue 27, at one pose).
  for (int step = 0; step < 30 && usable_and_settled(capped.evaluate(moved)); ++step) {
  }
  const auto& held = capped.evaluate(moved);
  const auto& reference = norm.evaluate(moved);
  const auto& free_result = free_model.evaluate(moved);
  wr::WheelsetContact<> cold_model(wr::Track(), wr::Wheelset(), model_options("elliptic"));
  const auto& cold = cold_model.evaluate(moved);
  for (std::size_t w = 0; w < 2; ++w) {
    REQUIRE(held.wheels[w].patches.size() == reference.wheels[w].patches.size());
    for (std::size_t k = 0; k < held.wheels[w].patches.size(); ++k) {
      const auto error = [&](const wr::WheelsetContactResult& result) {
        return std::abs(result.wheels[w].patches[k].solution.normal_force /
                            reference.wheels[w].patches[k].solution.normal_force - 1);
      };
      CHECK(held.wheels[w].patches[k].solution.status == fastnorm::Status::converged);
      CHECK(error(held) <= std::max(error(free_result), error(cold)) + 1e-12);
    }
  }
  options.warm_solve_iterations = -1;
  CHECK_THROWS_WITH(wr::WheelsetContact<>(wr::Track(), wr::Wheelset(), options), Contains("warm_solve_iterations"));
}

namespace {

// Along a short trajectory, trial steps evaluated, the history restored after each and the
// step evaluated again: bit for bit the answer of a model that never saw the trials. As a
// Runge–Kutta integrator takes them: one History kept from step to step (history(saved)),
// three trials a step, far off (new boxes, another patch count) and near; the restored
// model's spare workspaces are then not the untried model's, which no answer may show.
template <typename Solver>
void check_trial_steps(const char* name) {
  INFO(name);
  const auto options = model_options(name);
  wr::WheelsetContact<Solver> model(wr::Track(), wr::Wheelset(), options);
  wr::WheelsetContact<Solver> untried(wr::Track(), wr::Wheelset(), options);
  typename wr::WheelsetContact<Solver>::History saved;
  const auto base = pressed_pose();
  for (int step = 0; step < 8; ++step) {
    wr::WheelsetPose pose = base;
    pose.y += 0.4e-3 * step;  // more than an element per step: new boxes and shifted sets
    pose.yaw += 1e-3 * step;
    model.history(saved);
    for (const auto& [shift, lift] : {std::pair{1.5e-3, -0.05e-3}, std::pair{0.1e-3, 0.01e-3}, std::pair{-2.5e-3, 0.0}}) {
      wr::WheelsetPose trial = pose;  // a rejected trial
      trial.y += shift;
      trial.z -= lift;
      model.evaluate(trial);
      model.restore(saved);
    }
    check_same_patches(model.evaluate(pose), untried.evaluate(pose));
  }
  // history() by value is the same history.
  const auto copy = model.history();
  wr::WheelsetPose trial = base;
  trial.y -= 1e-3;
  model.evaluate(trial);
  model.restore(copy);
  check_same_patches(model.evaluate(base), untried.evaluate(base));
  // Another model's history, on other element sizes, is refused and changes nothing.
  auto other_options = options;
  other_options.grid.elements = 16;
  wr::WheelsetContact<Solver> other(wr::Track(), wr::Wheelset(), other_options);
  other.evaluate(base);
  CHECK_THROWS_WITH(model.restore(other.history()), Contains("another model's"));
  check_same_patches(model.evaluate(trial), untried.evaluate(trial));
}

}  // namespace

TEST_CASE("Trial steps restored leave no trace: the step again is bit for bit the untried model's",
          "[wheelrail][model]") {
  check_trial_steps<fastnorm::NormSolver<>>("norm");
  check_trial_steps<fastnorm::CgSolver<>>("cg");
  check_trial_steps<fastnorm::ReducedSolver<fastnorm::EllipticBasis>>("elliptic");
  check_trial_steps<fastnorm::ReducedSolver<fastnorm::PolynomialEdgeBasis>>("polynomial-edge:4:1");
  check_trial_steps<fastnorm::AnySolver<>>("polynomial:4");
}

namespace {

// After evaluations elsewhere and reset(), a pose gives bit for bit a new model's answer: no
// contact set, search or kept assembly of the earlier poses leaks through (a contact
// table's cases, computed in any order, rely on it: docs/tables.md §2).
template <typename Solver>
void check_reset_forgets(const char* name) {
  INFO(name);
  const auto options = model_options(name);
  const auto pose = pressed_pose();
  wr::WheelsetContact<Solver> fresh(wr::Track(), wr::Wheelset(), options);
  wr::WheelsetContact<Solver> model(wr::Track(), wr::Wheelset(), options);
  for (double shift : {-3e-3, 3.6e-3, 3.9e-3, 4.1e-3, 5e-3}) {  // other sizes, near sets, a flange
    auto other = pose;
    other.y = shift;
    model.evaluate(other);
    model.reset();
    check_same_patches(model.evaluate(pose), fresh.evaluate(pose));
    fresh.reset();
  }
}

}  // namespace

TEST_CASE("reset() forgets: a pose after other poses and a reset is bit for bit a new model's", "[wheelrail][model]") {
  check_reset_forgets<fastnorm::NormSolver<>>("norm");
  check_reset_forgets<fastnorm::ReducedSolver<fastnorm::EllipticBasis>>("elliptic");
  check_reset_forgets<fastnorm::ReducedSolver<fastnorm::PolynomialEdgeBasis>>("polynomial-edge:4:1");
  check_reset_forgets<fastnorm::AnySolver<>>("polynomial:4");
}

namespace {

// The solvers of every box size share one set of segment tables (docs/wheel-rail.md §9):
// their answers are bit for bit those of solvers with tables of their own (a shared table
// box smaller than any box), along poses that meet several box sizes. The shared solvers
// are all built with the model, those of every lattice box size up to the table box, so
// that no step builds one.
template <typename Solver>
void check_shared_tables(const char* name) {
  INFO(name);
  auto options = model_options(name);
  CHECK(options.table_box() == 32);  // the default: 1.5 × 20 elements, rounded up to 8
  options.shared_table_box = 48;     // holds every box of the poses below
  wr::WheelsetContact<Solver> shared(wr::Track(), wr::Wheelset(), options);
  options.shared_table_box = 8;  // no box fits: tables per box size, as before sharing
  wr::WheelsetContact<Solver> own(wr::Track(), wr::Wheelset(), options);
  const bool reduced = fastnorm::SolverSpec<>::parse(name).is_reduced();
  CHECK(shared.solver_count() == (reduced ? 36 : 0));  // sides 8, 16, …, 48 either way
  CHECK(own.solver_count() == (reduced ? 1 : 0));      // the 8 × 8 box
  auto pose = pressed_pose();
  for (double shift : {0.0, -3e-3, 3.6e-3, 3.9e-3, 4.1e-3, 5e-3, 1e-3}) {
    pose.y = shift;
    check_same_patches(shared.evaluate(pose), own.evaluate(pose));
  }
  CHECK(own.solver_count() >= 3);  // built as the steps met their box sizes
  // The reduced kinds' steps built none (NORM's were built as met, one per size).
  CHECK(shared.solver_count() == (reduced ? 36 : own.solver_count()));
  // Built with the model when they fit the budget together (every reduced kind's do on a
  // 32-element box; NORM has none).
  CHECK(shared.tables_built() == fastnorm::SolverSpec<>::parse(name).is_reduced());
}

}  // namespace

TEST_CASE("Solvers of all box sizes share the segment tables, with the answers of tables per box",
          "[wheelrail][model]") {
  check_shared_tables<fastnorm::ReducedSolver<fastnorm::EllipticBasis>>("elliptic");
  check_shared_tables<fastnorm::ReducedSolver<fastnorm::PolynomialEdgeBasis>>("polynomial-edge:4:1");
  check_shared_tables<fastnorm::AnySolver<>>("polynomial:4");
  check_shared_tables<fastnorm::NormSolver<>>("norm");  // no segment tables: the option changes nothing

  auto options = model_options("elliptic");
  options.shared_table_box = -1;
  CHECK_THROWS_WITH(wr::WheelsetContact<>(wr::Track(), wr::Wheelset(), options),
                    Catch::Matchers::Contains("shared_table_box"));
}

namespace {

// A copy of a model is a model of its own that shares its solvers' read-only tables
// (docs/wheel-rail.md §9, "Models of a vehicle"): a copy of a fresh model, stepped in turn
// with its original and with a model built on its own, answers bit for bit as both (nothing
// one of them keeps reaches the others), and a copy made mid-run goes on as the original.
template <typename Solver>
void check_copies(const char* name) {
  INFO(name);
  const auto options = model_options(name);
  wr::WheelsetContact<Solver> original(wr::Track(), wr::Wheelset(), options);
  wr::WheelsetContact<Solver> copy = original;
  wr::WheelsetContact<Solver> own(wr::Track(), wr::Wheelset(), options);
  CHECK(copy.solver_count() == original.solver_count());
  CHECK(copy.tables_built() == original.tables_built());
  auto pose = pressed_pose();
  for (double shift : {0.0, 1e-3, 3.6e-3, 3.9e-3, 4.1e-3, 5e-3, -3e-3}) {  // sizes, sets, a flange
    pose.y = shift;
    const wr::WheelsetContactResult expected = own.evaluate(pose);
    check_same_patches(original.evaluate(pose), expected);
    check_same_patches(copy.evaluate(pose), expected);
  }
  wr::WheelsetContact<Solver> later = original;  // the original's state after those steps
  for (double shift : {4.2e-3, 4.4e-3, 0.5e-3}) {
    pose.y = shift;
    const wr::WheelsetContactResult expected = original.evaluate(pose);
    check_same_patches(later.evaluate(pose), expected);
  }
}

}  // namespace

TEST_CASE("A copy of a model steps on its own and answers as a model built anew", "[wheelrail][model]") {
  check_copies<fastnorm::ReducedSolver<fastnorm::EllipticBasis>>("elliptic");
  check_copies<fastnorm::NormSolver<>>("norm");
  check_copies<fastnorm::AnySolver<>>("polynomial-edge:4:1");
}

TEST_CASE("The same pose reached along different histories: forces within the grid's and the basis's cold bounds",
          "[wheelrail][model]") {
  // An answer depends on the committed history in two ways (docs/wheel-rail.md §9): the
  // patch grid sits on the lattice of the element where the patch appeared (a placement of
  // the same discretisation, shifted by a fraction of an element), and a warm reduced solve
  // starts from the last contact set. The first is bounded by the discretisation error of
  // the grid itself, estimated by cold CG on twice as many elements; the second by the
  // basis's cold bound against NORM.
  const wr::Track track;
  const wr::Wheelset wheelset;
  auto target = wr::rigid_contact_pose(track, wheelset, 2e-3, 1e-3);
  target.z += 0.1e-3;
  auto cold_force = [&](const char* solver, Eigen::Index elements, std::optional<bool> warm) {
    auto options = model_options(solver);
    options.grid.elements = elements;
    options.reduced_warm_start = warm;
    wr::WheelsetContact<> model(track, wheelset, options);
    const auto& result = model.evaluate(target);
    REQUIRE(result.ok());
    return std::array<double, 2>{result.wheels[0].normal_force, result.wheels[1].normal_force};
  };
  const auto coarse_cg = cold_force("cg", 40, std::nullopt), fine_cg = cold_force("cg", 80, std::nullopt);
  struct Basis {
    const char* name;
    std::optional<bool> warm;
    double cold_bound;  // its force error against NORM (docs/performance.md §8)
  };
  for (const Basis& basis : {Basis{"norm", std::nullopt, 0}, Basis{"cg", std::nullopt, 1e-8},
                             Basis{"elliptic", false, 5.5e-4}, Basis{"elliptic", true, 5.5e-4},
                             Basis{"polynomial-edge:4:1", std::nullopt, 5e-5}}) {
    INFO(basis.name << (basis.warm ? (*basis.warm ? " warm" : " cold") : ""));
    const auto cold = cold_force(basis.name, 40, basis.warm);
    // Histories: from the left and from the right in 25 steps of 80 µm, pressed in from
    // 80 µm above, and a jump from the other side of the track (the patches appear anew).
    for (int history = 0; history < 4; ++history) {
      INFO("history " << history);
      auto options = model_options(basis.name);
      options.grid.elements = 40;
      options.reduced_warm_start = basis.warm;
      wr::WheelsetContact<> model(track, wheelset, options);
      const int steps = 25;
      for (int k = 0; k < steps; ++k) {
        const double remaining = static_cast<double>(steps - k) / steps;
        wr::WheelsetPose pose = target;
        if (history < 2) {
          pose = wr::rigid_contact_pose(track, wheelset, target.y + (history == 0 ? -2e-3 : 2e-3) * remaining, target.yaw);
          pose.z += 0.1e-3;
        } else if (history == 2) {
          pose.z -= 0.08e-3 * remaining;
        } else {
          pose = wr::rigid_contact_pose(track, wheelset, -4e-3, -2e-3);
          pose.z += 0.1e-3;
        }
        REQUIRE(model.evaluate(pose).ok());
      }
      const auto& result = model.evaluate(target);
      REQUIRE(result.ok());
      for (std::size_t w = 0; w < 2; ++w) {
        const double difference = std::abs(result.wheels[w].normal_force / cold[w] - 1);
        const double grid_bound = std::abs(coarse_cg[w] / fine_cg[w] - 1);
        CHECK(difference <= grid_bound + basis.cold_bound);
        // After the jump every patch appeared anew, on the grid and from the start of a cold model.
        if (history == 3) CHECK(result.wheels[w].normal_force == cold[w]);
      }
    }
  }
}

TEST_CASE("A warm model's equilibrium tries every pose from the model's state", "[wheelrail][model]") {
  // The elliptic basis starts warm by default. Evaluated one trial after the other, a trial's
  // contact set came from the one before, so the force was no function of the pose and the
  // search stalled here (not converged after 40 steps); from the committed state it balances.
  const wr::WheelsetPose stalled{-4e-3, 0, 0, -20e-3};
  wr::WheelsetContactOptions options;
  options.solver = fastnorm::SolverSpec<double>::parse("elliptic");
  REQUIRE(options.starts_warm());
  wr::WheelsetContact<fastnorm::ReducedSolver<fastnorm::EllipticBasis>> model(wr::Track(), wr::Wheelset(), options);
  const double load = 1e5;
  const auto found = wr::solve_equilibrium(model, stalled.y, stalled.yaw, load);
  REQUIRE(found.ok());
  CHECK(found.iterations < 10);
  // The model is left as evaluated at the pose found: evaluated there again (warm, from that
  // pose's contact sets), it carries the load as the search found.
  const auto& again = model.evaluate(found.pose);
  REQUIRE(again.ok());
  const double vertical = vertical_force(again);
  CHECK(vertical - load == Approx(found.vertical_residual).margin(1e-9 * load));
}

TEST_CASE("Where the model's force jumps across the load the search stops at its best pose", "[wheelrail][model]") {
  // A reduced basis's force jumps as an element joins its contact set. At y = 2 mm, yaw 5 mrad
  // the elliptic model's vertical force jumps by about 19 N (1.9e-4 of the load) between two
  // poses 4.7 nm apart, and a load of 100.008 kN falls inside the jump (loads of 100.001 to
  // 100.018 kN do): no pose carries it within the default tolerance (0.1 N). Before, the
  // search ping-ponged across the jump for its 40 steps and reported zeros.
  wr::WheelsetContactOptions options;
  options.solver = fastnorm::SolverSpec<double>::parse("elliptic");
  options.reduced_warm_start = false;
  options.snap_to_lattice = false;
  wr::WheelsetContact<fastnorm::ReducedSolver<fastnorm::EllipticBasis>> model(wr::Track(), wr::Wheelset(), options);
  const double load = 1.00008e5;
  const auto found = wr::solve_equilibrium(model, 2e-3, 5e-3, load);
  CHECK(found.status == wr::EquilibriumStatus::not_converged);
  CHECK_THAT(found.message, Contains("jump across the load") && Contains("nm apart"));
  CHECK(found.iterations < 12);
  // The best pose is given with its own patches and residuals, within the jump.
  REQUIRE(found.patches.size() == 2);
  const double vertical = vertical_force(found.patches);
  CHECK(found.vertical_force == Approx(vertical).epsilon(1e-14));
  CHECK(found.vertical_residual == Approx(vertical - load).margin(1e-9 * load));
  CHECK(std::abs(found.vertical_residual) > wr::EquilibriumOptions().force_tolerance * load);
  CHECK(std::abs(found.vertical_residual) < 2e-4 * load);
  CHECK(found.roll_residual != 0);
  // They are the pose's: a new model (cold, as this one) gives the same force there.
  wr::WheelsetContact<fastnorm::ReducedSolver<fastnorm::EllipticBasis>> fresh(wr::Track(), wr::Wheelset(), options);
  CHECK(vertical_force(fresh.evaluate(found.pose)) == Approx(found.vertical_force).epsilon(1e-12));
}
