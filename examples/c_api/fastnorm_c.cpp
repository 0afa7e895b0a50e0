// The C API (fastnorm_c.h) over the header-only library: each entry point checks its
// pointers, calls the C++ code, and turns every exception into a return code and a
// per-thread message (docs/bindings.md).
#include "fastnorm_c.h"

#include <fastnorm/any_solver.hpp>
#include <fastnorm/case_file.hpp>
#include <fastnorm/contact_table_file.hpp>
#include <fastnorm/tangential_solver.hpp>
#include <fastnorm/version.hpp>
#include <fastnorm/wheelrail.hpp>

#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace wr = fastnorm::wheelrail;

struct fastnorm_solver {
  fastnorm::AnySolver<double> solver;
  fastnorm::Solution<double> last_next;  // the last solve_next's answer, for the stiffness
};

struct fastnorm_case {
  fastnorm::Case<double> problem;
};

struct fastnorm_table {
  fastnorm::ContactTable table;
};

struct fastnorm_wheelset {
  wr::WheelsetContact<> model;  // owns its track and wheelset
  wr::StepStatus step;          // of the last evaluate; not_solved after an equilibrium
  std::optional<wr::Equilibrium> equilibrium;  // the last equilibrium, when it was the last call
  std::array<std::vector<const wr::PatchContact*>, 2> patches;  // what fastnorm_wheelset_patch reads
  int iterations;  // the solver iterations of the last evaluate
  std::optional<wr::WheelsetContact<>::History> saved;  // fastnorm_wheelset_save_history
};

namespace {

thread_local std::string last_error;

// A step whose patch solve gave no usable answer: a status that evaluate reports with its
// message (FASTNORM_ERROR_PATCH_FAILED), its results still written.
struct patch_failed : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Runs `body`, turning exceptions into a code and this thread's message.
template <typename Body>
int guarded(const char* function, Body&& body) {
  try {
    body();
    return FASTNORM_OK;
  } catch (const fastnorm::invalid_argument& error) {
    last_error = std::string(function) + ": " + error.what();
    return FASTNORM_ERROR_ARGUMENT;
  } catch (const patch_failed& failure) {
    last_error = std::string(function) + ": " + failure.what();
    return FASTNORM_ERROR_PATCH_FAILED;
  } catch (const std::bad_alloc&) {
    last_error = std::string(function) + ": out of memory";
    return FASTNORM_ERROR_MEMORY;
  } catch (const std::exception& error) {
    last_error = std::string(function) + ": internal error: " + error.what();
    return FASTNORM_ERROR_INTERNAL;
  } catch (...) {
    last_error = std::string(function) + ": internal error";
    return FASTNORM_ERROR_INTERNAL;
  }
}

void require_pointer(const void* pointer, const char* name) {
  if (!pointer) throw fastnorm::invalid_argument(std::string("fastnorm: ") + name + " must not be NULL");
}

fastnorm::Grid<double> grid_of(const fastnorm_grid* grid) {
  require_pointer(grid, "grid");
  return {grid->mx, grid->my, grid->dx, grid->dy, grid->x0, grid->y0};
}

fastnorm_grid grid_to_c(const fastnorm::Grid<double>& grid) {
  return {static_cast<int>(grid.mx()), static_cast<int>(grid.my()), grid.dx(), grid.dy(), grid.x0(), grid.y0()};
}

fastnorm::Material<double> material_of(const fastnorm_material* material) {
  require_pointer(material, "material");
  return {material->young_modulus_1, material->poisson_ratio_1, material->young_modulus_2, material->poisson_ratio_2};
}

fastnorm_result result_to_c(const fastnorm::Solution<double>& solution) {
  fastnorm_result result{};
  result.status = static_cast<int>(solution.status);
  result.iterations = solution.iterations;
  result.contact_count = static_cast<int>(solution.contact_count());
  result.at_edge = solution.at_edge ? 1 : 0;
  result.normal_force = solution.normal_force;
  result.approach = solution.approach;
  result.residual = solution.residual;
  return result;
}

// Solves with `run` and copies the answer out; returns it.
template <typename Run>
fastnorm::Solution<double> solve_into(fastnorm_solver* solver, const double* h, double* pressure,
                                      fastnorm_result* result, Run run) {
  require_pointer(solver, "solver");
  require_pointer(h, "h");
  require_pointer(pressure, "pressure");
  require_pointer(result, "result");
  const Eigen::Index size = solver->solver.grid().size();
  auto solution = run(Eigen::Map<const Eigen::VectorXd>(h, size));
  Eigen::Map<Eigen::VectorXd>(pressure, size) = solution.pressure;
  *result = result_to_c(solution);
  return solution;
}

// solve_next's loading: Fn > 0 force control, Fn <= 0 approach control, NaN or inf refused.
fastnorm::Loading<double> loading_of(double normal_force) {
  FASTNORM_CHECK(std::isfinite(normal_force),
                 fastnorm::describe("normal_force must be finite (N; <= 0 for approach control)", normal_force));
  return normal_force > 0 ? fastnorm::Loading<double>::force(normal_force) : fastnorm::Loading<double>::approach();
}

const wr::PatchContact& patch_of(const fastnorm_wheelset* model, int wheel, int patch) {
  require_pointer(model, "model");
  FASTNORM_CHECK(wheel == 0 || wheel == 1, fastnorm::describe("wheel must be 0 (left) or 1 (right)", wheel));
  const auto& patches = model->patches[static_cast<std::size_t>(wheel)];
  FASTNORM_CHECK(patch >= 0 && static_cast<std::size_t>(patch) < patches.size(),
                 fastnorm::describe("patch must lie in [0, patch count)", patch));
  return *patches[static_cast<std::size_t>(patch)];
}

fastnorm_tangential_result tangential_to_c(const fastnorm::TangentialSolution<double>& answer) {
  return {static_cast<int>(answer.status),
          answer.sweeps,
          static_cast<int>(answer.adhesion_elements),
          static_cast<int>(answer.slip_elements),
          answer.force_x,
          answer.force_y,
          answer.spin_moment,
          answer.frictional_power_per_speed,
          answer.residual};
}

fastnorm_creepage creepage_to_c(const fastnorm::Creepage<double>& creepage) {
  return {creepage.longitudinal, creepage.lateral, creepage.spin, creepage.spin_centre_x, creepage.spin_centre_y};
}

// options.max_iterations of the C structs: 0 keeps the solver's default.
void apply_max_iterations(int max_iterations, fastnorm::SolverSpec<double>& spec) {
  FASTNORM_CHECK(max_iterations >= 0, fastnorm::describe("options.max_iterations must be >= 0", max_iterations));
  if (max_iterations > 0) spec.set_max_iterations(max_iterations);
}

// options.tolerance and options.gap_tolerance of the C structs: 0 keeps the solver's
// default; a tolerance for a solver it does not apply to is refused (SolverSpec).
void apply_tolerances(double tolerance, double gap_tolerance, fastnorm::SolverSpec<double>& spec) {
  FASTNORM_CHECK(std::isfinite(tolerance) && tolerance >= 0, fastnorm::describe("options.tolerance must be >= 0", tolerance));
  FASTNORM_CHECK(std::isfinite(gap_tolerance) && gap_tolerance >= 0,
                 fastnorm::describe("options.gap_tolerance must be >= 0", gap_tolerance));
  if (tolerance > 0) spec.set_cg_tolerance(tolerance);
  if (gap_tolerance > 0) spec.set_gap_tolerance(gap_tolerance);
}

void copy3(const Eigen::Vector3d& from, double* to) {
  for (int k = 0; k < 3; ++k) to[k] = from(k);
}

// The C codes are the C++ enumerators' values.
static_assert(static_cast<int>(fastnorm::Status::not_solved) == FASTNORM_NOT_SOLVED &&
              static_cast<int>(fastnorm::Status::converged) == FASTNORM_CONVERGED &&
              static_cast<int>(fastnorm::Status::no_contact) == FASTNORM_NO_CONTACT &&
              static_cast<int>(fastnorm::Status::iteration_limit) == FASTNORM_ITERATION_LIMIT &&
              static_cast<int>(fastnorm::Status::cycled) == FASTNORM_CYCLED &&
              static_cast<int>(fastnorm::Status::numerical_issue) == FASTNORM_NUMERICAL_ISSUE &&
              static_cast<int>(fastnorm::Status::budget_reached) == FASTNORM_BUDGET_REACHED);
static_assert(static_cast<int>(wr::EquilibriumStatus::not_solved) == FASTNORM_EQUILIBRIUM_NOT_SOLVED &&
              static_cast<int>(wr::EquilibriumStatus::converged) == FASTNORM_EQUILIBRIUM_CONVERGED &&
              static_cast<int>(wr::EquilibriumStatus::lost_contact) == FASTNORM_EQUILIBRIUM_LOST_CONTACT &&
              static_cast<int>(wr::EquilibriumStatus::not_converged) == FASTNORM_EQUILIBRIUM_NOT_CONVERGED &&
              static_cast<int>(wr::EquilibriumStatus::solver_failed) == FASTNORM_EQUILIBRIUM_SOLVER_FAILED &&
              static_cast<int>(wr::EquilibriumStatus::flange_climb) == FASTNORM_EQUILIBRIUM_FLANGE_CLIMB);
static_assert(static_cast<int>(wr::StepStatus::Code::not_solved) == FASTNORM_STEP_NOT_SOLVED &&
              static_cast<int>(wr::StepStatus::Code::ok) == FASTNORM_STEP_OK &&
              static_cast<int>(wr::StepStatus::Code::patch_failed) == FASTNORM_STEP_PATCH_FAILED);
static_assert(static_cast<int>(wr::PatchHistory::continued) == FASTNORM_PATCH_CONTINUED &&
              static_cast<int>(wr::PatchHistory::appeared) == FASTNORM_PATCH_APPEARED &&
              static_cast<int>(wr::PatchHistory::merged) == FASTNORM_PATCH_MERGED &&
              static_cast<int>(wr::PatchHistory::split) == FASTNORM_PATCH_SPLIT);
static_assert(static_cast<int>(fastnorm::TableLookupStatus::ok) == FASTNORM_TABLE_FOUND &&
              static_cast<int>(fastnorm::TableLookupStatus::out_of_range) == FASTNORM_TABLE_OUT_OF_RANGE &&
              static_cast<int>(fastnorm::TableLookupStatus::topology_change) == FASTNORM_TABLE_TOPOLOGY_CHANGE &&
              static_cast<int>(fastnorm::TableLookupStatus::failed_case) == FASTNORM_TABLE_FAILED_CASE);
static_assert(static_cast<int>(fastnorm::TangentialStop::largest_change) == FASTNORM_STOP_LARGEST_CHANGE &&
              static_cast<int>(fastnorm::TangentialStop::rms_change) == FASTNORM_STOP_RMS_CHANGE);

/// The C options as the exact tangential path's, a 0 field keeping the default.
fastnorm::TangentialOptions<double> tangential_options_of(const fastnorm_tangential_options* options) {
  fastnorm::TangentialOptions<double> value;
  if (!options) return value;
  FASTNORM_CHECK(options->stop == FASTNORM_STOP_LARGEST_CHANGE || options->stop == FASTNORM_STOP_RMS_CHANGE,
                 "options.stop must be FASTNORM_STOP_LARGEST_CHANGE (0) or FASTNORM_STOP_RMS_CHANGE (1), not " +
                     std::to_string(options->stop));
  FASTNORM_CHECK(options->max_sweeps >= 0, "options.max_sweeps must be >= 0 (0: the default), not " +
                                               std::to_string(options->max_sweeps));
  value.stop = static_cast<fastnorm::TangentialStop>(options->stop);
  if (options->max_sweeps > 0) value.max_sweeps = options->max_sweeps;
  FASTNORM_CHECK(options->tolerance == 0 || (options->tolerance > 0 && options->tolerance < 1),
                 fastnorm::describe("options.tolerance must lie in (0, 1) (0: the default)", options->tolerance));
  if (options->tolerance != 0) value.tolerance = options->tolerance;
  return value;
}

}  // namespace

extern "C" {

const char* fastnorm_last_error(void) { return last_error.c_str(); }

const char* fastnorm_status_name(int status) {
  if (status < FASTNORM_NOT_SOLVED || status > FASTNORM_NUMERICAL_ISSUE) return "unknown";
  return fastnorm::to_string(static_cast<fastnorm::Status>(status));
}

#define FASTNORM_C_TEXT(value) #value
#define FASTNORM_C_VERSION(major, minor, patch) FASTNORM_C_TEXT(major) "." FASTNORM_C_TEXT(minor) "." FASTNORM_C_TEXT(patch)
const char* fastnorm_version(void) {
  return FASTNORM_C_VERSION(FASTNORM_VERSION_MAJOR, FASTNORM_VERSION_MINOR, FASTNORM_VERSION_PATCH);
}

int fastnorm_solver_create(const char* name, const fastnorm_grid* grid, const fastnorm_material* material,
                           const fastnorm_solver_options* options, fastnorm_solver** solver) {
  return guarded("fastnorm_solver_create", [&] {
    require_pointer(name, "name");
    require_pointer(solver, "solver");
    *solver = nullptr;
    auto spec = fastnorm::SolverSpec<double>::parse(name);
    if (options) {
      apply_max_iterations(options->max_iterations, spec);
      apply_tolerances(options->tolerance, options->gap_tolerance, spec);
    }
    *solver = new fastnorm_solver{fastnorm::AnySolver<double>(spec, grid_of(grid), material_of(material)), {}};
  });
}

void fastnorm_solver_destroy(fastnorm_solver* solver) { delete solver; }

int fastnorm_solve_approach(fastnorm_solver* solver, const double* h, double* pressure, fastnorm_result* result) {
  return guarded("fastnorm_solve_approach", [&] {
    solve_into(solver, h, pressure, result,
               [&](const auto& gap) { return solver->solver.solve(gap, fastnorm::Loading<double>::approach()); });
  });
}

int fastnorm_solve_force(fastnorm_solver* solver, const double* h, double normal_force, double* pressure,
                         fastnorm_result* result) {
  return guarded("fastnorm_solve_force", [&] {
    const auto loading = fastnorm::Loading<double>::force(normal_force);
    solve_into(solver, h, pressure, result, [&](const auto& gap) { return solver->solver.solve(gap, loading); });
  });
}

int fastnorm_solve_next(fastnorm_solver* solver, const double* h, double normal_force, double* pressure,
                        fastnorm_result* result) {
  return guarded("fastnorm_solve_next", [&] {
    const auto loading = loading_of(normal_force);
    solver->last_next =
        solve_into(solver, h, pressure, result, [&](const auto& gap) { return solver->solver.solve_next(gap, loading); });
  });
}

int fastnorm_normal_stiffness(fastnorm_solver* solver, double* stiffness) {
  return guarded("fastnorm_normal_stiffness", [&] {
    require_pointer(solver, "solver");
    require_pointer(stiffness, "stiffness");
    FASTNORM_CHECK(solver->last_next.status != fastnorm::Status::not_solved, "no solve_next to take the stiffness of");
    *stiffness = solver->solver.normal_stiffness(solver->last_next, solver->solver.workspace());
  });
}

int fastnorm_steady_rolling(const fastnorm_grid* grid, const fastnorm_material* material, const double* pressure,
                            double friction, const fastnorm_creepage* creepage, int rolling,
                            const fastnorm_tangential_options* options, double* traction_x, double* traction_y,
                            fastnorm_tangential_result* result) {
  return guarded("fastnorm_steady_rolling", [&] {
    for (const auto& [pointer, name] : {std::pair<const void*, const char*>{pressure, "pressure"},
                                        {creepage, "creepage"}, {traction_x, "traction_x"},
                                        {traction_y, "traction_y"}, {result, "result"}}) {
      require_pointer(pointer, name);
    }
    FASTNORM_CHECK(rolling == 1 || rolling == -1, "rolling must be +1 or -1, not " + std::to_string(rolling));
    const auto grid_value = grid_of(grid);
    // The normal answer as the solver reads it: pressures, and contact where they are positive.
    fastnorm::Solution<double> normal;
    normal.pressure = Eigen::Map<const Eigen::VectorXd>(pressure, grid_value.size());
    FASTNORM_CHECK(normal.pressure.allFinite(), "pressure must be finite");
    normal.in_contact = normal.pressure.array() > 0;
    normal.status = normal.in_contact.any() ? fastnorm::Status::converged : fastnorm::Status::no_contact;
    fastnorm::Creepage<double> value;
    value.longitudinal = creepage->longitudinal;
    value.lateral = creepage->lateral;
    value.spin = creepage->spin;
    value.spin_centre_x = creepage->spin_centre_x;
    value.spin_centre_y = creepage->spin_centre_y;
    const auto answer = fastnorm::solve_steady_rolling(
        grid_value, material_of(material), normal, friction, value,
        rolling == 1 ? fastnorm::RollingDirection::positive_x : fastnorm::RollingDirection::negative_x,
        tangential_options_of(options));
    Eigen::Map<Eigen::VectorXd>(traction_x, grid_value.size()) = answer.traction_x;
    Eigen::Map<Eigen::VectorXd>(traction_y, grid_value.size()) = answer.traction_y;
    *result = tangential_to_c(answer);
  });
}

int fastnorm_case_read(const char* path, fastnorm_case** problem) {
  return guarded("fastnorm_case_read", [&] {
    require_pointer(path, "path");
    require_pointer(problem, "problem");
    *problem = nullptr;
    *problem = new fastnorm_case{fastnorm::read_case_file<double>(path)};
  });
}

void fastnorm_case_destroy(fastnorm_case* problem) { delete problem; }

int fastnorm_case_info(const fastnorm_case* problem, fastnorm_grid* grid, fastnorm_material* material,
                       int* force_control, double* control_value) {
  return guarded("fastnorm_case_info", [&] {
    require_pointer(problem, "problem");
    const auto& stored = problem->problem;
    if (grid) *grid = grid_to_c(stored.grid);
    if (material) {
      *material = {stored.material.young_modulus(1), stored.material.poisson_ratio(1),
                   stored.material.young_modulus(2), stored.material.poisson_ratio(2)};
    }
    const bool by_force = stored.loading.control == fastnorm::Control::force;
    if (force_control) *force_control = by_force ? 1 : 0;
    if (control_value) *control_value = by_force ? stored.loading.normal_force : stored.stated_approach;
  });
}

int fastnorm_case_undeformed_distance(const fastnorm_case* problem, double* h) {
  return guarded("fastnorm_case_undeformed_distance", [&] {
    require_pointer(problem, "problem");
    require_pointer(h, "h");
    const auto& values = problem->problem.undeformed_distance;
    Eigen::Map<Eigen::VectorXd>(h, values.size()) = values;
  });
}

int fastnorm_case_rolling(const fastnorm_case* problem, double* friction, fastnorm_creepage* creepage, int* rolling) {
  return guarded("fastnorm_case_rolling", [&] {
    require_pointer(problem, "problem");
    require_pointer(friction, "friction");
    require_pointer(creepage, "creepage");
    require_pointer(rolling, "rolling");
    FASTNORM_CHECK(problem->problem.rolling.has_value(), "the case has no tangential line");
    const auto& stored = *problem->problem.rolling;
    *friction = stored.friction;
    *creepage = {stored.creepage.longitudinal, stored.creepage.lateral, stored.creepage.spin,
                 stored.creepage.spin_centre_x, stored.creepage.spin_centre_y};
    *rolling = stored.direction == fastnorm::RollingDirection::positive_x ? 1 : -1;
  });
}

int fastnorm_case_result(const fastnorm_case* problem, double* pressure, fastnorm_result* result) {
  return guarded("fastnorm_case_result", [&] {
    require_pointer(problem, "problem");
    require_pointer(pressure, "pressure");
    require_pointer(result, "result");
    FASTNORM_CHECK(problem->problem.result.has_value(), "the case has no stored solution");
    const auto& stored = *problem->problem.result;
    Eigen::Map<Eigen::VectorXd>(pressure, stored.pressure.size()) = stored.pressure;
    *result = fastnorm_result{};
    result->normal_force = stored.normal_force;
    result->approach = stored.approach;
    result->contact_count = static_cast<int>(stored.contact_count);
    result->iterations = stored.iterations;
  });
}

int fastnorm_case_write(const char* path, const char* name, const fastnorm_grid* grid,
                        const fastnorm_material* material, int force_control, double control_value, const double* h,
                        const double* pressure, const fastnorm_result* result) {
  return guarded("fastnorm_case_write", [&] {
    require_pointer(path, "path");
    require_pointer(name, "name");
    require_pointer(h, "h");
    FASTNORM_CHECK((pressure == nullptr) == (result == nullptr), "give both pressure and result, or neither");
    const auto grid_value = grid_of(grid);
    fastnorm::Case<double> problem{name, "fastnorm C API", grid_value, material_of(material),
                                   fastnorm::Loading<double>::approach(), 0.0,
                                   Eigen::Map<const Eigen::VectorXd>(h, grid_value.size()), std::nullopt, std::nullopt};
    if (force_control) {
      problem.loading = fastnorm::Loading<double>::force(control_value);
    } else {
      problem.stated_approach = control_value;
    }
    if (result) {
      fastnorm::CaseResult<double> stored;
      stored.normal_force = result->normal_force;
      stored.approach = result->approach;
      stored.contact_count = result->contact_count;
      stored.iterations = result->iterations;
      stored.pressure = Eigen::Map<const Eigen::VectorXd>(pressure, grid_value.size());
      problem.result = stored;
    }
    fastnorm::write_case_file(path, problem);
  });
}

void fastnorm_wheelset_options_default(fastnorm_wheelset_options* options) {
  if (!options) return;
  *options = {};
  options->solver = "norm";
  options->nominal_radius = wr::WheelsetLayout().nominal_radius;
  options->gauge = wr::TrackLayout().gauge;
  options->cant = wr::TrackLayout().cant;
  const auto steel = fastnorm::Material<double>::steel();
  options->material = {steel.young_modulus(1), steel.poisson_ratio(1), steel.young_modulus(2), steel.poisson_ratio(2)};
  options->elements = static_cast<int>(wr::PatchGridOptions().elements);
  options->stiffness = 1;
  options->distance_tolerance = wr::DistanceAccuracy().tolerance;
  options->distance_node_spacing = wr::DistanceAccuracy().node_spacing;
}

int fastnorm_wheelset_create(const fastnorm_wheelset_options* options, fastnorm_wheelset** model) {
  return guarded("fastnorm_wheelset_create", [&] {
    require_pointer(options, "options");
    require_pointer(model, "model");
    *model = nullptr;
    require_pointer(options->solver, "options.solver");
    wr::WheelsetOnTrack setup;
    setup.wheel_profile = options->wheel_profile ? options->wheel_profile : "";
    setup.rail_profile = options->rail_profile ? options->rail_profile : "";
    setup.nominal_radius = options->nominal_radius;
    setup.gauge = options->gauge;
    setup.cant = options->cant;
    wr::WheelsetContactOptions contact;
    contact.solver = fastnorm::SolverSpec<double>::parse(options->solver);
    contact.material = material_of(&options->material);
    contact.grid.elements = options->elements;
    contact.stiffness = options->stiffness != 0;
    apply_max_iterations(options->max_iterations, contact.solver);
    apply_tolerances(options->tolerance, options->gap_tolerance, contact.solver);
    contact.distance.tolerance = options->distance_tolerance;
    contact.distance.node_spacing = options->distance_node_spacing;
    contact.distance_everywhere = options->distance_everywhere != 0;
    contact.warm_solve_iterations = options->warm_solve_iterations;
    FASTNORM_CHECK(options->friction >= 0, fastnorm::describe("options.friction must be >= 0 (0: none)", options->friction));
    if (options->friction > 0) contact.creep.friction = options->friction;
    FASTNORM_CHECK(options->creep_method == FASTNORM_STRIP_THEORY || options->creep_method == FASTNORM_FASTSIM,
                   fastnorm::describe("options.creep_method must be FASTNORM_STRIP_THEORY (0) or FASTNORM_FASTSIM (1)",
                                      options->creep_method));
    contact.creep.method =
        options->creep_method == FASTNORM_FASTSIM ? wr::CreepMethod::fastsim : wr::CreepMethod::strip_theory;
    *model = new fastnorm_wheelset{wr::WheelsetContact<>(setup.track(), setup.wheelset(), contact), {}, {}, {}, 0, {}};
  });
}

void fastnorm_wheelset_destroy(fastnorm_wheelset* model) { delete model; }

int fastnorm_wheelset_copy(const fastnorm_wheelset* model, fastnorm_wheelset** copy) {
  return guarded("fastnorm_wheelset_copy", [&] {
    require_pointer(model, "model");
    require_pointer(copy, "copy");
    *copy = nullptr;
    auto made = std::make_unique<fastnorm_wheelset>(*model);
    // The copied patch pointers still point into model's equilibrium, or else its last
    // evaluate's result: point them at the same places of the copy's own.
    for (std::size_t wheel = 0; wheel < 2; ++wheel) {
      const auto& from = model->equilibrium ? model->equilibrium->patches : model->model.result().wheels[wheel].patches;
      const auto& to = made->equilibrium ? made->equilibrium->patches : made->model.result().wheels[wheel].patches;
      for (auto& patch : made->patches[wheel]) patch = &to[static_cast<std::size_t>(patch - from.data())];
    }
    *copy = made.release();
  });
}

namespace {

// An evaluate of the C API, with velocities or without: the patches to read, the totals
// and the status kept.
void evaluate_into(fastnorm_wheelset* model, const fastnorm_pose* pose, const fastnorm_velocity* velocity,
                   double* force, double* moment) {
  require_pointer(model, "model");
  require_pointer(pose, "pose");
  model->equilibrium.reset();
  for (auto& patches : model->patches) patches.clear();
  model->step = {};
  model->iterations = 0;
  const wr::WheelsetPose at{pose->y, pose->z, pose->roll, pose->yaw};
  const auto& result =
      velocity ? model->model.evaluate(at, wr::WheelsetVelocity{velocity->forward, velocity->lateral, velocity->vertical,
                                                                velocity->roll_rate, velocity->yaw_rate,
                                                                velocity->pitch_rate})
               : model->model.evaluate(at);
  for (std::size_t wheel = 0; wheel < 2; ++wheel) {
    for (const auto& patch : result.wheels[wheel].patches) model->patches[wheel].push_back(&patch);
  }
  if (force) copy3(result.force, force);
  if (moment) copy3(result.moment, moment);
  model->step = result.status;
  model->iterations = result.iterations;
  if (!result.ok()) throw patch_failed(result.status.message);
}

}  // namespace

int fastnorm_wheelset_evaluate(fastnorm_wheelset* model, const fastnorm_pose* pose, double* force, double* moment) {
  return guarded("fastnorm_wheelset_evaluate",
                 [&] { evaluate_into(model, pose, nullptr, force, moment); });
}

int fastnorm_wheelset_evaluate_moving(fastnorm_wheelset* model, const fastnorm_pose* pose,
                                      const fastnorm_velocity* velocity, double* force, double* moment) {
  return guarded("fastnorm_wheelset_evaluate_moving", [&] {
    require_pointer(velocity, "velocity");
    evaluate_into(model, pose, velocity, force, moment);
  });
}

int fastnorm_wheelset_reset(fastnorm_wheelset* model) {
  return guarded("fastnorm_wheelset_reset", [&] {
    require_pointer(model, "model");
    model->model.reset();
    model->equilibrium.reset();
    model->step = {};
    for (auto& patches : model->patches) patches.clear();
  });
}

int fastnorm_wheelset_save_history(fastnorm_wheelset* model) {
  return guarded("fastnorm_wheelset_save_history", [&] {
    require_pointer(model, "model");
    if (!model->saved) model->saved.emplace();
    model->model.history(*model->saved);
  });
}

int fastnorm_wheelset_restore_history(fastnorm_wheelset* model) {
  return guarded("fastnorm_wheelset_restore_history", [&] {
    require_pointer(model, "model");
    FASTNORM_CHECK(model->saved.has_value(), "fastnorm_wheelset_restore_history: no history saved "
                                             "(fastnorm_wheelset_save_history first)");
    model->model.restore(*model->saved);
  });
}

int fastnorm_wheelset_set_iteration_budget(fastnorm_wheelset* model, int iterations) {
  return guarded("fastnorm_wheelset_set_iteration_budget", [&] {
    require_pointer(model, "model");
    model->model.set_iteration_budget(iterations);
  });
}

int fastnorm_wheelset_iterations(const fastnorm_wheelset* model, int* iterations) {
  return guarded("fastnorm_wheelset_iterations", [&] {
    require_pointer(model, "model");
    require_pointer(iterations, "iterations");
    *iterations = model->iterations;
  });
}

int fastnorm_wheelset_step_status(const fastnorm_wheelset* model, fastnorm_step_status* status) {
  return guarded("fastnorm_wheelset_step_status", [&] {
    require_pointer(model, "model");
    require_pointer(status, "status");
    const wr::StepStatus& step = model->step;
    const bool failed = step.code == wr::StepStatus::Code::patch_failed;
    *status = {static_cast<int>(step.code), failed ? static_cast<int>(wr::wheel_index(step.side)) : -1, step.patch,
               static_cast<int>(step.solver_status)};
  });
}

int fastnorm_wheelset_patch_count(const fastnorm_wheelset* model, int wheel, int* count) {
  return guarded("fastnorm_wheelset_patch_count", [&] {
    require_pointer(model, "model");
    require_pointer(count, "count");
    FASTNORM_CHECK(wheel == 0 || wheel == 1, fastnorm::describe("wheel must be 0 (left) or 1 (right)", wheel));
    *count = static_cast<int>(model->patches[static_cast<std::size_t>(wheel)].size());
  });
}

int fastnorm_wheelset_patch(const fastnorm_wheelset* model, int wheel, int patch, fastnorm_patch* out) {
  return guarded("fastnorm_wheelset_patch", [&] {
    require_pointer(out, "out");
    const auto& contact = patch_of(model, wheel, patch);
    fastnorm_patch value{};
    const wr::PatchFrame& frame = contact.patch.frame;
    value.status = static_cast<int>(contact.solution.status);
    value.at_edge = contact.solution.at_edge ? 1 : 0;
    value.flange_climb = model->model.wheelset().at_flange_climb(contact.profile_y) ? 1 : 0;
    value.history = static_cast<int>(contact.history);
    value.contact_elements = static_cast<int>(contact.contact_elements);
    value.grid = grid_to_c(contact.patch.grid);
    copy3(frame.reference, value.reference);
    copy3(Eigen::Vector3d::UnitX(), value.e_x);
    copy3(frame.lateral_axis(), value.t_s);
    copy3(frame.normal(), value.normal);
    copy3(contact.centre, value.centre);
    copy3(contact.pressure_centre, value.pressure_centre);
    value.profile_y = contact.profile_y;
    value.normal_force = contact.normal_force;
    copy3(contact.force, value.force);
    copy3(contact.moment, value.moment);
    value.contact_angle = contact.contact_angle;
    value.approach = contact.approach;
    value.max_pressure = contact.max_pressure;
    value.stiffness = contact.stiffness;
    value.creepage = creepage_to_c(contact.creepage);
    value.creep = tangential_to_c(contact.traction);
    copy3(contact.creep_force, value.creep_force);
    *out = value;
  });
}

int fastnorm_wheelset_patch_pressure(const fastnorm_wheelset* model, int wheel, int patch, double* pressure) {
  return guarded("fastnorm_wheelset_patch_pressure", [&] {
    require_pointer(pressure, "pressure");
    const auto& values = patch_of(model, wheel, patch).solution.pressure;
    Eigen::Map<Eigen::VectorXd>(pressure, values.size()) = values;
  });
}

int fastnorm_wheelset_patch_traction(const fastnorm_wheelset* model, int wheel, int patch, double* traction_x,
                                     double* traction_s) {
  return guarded("fastnorm_wheelset_patch_traction", [&] {
    require_pointer(traction_x, "traction_x");
    require_pointer(traction_s, "traction_s");
    const auto& contact = patch_of(model, wheel, patch);
    const auto& traction = contact.traction;
    FASTNORM_CHECK(traction.traction_x.size() == contact.patch.grid.size(),
                   "the patch has no tractions: evaluate with fastnorm_wheelset_evaluate_moving");
    Eigen::Map<Eigen::VectorXd>(traction_x, traction.traction_x.size()) = traction.traction_x;
    Eigen::Map<Eigen::VectorXd>(traction_s, traction.traction_y.size()) = traction.traction_y;
  });
}

int fastnorm_wheelset_equilibrium(fastnorm_wheelset* model, double load, double y, double yaw,
                                  fastnorm_equilibrium* result) {
  return guarded("fastnorm_wheelset_equilibrium", [&] {
    require_pointer(model, "model");
    require_pointer(result, "result");
    model->equilibrium.reset();
    model->step = {};
    for (auto& patches : model->patches) patches.clear();
    model->equilibrium = wr::solve_equilibrium(model->model, y, yaw, load);
    const auto& found = *model->equilibrium;
    for (const auto& patch : found.patches) model->patches[wr::wheel_index(patch.patch.frame.side)].push_back(&patch);
    fastnorm_equilibrium value{};
    value.status = static_cast<int>(found.status);
    value.iterations = found.iterations;
    value.pose = {found.pose.y, found.pose.z, found.pose.roll, found.pose.yaw};
    value.vertical_force = found.vertical_force;
    value.lateral_force = found.lateral_force;
    for (std::size_t wheel = 0; wheel < 2; ++wheel) value.patch_count[wheel] = static_cast<int>(model->patches[wheel].size());
    *result = value;
  });
}

}  // extern "C"

int fastnorm_table_read(const char* path, fastnorm_table** table) {
  return guarded("fastnorm_table_read", [&] {
    require_pointer(path, "path");
    require_pointer(table, "table");
    *table = nullptr;
    *table = new fastnorm_table{fastnorm::read_contact_table(path)};
  });
}

void fastnorm_table_destroy(fastnorm_table* table) { delete table; }

int fastnorm_table_info(const fastnorm_table* table, int* pairs, int* outputs) {
  return guarded("fastnorm_table_info", [&] {
    require_pointer(table, "table");
    if (pairs) *pairs = static_cast<int>(table->table.pairs());
    if (outputs) *outputs = static_cast<int>(table->table.outputs());
  });
}

int fastnorm_table_output_index(const fastnorm_table* table, const char* name, int* index) {
  return guarded("fastnorm_table_output_index", [&] {
    require_pointer(table, "table");
    require_pointer(name, "name");
    require_pointer(index, "index");
    *index = static_cast<int>(table->table.output_index(name));
  });
}

int fastnorm_table_output_name(const fastnorm_table* table, int index, const char** name, const char** unit) {
  return guarded("fastnorm_table_output_name", [&] {
    require_pointer(table, "table");
    if (index < 0 || static_cast<std::size_t>(index) >= table->table.outputs())
      throw fastnorm::invalid_argument(
          "fastnorm: " + fastnorm::describe("index must be below the table's " +
                                                std::to_string(table->table.outputs()) + " outputs",
                                            index));
    if (name) *name = table->table.output_names()[static_cast<std::size_t>(index)].c_str();
    if (unit) *unit = table->table.output_units()[static_cast<std::size_t>(index)].c_str();
  });
}

int fastnorm_table_lookup(const fastnorm_table* table, int pair, double y, double yaw, double load,
                          int interpolation, double* out, int* found) {
  return guarded("fastnorm_table_lookup", [&] {
    require_pointer(table, "table");
    require_pointer(out, "out");
    require_pointer(found, "found");
    if (pair < 0) throw fastnorm::invalid_argument("fastnorm: " + fastnorm::describe("pair must not be negative", pair));
    if (interpolation != FASTNORM_TABLE_MULTILINEAR && interpolation != FASTNORM_TABLE_PCHIP)
      throw fastnorm::invalid_argument(
          "fastnorm: " + fastnorm::describe("interpolation must be FASTNORM_TABLE_MULTILINEAR (0) or "
                                            "FASTNORM_TABLE_PCHIP (1)",
                                            interpolation));
    const auto how = interpolation == FASTNORM_TABLE_PCHIP ? fastnorm::TableInterpolation::pchip
                                                           : fastnorm::TableInterpolation::multilinear;
    *found = static_cast<int>(table->table.lookup(static_cast<std::size_t>(pair), y, yaw, load, how, out));
  });
}
