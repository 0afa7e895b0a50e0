// The C API gives the C++ library's numbers, bit for bit: the wheelset model with
// velocities (creepages, creep forces, tractions, sums; both creep methods) along a short
// motion, and steady rolling on one patch. What it guards is the C layer's conversions
// (frames, signs, units, element order, which wheel is which), not the mechanics.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <fastnorm/fastnorm.hpp>
#include <string>
#include <vector>

#include "fastnorm_c.h"
#include "support/surfaces.hpp"

namespace wr = fastnorm::wheelrail;

namespace {

#define REQUIRE_C_OK(call)          \
  do {                              \
    const int c_status = (call);    \
    INFO(fastnorm_last_error());    \
    REQUIRE(c_status == FASTNORM_OK); \
  } while (false)

void check_equal(const double (&c)[3], const Eigen::Vector3d& cpp) {
  for (int k = 0; k < 3; ++k) CHECK(c[k] == cpp(k));
}

/// Every number the C API reports of wheel `w`'s patches at its last evaluate against the
/// C++ model's result.
void check_wheel(const fastnorm_wheelset* model, int w, const wr::WheelContact& wheel) {
  int count = -1;
  REQUIRE_C_OK(fastnorm_wheelset_patch_count(model, w, &count));
  REQUIRE(count == static_cast<int>(wheel.patches.size()));
  for (int k = 0; k < count; ++k) {
    const wr::PatchContact& cpp = wheel.patches[static_cast<std::size_t>(k)];
    fastnorm_patch patch{};
    REQUIRE_C_OK(fastnorm_wheelset_patch(model, w, k, &patch));
    INFO("wheel " << w << ", patch " << k);
    CHECK(patch.normal_force == cpp.normal_force);
    std::vector<double> pressure(static_cast<std::size_t>(cpp.patch.grid.size()));
    REQUIRE_C_OK(fastnorm_wheelset_patch_pressure(model, w, k, pressure.data()));
    CHECK(Eigen::Map<const Eigen::VectorXd>(pressure.data(), cpp.patch.grid.size()) == cpp.solution.pressure);
    check_equal(patch.force, cpp.force);
    check_equal(patch.moment, cpp.moment);
    check_equal(patch.creep_force, cpp.creep_force);
    CHECK(patch.stiffness == cpp.stiffness);
    CHECK(patch.creepage.longitudinal == cpp.creepage.longitudinal);
    CHECK(patch.creepage.lateral == cpp.creepage.lateral);
    CHECK(patch.creepage.spin == cpp.creepage.spin);
    CHECK(patch.creep.status == FASTNORM_CONVERGED);
    CHECK(cpp.traction.ok());
    CHECK(patch.creep.force_x == cpp.traction.force_x);
    CHECK(patch.creep.force_y == cpp.traction.force_y);
    CHECK(patch.creep.spin_moment == cpp.traction.spin_moment);
    CHECK(patch.creep.frictional_power_per_speed == cpp.traction.frictional_power_per_speed);
    CHECK(patch.creep.adhesion_elements == cpp.traction.adhesion_elements);
    CHECK(patch.creep.slip_elements == cpp.traction.slip_elements);
    const auto elements = static_cast<std::size_t>(patch.grid.mx) * static_cast<std::size_t>(patch.grid.my);
    REQUIRE(static_cast<Eigen::Index>(elements) == cpp.patch.grid.size());
    std::vector<double> traction_x(elements), traction_s(elements);
    REQUIRE_C_OK(fastnorm_wheelset_patch_traction(model, w, k, traction_x.data(), traction_s.data()));
    CHECK(Eigen::Map<const Eigen::VectorXd>(traction_x.data(), cpp.patch.grid.size()) == cpp.traction.traction_x);
    CHECK(Eigen::Map<const Eigen::VectorXd>(traction_s.data(), cpp.patch.grid.size()) == cpp.traction.traction_y);
  }
}

/// The C++ model of a C model of fastnorm_wheelset_options_default with `options` and
/// `cant` (S1002 on UIC60, steel: fastnorm_c.h).
wr::WheelsetContact<> cpp_model(const wr::WheelsetContactOptions& options, double cant = wr::TrackLayout().cant) {
  wr::WheelsetOnTrack setup;
  setup.cant = cant;
  return wr::WheelsetContact<>(setup.track(), setup.wheelset(), options);
}

/// The same with `solver`, `elements`, `cant` and the creep options changed.
wr::WheelsetContact<> cpp_model(const char* solver, int elements, double cant = wr::TrackLayout().cant,
                                const wr::CreepOptions& creep = {}) {
  wr::WheelsetContactOptions options;
  options.solver = fastnorm::SolverSpec<double>::parse(solver);
  options.grid.elements = elements;
  options.creep = creep;
  return cpp_model(options, cant);
}

/// The model's rigid contact at (y, yaw), pressed `depth` (m) further.
wr::WheelsetPose pressed(const wr::WheelsetContact<>& model, double y, double yaw, double depth) {
  wr::WheelsetPose pose = wr::rigid_contact_pose(model.track(), model.wheelset(), y, yaw);
  pose.z += depth;
  return pose;
}

}  // namespace

TEST_CASE("The C API's wheelset model gives the C++ model's creep forces bit for bit", "[cli][c_api][creep]") {
  for (const int method : {FASTNORM_STRIP_THEORY, FASTNORM_FASTSIM}) {
    DYNAMIC_SECTION((method == FASTNORM_FASTSIM ? "FASTSIM" : "strip theory")) {
      fastnorm_wheelset_options c_options;
      fastnorm_wheelset_options_default(&c_options);
      c_options.solver = "elliptic";
      c_options.elements = 30;
      c_options.friction = 0.3;
      c_options.creep_method = method;
      c_options.cant = 0.05;  // 1:20, where S1002 meets UIC60 at two points from y = 5.5 mm
      fastnorm_wheelset* c_model = nullptr;
      REQUIRE_C_OK(fastnorm_wheelset_create(&c_options, &c_model));

      wr::CreepOptions creep;
      creep.friction = 0.3;
      creep.method = method == FASTNORM_FASTSIM ? wr::CreepMethod::fastsim : wr::CreepMethod::strip_theory;
      auto model = cpp_model("elliptic", 30, 0.05, creep);

      // A short lateral run from the centre to two-point contact on the right wheel, yawed,
      // moving at 30 m/s with lateral and yaw rates.
      std::size_t most_patches = 0;
      for (const double y : {0.0, 3e-3, 5e-3, 6e-3, 6.5e-3, 7e-3}) {
        INFO("y = " << y);
        const wr::WheelsetPose pose = pressed(model, y, 1e-3, 0.05e-3);
        wr::WheelsetVelocity velocity;
        velocity.forward = 30;
        velocity.lateral = 0.05;
        velocity.yaw_rate = 0.01;
        velocity.pitch_rate = -30 / 0.45;
        const auto& cpp = model.evaluate(pose, velocity);
        REQUIRE(cpp.ok());

        const fastnorm_pose c_pose = {pose.y, pose.z, pose.roll, pose.yaw};
        const fastnorm_velocity c_velocity = {velocity.forward,   velocity.lateral,  velocity.vertical,
                                              velocity.roll_rate, velocity.yaw_rate, velocity.pitch_rate};
        double force[3], moment[3];
        REQUIRE_C_OK(fastnorm_wheelset_evaluate_moving(c_model, &c_pose, &c_velocity, force, moment));
        check_equal(force, cpp.force);
        check_equal(moment, cpp.moment);
        check_wheel(c_model, 0, cpp.wheels[0]);
        check_wheel(c_model, 1, cpp.wheels[1]);
        for (const auto& wheel : cpp.wheels) most_patches = std::max(most_patches, wheel.patches.size());
      }
      CHECK(most_patches == 2);
      fastnorm_wheelset_destroy(c_model);
    }
  }
}

TEST_CASE("The C API's steady rolling is the C++ solver's bit for bit", "[cli][c_api][tangential]") {
  // A wheel-rail patch of the model (elliptic pressures), rolled towards -x with all three
  // creepages about a spin centre off the grid's origin: the exact path through both, with
  // the default options (NULL) and with CONTACT's stopping rule.
  auto model = cpp_model("elliptic", 24);
  const auto& patch = model.evaluate(pressed(model, 3e-3, 0, 0.1e-3)).wheels[1].patches.at(0);
  const auto& grid = patch.patch.grid;
  const fastnorm::Creepage<double> creepage{1e-3, -5e-4, 0.4, 1e-3, -2e-4};
  const auto material = model.options().material;
  const fastnorm_grid c_grid = {static_cast<int>(grid.mx()), static_cast<int>(grid.my()), grid.dx(), grid.dy(),
                                grid.x0(), grid.y0()};
  const fastnorm_material c_material = {material.young_modulus(1), material.poisson_ratio(1),
                                        material.young_modulus(2), material.poisson_ratio(2)};
  const fastnorm_creepage c_creepage = {creepage.longitudinal, creepage.lateral, creepage.spin,
                                        creepage.spin_centre_x, creepage.spin_centre_y};
  const fastnorm_tangential_options contact_rule = {FASTNORM_STOP_RMS_CHANGE, 0, 1e-5};
  for (const fastnorm_tangential_options* c_options : {static_cast<const fastnorm_tangential_options*>(nullptr),
                                                       &contact_rule}) {
    INFO((c_options ? "CONTACT's rule" : "default options"));
    fastnorm::TangentialOptions<double> options;
    if (c_options) {
      options.stop = fastnorm::TangentialStop::rms_change;
      options.tolerance = c_options->tolerance;
    }
    const auto cpp = fastnorm::solve_steady_rolling(grid, material, patch.solution, 0.3, creepage,
                                                    fastnorm::RollingDirection::negative_x, options);
    REQUIRE(cpp.ok());
    std::vector<double> traction_x(static_cast<std::size_t>(grid.size())), traction_y(traction_x.size());
    fastnorm_tangential_result result{};
    REQUIRE_C_OK(fastnorm_steady_rolling(&c_grid, &c_material, patch.solution.pressure.data(), 0.3, &c_creepage, -1,
                                         c_options, traction_x.data(), traction_y.data(), &result));
    CHECK(result.status == FASTNORM_CONVERGED);
    CHECK(result.force_x == cpp.force_x);
    CHECK(result.force_y == cpp.force_y);
    CHECK(result.spin_moment == cpp.spin_moment);
    CHECK(result.frictional_power_per_speed == cpp.frictional_power_per_speed);
    CHECK(result.adhesion_elements == cpp.adhesion_elements);
    CHECK(result.slip_elements == cpp.slip_elements);
    CHECK(result.sweeps == cpp.sweeps);
    CHECK(result.residual == cpp.residual);
    CHECK(Eigen::Map<const Eigen::VectorXd>(traction_x.data(), grid.size()) == cpp.traction_x);
    CHECK(Eigen::Map<const Eigen::VectorXd>(traction_y.data(), grid.size()) == cpp.traction_y);
  }
}

TEST_CASE("The C API's iteration budget and the work it reports are the C++ model's", "[cli][c_api]") {
  fastnorm_wheelset_options c_options;
  fastnorm_wheelset_options_default(&c_options);
  c_options.solver = "elliptic";
  c_options.elements = 24;
  fastnorm_wheelset* c_model = nullptr;
  REQUIRE_C_OK(fastnorm_wheelset_create(&c_options, &c_model));
  auto model = cpp_model("elliptic", 24);
  const wr::WheelsetPose pose = pressed(model, 2e-3, 0, 0.1e-3);
  const fastnorm_pose c_pose = {pose.y, pose.z, pose.roll, pose.yaw};
  int spent = -1;
  for (const int budget : {0, 1, 100000}) {
    INFO("budget " << budget);
    model.set_iteration_budget(budget);
    REQUIRE_C_OK(fastnorm_wheelset_set_iteration_budget(c_model, budget));
    model.reset();
    REQUIRE_C_OK(fastnorm_wheelset_reset(c_model));
    const auto& cpp = model.evaluate(pose);
    const int status = fastnorm_wheelset_evaluate(c_model, &c_pose, nullptr, nullptr);
    CHECK(status == (cpp.ok() ? FASTNORM_OK : FASTNORM_ERROR_PATCH_FAILED));
    // One iteration a patch cannot settle these cold solves: each stops early, the same in C.
    for (int w = 0; w < 2; ++w) {
      const auto& patches = cpp.wheels[static_cast<std::size_t>(w)].patches;
      for (std::size_t k = 0; k < patches.size(); ++k) {
        CHECK(patches[k].solution.stopped_early() == (budget == 1));
        fastnorm_patch c_patch;
        REQUIRE_C_OK(fastnorm_wheelset_patch(c_model, w, static_cast<int>(k), &c_patch));
        CHECK(c_patch.status == static_cast<int>(patches[k].solution.status));
      }
    }
    REQUIRE_C_OK(fastnorm_wheelset_iterations(c_model, &spent));
    CHECK(spent == cpp.iterations);
    CHECK(spent > 0);
  }
  CHECK(fastnorm_wheelset_set_iteration_budget(c_model, -1) == FASTNORM_ERROR_ARGUMENT);
  CHECK(std::string(fastnorm_last_error()).find("iterations must be >= 0") != std::string::npos);
  fastnorm_wheelset_destroy(c_model);
}

TEST_CASE("The C API's solver tolerances are the C++ spec's, and refused where they do not apply", "[cli][c_api]") {
  // A Hertz problem in force control: a loose join tolerance for the elliptic basis and a
  // loose stopping tolerance for CG, through fastnorm_solver_options and through the spec.
  using fastnorm::test::steel;
  const auto [grid, h, loading] = fastnorm::test::hertz_ellipsoid(24);
  const fastnorm_grid c_grid = {static_cast<int>(grid.mx()), static_cast<int>(grid.my()), grid.dx(), grid.dy(),
                                grid.x0(), grid.y0()};
  const fastnorm_material c_steel = {2.1e11, 0.3, 2.1e11, 0.3};
  struct Setting {
    const char* solver;
    fastnorm_solver_options options;
  };
  for (const Setting& setting : {Setting{"elliptic", {0, 0, 1e-2}}, Setting{"cg", {0, 1e-4, 0}}}) {
    INFO(setting.solver);
    auto spec = fastnorm::SolverSpec<double>::parse(setting.solver);
    if (setting.options.tolerance > 0) spec.set_cg_tolerance(setting.options.tolerance);
    if (setting.options.gap_tolerance > 0) spec.set_gap_tolerance(setting.options.gap_tolerance);
    const auto cpp = fastnorm::AnySolver<>(spec, grid, steel).solve(h, loading);
    const auto by_default = fastnorm::AnySolver<>(setting.solver, grid, steel).solve(h, loading);
    CHECK(cpp.iterations != by_default.iterations);  // the tolerance takes effect
    fastnorm_solver* solver = nullptr;
    REQUIRE_C_OK(fastnorm_solver_create(setting.solver, &c_grid, &c_steel, &setting.options, &solver));
    std::vector<double> pressure(static_cast<std::size_t>(grid.size()));
    fastnorm_result result{};
    const int status = fastnorm_solve_force(solver, h.data(), 5e4, pressure.data(), &result);
    fastnorm_solver_destroy(solver);
    REQUIRE(status == FASTNORM_OK);
    CHECK(result.iterations == cpp.iterations);
    CHECK(Eigen::Map<const Eigen::VectorXd>(pressure.data(), grid.size()) == cpp.pressure);
  }
  const auto refused = [&](const char* name, const fastnorm_solver_options& options, const std::string& message) {
    INFO(name << ": " << message);
    fastnorm_solver* solver = nullptr;
    CHECK(fastnorm_solver_create(name, &c_grid, &c_steel, &options, &solver) == FASTNORM_ERROR_ARGUMENT);
    CHECK(solver == nullptr);
    CHECK(std::string(fastnorm_last_error()).find(message) != std::string::npos);
  };
  refused("elliptic", {0, 1e-6, 0}, "'elliptic' is an active-set solver, whose join tolerance is gap_tolerance");
  refused("cg", {0, 0, 1e-6}, "gap_tolerance is the join tolerance of the active-set solvers");
  refused("norm", {0, 0, -1}, "options.gap_tolerance must be >= 0");

  // The wheelset model's patch solvers take them alike (and h its node spacing).
  fastnorm_wheelset_options c_options;
  fastnorm_wheelset_options_default(&c_options);
  CHECK(c_options.distance_node_spacing == wr::DistanceAccuracy().node_spacing);
  c_options.solver = "elliptic";
  c_options.elements = 24;
  c_options.gap_tolerance = 1e-2;
  c_options.distance_tolerance = 5e-10;
  c_options.distance_node_spacing = 5e-3;
  fastnorm_wheelset* c_model = nullptr;
  REQUIRE_C_OK(fastnorm_wheelset_create(&c_options, &c_model));
  wr::WheelsetContactOptions options;
  options.solver = fastnorm::SolverSpec<double>::parse("elliptic");
  options.solver.set_gap_tolerance(1e-2);
  options.grid.elements = 24;
  options.distance = {5e-10, 5e-3};
  auto model = cpp_model(options);
  const wr::WheelsetPose pose = pressed(model, 2e-3, 0, 0.1e-3);
  const fastnorm_pose c_pose = {pose.y, pose.z, pose.roll, pose.yaw};
  const auto& cpp = model.evaluate(pose);
  double force[3];
  REQUIRE_C_OK(fastnorm_wheelset_evaluate(c_model, &c_pose, force, nullptr));
  fastnorm_wheelset_destroy(c_model);
  check_equal(force, cpp.force);
  c_options.distance_node_spacing = 0;
  CHECK(fastnorm_wheelset_create(&c_options, &c_model) == FASTNORM_ERROR_ARGUMENT);
  CHECK(std::string(fastnorm_last_error()).find("node_spacing") != std::string::npos);
  c_options.distance_node_spacing = 5e-3;
  c_options.solver = "cg";
  CHECK(fastnorm_wheelset_create(&c_options, &c_model) == FASTNORM_ERROR_ARGUMENT);
  CHECK(std::string(fastnorm_last_error()).find("gap_tolerance") != std::string::npos);
}
