// The compiled part of the Python module fastnorm (pybind11): solvers, .case files, the
// wheelset contact model and the static equilibrium, with NumPy arrays of shape (my, mx)
// and SI units in the keyword names (docs/bindings.md). fastnorm/__init__.py re-exports it;
// fastnorm/plot.py draws. Bad input raises fastnorm.FastnormError, a ValueError carrying the
// library's message. Solves release the GIL; an object that keeps state between calls
// (solve_next, the wheelset model) serialises its calls with its own mutex.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fastnorm/any_solver.hpp>
#include <fastnorm/case_file.hpp>
#include <fastnorm/contact_table_file.hpp>
#include <fastnorm/tangential_solver.hpp>
#include <fastnorm/version.hpp>
#include <fastnorm/wheelrail.hpp>


#include <algorithm>
#include <cstdint>
#include <array>
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace py = pybind11;
using namespace pybind11::literals;
namespace wr = fastnorm::wheelrail;

namespace {

using Grid = fastnorm::Grid<double>;
using Material = fastnorm::Material<double>;
using Solution = fastnorm::Solution<double>;
// C order: row j of a (my, mx) array is strip j, so element k = i + mx·j is [j, i].
using InputArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

py::ssize_t rows(const Grid& grid) { return static_cast<py::ssize_t>(grid.my()); }
py::ssize_t columns(const Grid& grid) { return static_cast<py::ssize_t>(grid.mx()); }

// The values of a (my, mx) array of the grid; `name` is the Python argument.
Eigen::VectorXd values_on(const Grid& grid, const InputArray& array, const char* name) {
  FASTNORM_CHECK(array.ndim() == 2 && array.shape(0) == rows(grid) && array.shape(1) == columns(grid),
                 std::string(name) + " must have shape (my, mx) = (" + std::to_string(grid.my()) + ", " +
                     std::to_string(grid.mx()) + ") of its grid");
  return Eigen::Map<const Eigen::VectorXd>(array.data(), grid.size());
}

template <typename Value, typename Vector>
py::array_t<Value> map_of(const Grid& grid, const Vector& values) {
  py::array_t<Value> map({rows(grid), columns(grid)});
  std::copy(values.data(), values.data() + values.size(), map.mutable_data());
  return map;
}

py::array_t<double> vector3(const Eigen::Vector3d& value) {
  py::array_t<double> array(3);
  std::copy(value.data(), value.data() + 3, array.mutable_data());
  return array;
}

// A number as Python's repr writes it (the shortest text that reads back the same).
std::string number(double value) { return py::repr(py::float_(value)).cast<std::string>(); }

std::string vector_text(const py::array_t<double>& values) {
  const double* data = values.data();
  return "[" + number(data[0]) + ", " + number(data[1]) + ", " + number(data[2]) + "]";
}

// A solver's answer as Python holds it.
struct PySolution {
  std::string status;
  std::string message;
  py::array_t<double> pressure;  // Pa, (my, mx)
  py::array_t<bool> in_contact;  // (my, mx)
  double normal_force = 0;       // N
  double approach = 0;           // m
  double residual = 0;
  int iterations = 0;
  Eigen::Index contact_count = 0;
  bool at_edge = false;
  bool ok = false;
  Solution solution;  // the C++ answer, for the tangential solve
};

PySolution to_python(const Grid& grid, const Solution& solution) {
  PySolution out;
  out.status = fastnorm::to_string(solution.status);
  out.message = solution.message;
  out.pressure = map_of<double>(grid, solution.pressure);
  out.in_contact = map_of<bool>(grid, solution.in_contact);
  out.normal_force = solution.normal_force;
  out.approach = solution.approach;
  out.residual = solution.residual;
  out.iterations = solution.iterations;
  out.contact_count = solution.contact_count();
  out.at_edge = solution.at_edge;
  out.ok = solution.ok();
  out.solution = solution;
  return out;
}

// A steady-rolling answer as Python holds it (tangential_solver.hpp, docs/tangential.md).
struct PyTangentialSolution {
  std::string status, message;
  bool ok = false;
  py::array_t<double> traction_x, traction_y;  // Pa on the rail, (my, mx)
  py::array_t<std::int8_t> state;              // 0 exterior, 1 adhesion, 2 slip, (my, mx)
  double force_x = 0, force_y = 0, spin_moment = 0, frictional_power_per_speed = 0, residual = 0;
  Eigen::Index adhesion_elements = 0, slip_elements = 0;
  int sweeps = 0;
};

// A tangential answer (the exact path's or FASTSIM's) on `grid`, copied out.
PyTangentialSolution to_python(const Grid& grid, const fastnorm::TangentialSolution<double>& answer) {
  PyTangentialSolution out;
  out.status = fastnorm::to_string(answer.status);
  out.message = answer.message;
  out.ok = answer.ok();
  out.traction_x = map_of<double>(grid, answer.traction_x);
  out.traction_y = map_of<double>(grid, answer.traction_y);
  Eigen::Matrix<std::int8_t, Eigen::Dynamic, 1> state(answer.state.size());
  for (Eigen::Index k = 0; k < state.size(); ++k) state(k) = static_cast<std::int8_t>(answer.state(k));
  out.state = map_of<std::int8_t>(grid, state);
  out.force_x = answer.force_x;
  out.force_y = answer.force_y;
  out.spin_moment = answer.spin_moment;
  out.frictional_power_per_speed = answer.frictional_power_per_speed;
  out.residual = answer.residual;
  out.adhesion_elements = answer.adhesion_elements;
  out.slip_elements = answer.slip_elements;
  out.sweeps = answer.sweeps;
  return out;
}

// The rolling direction a Python call names, '+x' or '-x'.
fastnorm::RollingDirection direction_of(const std::string& rolling) {
  FASTNORM_CHECK(rolling == "+x" || rolling == "-x", "rolling must be '+x' or '-x', not '" + rolling + "'");
  return rolling == "+x" ? fastnorm::RollingDirection::positive_x : fastnorm::RollingDirection::negative_x;
}

fastnorm::Creepage<double> creepage_of(double creepage_x, double creepage_y, double spin, double spin_centre_x,
                                       double spin_centre_y) {
  return {creepage_x, creepage_y, spin, spin_centre_x, spin_centre_y};
}

/// The exact tangential path's options: stop "largest_change" or "rms_change" (CONTACT's),
/// None keeping a default.
fastnorm::TangentialOptions<double> tangential_options_of(const std::string& stop, std::optional<double> tolerance,
                                                          std::optional<int> max_sweeps) {
  FASTNORM_CHECK(stop == "largest_change" || stop == "rms_change",
                 "stop must be 'largest_change' or 'rms_change', not '" + stop + "'");
  fastnorm::TangentialOptions<double> options;
  options.stop = stop == "rms_change" ? fastnorm::TangentialStop::rms_change : fastnorm::TangentialStop::largest_change;
  if (tolerance) options.tolerance = *tolerance;
  if (max_sweeps) options.max_sweeps = *max_sweeps;
  options.validate();
  return options;
}

PyTangentialSolution solve_steady_rolling(const Grid& grid, const Material& material, const PySolution& normal,
                                          double friction, double creepage_x, double creepage_y, double spin,
                                          double spin_centre_x, double spin_centre_y, const std::string& rolling,
                                          const std::string& stop, std::optional<double> tolerance,
                                          std::optional<int> max_sweeps) {
  const auto creepage = creepage_of(creepage_x, creepage_y, spin, spin_centre_x, spin_centre_y);
  const auto direction = direction_of(rolling);
  const auto options = tangential_options_of(stop, tolerance, max_sweeps);
  fastnorm::TangentialSolution<double> answer;
  {
    py::gil_scoped_release release;
    answer = fastnorm::solve_steady_rolling(grid, material, normal.solution, friction, creepage, direction, options);
  }
  return to_python(grid, answer);
}

// None: approach control; a number: force control (N).
fastnorm::Loading<double> loading_of(std::optional<double> normal_force) {
  return normal_force ? fastnorm::Loading<double>::force(*normal_force) : fastnorm::Loading<double>::approach();
}

// A tolerance given for a solver it does not apply to is refused (SolverSpec::set_cg_tolerance).
fastnorm::SolverSpec<double> spec_of(const std::string& name, std::optional<int> max_iterations,
                                     std::optional<double> tolerance, std::optional<double> gap_tolerance) {
  auto spec = fastnorm::SolverSpec<double>::parse(name);
  if (max_iterations) spec.set_max_iterations(*max_iterations);
  if (tolerance) spec.set_cg_tolerance(*tolerance);
  if (gap_tolerance) spec.set_gap_tolerance(*gap_tolerance);
  spec.validate();
  return spec;
}

// A solver by name. solve is cold and may run in several threads at once; solve_next and
// the stiffness keep the sequence's state, one call at a time.
class PySolver {
 public:
  PySolver(const std::string& name, const Grid& grid, const Material& material, std::optional<int> max_iterations,
           std::optional<double> tolerance, std::optional<double> gap_tolerance)
      : solver_(spec_of(name, max_iterations, tolerance, gap_tolerance), grid, material) {}

  PySolution solve(const InputArray& undeformed_distance, std::optional<double> normal_force) const {
    const Eigen::VectorXd h = values_on(grid(), undeformed_distance, "undeformed_distance_m");
    const auto loading = loading_of(normal_force);
    Solution solution;
    {
      py::gil_scoped_release released;
      solution = solver_.solve(h, loading);
    }
    return to_python(grid(), solution);
  }

  PySolution solve_next(const InputArray& undeformed_distance, std::optional<double> normal_force) {
    const Eigen::VectorXd h = values_on(grid(), undeformed_distance, "undeformed_distance_m");
    const auto loading = loading_of(normal_force);
    Solution solution;
    {
      py::gil_scoped_release released;
      const std::lock_guard<std::mutex> lock(sequence_);
      last_next_ = solver_.solve_next(h, loading);
      solution = last_next_;
    }
    return to_python(grid(), solution);
  }

  double normal_stiffness() {
    py::gil_scoped_release released;
    const std::lock_guard<std::mutex> lock(sequence_);
    FASTNORM_CHECK(last_next_.status != fastnorm::Status::not_solved, "no solve_next to take the stiffness of");
    return solver_.normal_stiffness(last_next_, solver_.workspace());
  }

  std::string name() const { return solver_.name(); }
  const Grid& grid() const { return solver_.grid(); }

 private:
  fastnorm::AnySolver<double> solver_;
  std::mutex sequence_;  // guards last_next_ and the solver's own workspace
  Solution last_next_;
};

// A .case file's content.
using Case = fastnorm::Case<double>;

// A case's steady-rolling problem (its tangential line), checked as the reader checks it.
fastnorm::CaseRolling<double> make_rolling(double friction, double creepage_x, double creepage_y, double spin,
                                           double spin_centre_x, double spin_centre_y, const std::string& rolling) {
  FASTNORM_CHECK(friction > 0 && std::isfinite(friction), fastnorm::describe("friction must be positive", friction));
  for (const auto& [value, name] : {std::pair<double, const char*>{creepage_x, "creepage_x"}, {creepage_y, "creepage_y"},
                                    {spin, "spin_per_m"}, {spin_centre_x, "spin_centre_x_m"},
                                    {spin_centre_y, "spin_centre_y_m"}}) {
    FASTNORM_CHECK(std::isfinite(value), fastnorm::describe(std::string(name) + " must be finite", value));
  }
  return {friction, creepage_of(creepage_x, creepage_y, spin, spin_centre_x, spin_centre_y), direction_of(rolling)};
}

Case make_case(const std::string& name, const Grid& grid, const Material& material,
               const InputArray& undeformed_distance, std::optional<double> normal_force, double stated_approach,
               std::optional<fastnorm::CaseRolling<double>> rolling) {
  fastnorm::check_case_material(material);  // what write_case can store
  return Case{name,
              "fastnorm Python module",
              grid,
              material,
              loading_of(normal_force),
              normal_force ? 0.0 : stated_approach,
              values_on(grid, undeformed_distance, "undeformed_distance_m"),
              std::nullopt,
              std::move(rolling)};
}

void write_case(const std::string& path, Case problem, const std::optional<PySolution>& solution) {
  if (solution) {
    fastnorm::CaseResult<double> stored;
    stored.normal_force = solution->normal_force;
    stored.approach = solution->approach;
    stored.contact_count = solution->contact_count;
    stored.iterations = solution->iterations;
    stored.pressure = values_on(problem.grid, solution->pressure, "solution.pressure_pa");
    problem.result = stored;
  }
  fastnorm::write_case_file(path, problem);
}

// One contact patch of the wheelset model, copied out. Track frame: x forward, y right, z down.
struct PyPatch {
  Grid grid{1, 1, 1, 1};
  PySolution solution;
  py::array_t<double> undeformed_distance;  // m, (my, mx), at approach 0
  py::array_t<double> reference, e_x, t_s, normal;  // the grid's frame
  py::array_t<double> centre, force, moment, pressure_centre;
  double normal_force = 0, contact_angle = 0, approach = 0, stiffness = 0, profile_y = 0, max_pressure = 0;
  double rolling_radius = 0;  // m, the wheel's radius at profile_y
  Eigen::Index contact_elements = 0;
  bool flange_climb = false;
  std::string history;
  // With velocities (docs/wheel-rail.md §10): creepages at reference, creep forces, else None.
  std::optional<PyTangentialSolution> traction;
  double creepage_x = 0, creepage_y = 0, spin = 0;
  py::array_t<double> creep_force;  // on the wheel, track frame (N)
};

PyPatch to_python(const wr::PatchContact& contact, const wr::Wheelset& wheelset) {
  PyPatch out;
  out.grid = contact.patch.grid;
  out.solution = to_python(contact.patch.grid, contact.solution);
  out.undeformed_distance = map_of<double>(contact.patch.grid, contact.patch.undeformed_distance);
  out.reference = vector3(contact.patch.frame.reference);
  out.e_x = vector3(Eigen::Vector3d::UnitX());
  out.t_s = vector3(contact.patch.frame.lateral_axis());
  out.normal = vector3(contact.patch.frame.normal());
  out.contact_elements = contact.contact_elements;
  out.centre = vector3(contact.centre);
  out.force = vector3(contact.force);
  out.moment = vector3(contact.moment);
  out.pressure_centre = vector3(contact.pressure_centre);
  out.normal_force = contact.normal_force;
  out.contact_angle = contact.contact_angle;
  out.approach = contact.approach;
  out.stiffness = contact.stiffness;
  out.profile_y = contact.profile_y;
  out.rolling_radius = wheelset.radius(contact.patch.frame.side, contact.profile_y).value;
  out.max_pressure = contact.max_pressure;
  out.flange_climb = wheelset.at_flange_climb(contact.profile_y);
  out.history = wr::to_string(contact.history);
  if (contact.traction.status != fastnorm::Status::not_solved) out.traction = to_python(contact.patch.grid, contact.traction);
  out.creepage_x = contact.creepage.longitudinal;
  out.creepage_y = contact.creepage.lateral;
  out.spin = contact.creepage.spin;
  out.creep_force = vector3(contact.creep_force);
  return out;
}

struct PyWheel {
  std::string side;
  std::vector<PyPatch> patches;
  py::array_t<double> force, moment;
  double normal_force = 0;
  bool flange_climb = false;
  wr::StepStatus status;
  int iterations = 0;
};

struct PyWheelsetResult {
  wr::WheelsetPose pose;
  std::vector<PyWheel> wheels;  // left, right
  py::array_t<double> force, moment;
  wr::StepStatus status;
  int iterations = 0;
};

struct PyEquilibrium {
  std::string status, message;
  wr::WheelsetPose pose;
  std::vector<PyWheel> wheels;  // left, right: the loaded patches at pose
  double vertical_force = 0, lateral_force = 0, vertical_residual = 0, roll_residual = 0;
  int iterations = 0;
  bool ok = false;
};

// The patches of both wheels, summed per wheel (the equilibrium's list, split by rail).
std::vector<PyWheel> wheels_of(const std::vector<wr::PatchContact>& patches, const wr::Wheelset& wheelset) {
  std::vector<PyWheel> wheels(2);
  wheels[0].side = "left";
  wheels[1].side = "right";
  std::array<Eigen::Vector3d, 2> force{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  std::array<Eigen::Vector3d, 2> moment = force;
  for (const auto& patch : patches) {
    const std::size_t wheel = wr::wheel_index(patch.patch.frame.side);
    wheels[wheel].patches.push_back(to_python(patch, wheelset));
    wheels[wheel].normal_force += patch.normal_force;
    wheels[wheel].flange_climb = wheels[wheel].flange_climb || wheels[wheel].patches.back().flange_climb;
    force[wheel] += patch.force;
    moment[wheel] += patch.moment;
  }
  for (std::size_t wheel = 0; wheel < 2; ++wheel) {
    wheels[wheel].force = vector3(force[wheel]);
    wheels[wheel].moment = vector3(moment[wheel]);
  }
  return wheels;
}

// A time-loop step's result, every patch's arrays copied.
PyWheelsetResult to_python(const wr::WheelsetContactResult& result, const wr::Wheelset& wheelset) {
  PyWheelsetResult out;
  out.pose = result.pose;
  for (const auto& wheel : result.wheels) {
    PyWheel copy;
    copy.side = wr::to_string(wheel.side);
    for (const auto& patch : wheel.patches) copy.patches.push_back(to_python(patch, wheelset));
    copy.force = vector3(wheel.force);
    copy.moment = vector3(wheel.moment);
    copy.normal_force = wheel.normal_force;
    copy.flange_climb = wheel.flange_climb;
    copy.status = wheel.status;
    copy.iterations = wheel.iterations;
    out.wheels.push_back(std::move(copy));
  }
  out.force = vector3(result.force);
  out.moment = vector3(result.moment);
  out.status = result.status;
  out.iterations = result.iterations;
  return out;
}

// The wheelset contact model of the time loop and the equilibrium on the same set-up.
class PyWheelset {
 public:
  PyWheelset(const wr::WheelsetOnTrack& setup, const wr::WheelsetContactOptions& options)
      : model_(setup.track(), setup.wheelset(), options) {}

  // The arrays are made from the model's own result while the model stays locked, so the
  // result is copied once, into them (docs/bindings.md, "Results are copies"). The GIL is
  // released while waiting for the lock and while solving, and taken back for the arrays;
  // no call takes calls_ while it holds the GIL, so the two cannot deadlock.
  PyWheelsetResult evaluate(const wr::WheelsetPose& pose, const std::optional<wr::WheelsetVelocity>& velocity) {
    py::gil_scoped_release released;
    const std::lock_guard<std::mutex> lock(calls_);
    const wr::WheelsetContactResult& result = velocity ? model_.evaluate(pose, *velocity) : model_.evaluate(pose);
    py::gil_scoped_acquire held;
    return to_python(result, model_.wheelset());
  }

  void set_iteration_budget(int iterations) {
    py::gil_scoped_release released;
    const std::lock_guard<std::mutex> lock(calls_);
    model_.set_iteration_budget(iterations);
  }
  int iteration_budget() const { return model_.iteration_budget(); }

  PyEquilibrium equilibrium(double load, double y, double yaw, double force_tolerance, int max_iterations) {
    wr::EquilibriumOptions options;
    options.force_tolerance = force_tolerance;
    options.max_iterations = max_iterations;
    std::optional<wr::Equilibrium> found;
    {
      py::gil_scoped_release released;
      const std::lock_guard<std::mutex> lock(calls_);
      found = wr::solve_equilibrium(model_, y, yaw, load, options);
    }
    PyEquilibrium out;
    out.status = wr::to_string(found->status);
    out.message = found->message;
    out.pose = found->pose;
    out.wheels = wheels_of(found->patches, model_.wheelset());
    out.vertical_force = found->vertical_force;
    out.lateral_force = found->lateral_force;
    out.vertical_residual = found->vertical_residual;
    out.roll_residual = found->roll_residual;
    out.iterations = found->iterations;
    out.ok = found->ok();
    return out;
  }

  double flange_angle() const { return model_.wheelset().flange_angle(); }

  std::string description() const {
    return "WheelsetContact(solver='" + model_.options().solver.name() + "', element_length_m=" +
           number(model_.element_length()) + ", element_width_m=" + number(model_.element_width()) + ")";
  }

  void reset() {
    py::gil_scoped_release released;
    const std::lock_guard<std::mutex> lock(calls_);
    model_.reset();
  }

  void save_history() {
    py::gil_scoped_release released;
    const std::lock_guard<std::mutex> lock(calls_);
    model_.history(saved_);
    has_saved_ = true;
  }

  void restore_history() {
    py::gil_scoped_release released;
    const std::lock_guard<std::mutex> lock(calls_);
    FASTNORM_CHECK(has_saved_, "WheelsetContact.restore_history: no history saved (save_history first)");
    model_.restore(saved_);
  }

  // A model of its own sharing this one's read-only tables (WheelsetContact's copy), taken
  // while this one is locked.
  std::unique_ptr<PyWheelset> copy() {
    py::gil_scoped_release released;
    const std::lock_guard<std::mutex> lock(calls_);
    return std::unique_ptr<PyWheelset>(new PyWheelset(*this));
  }

 private:
  // The model, its saved history and whether it has one; a lock of its own. Only copy()
  // calls it, with `other` locked.
  PyWheelset(const PyWheelset& other) : model_(other.model_), saved_(other.saved_), has_saved_(other.has_saved_) {}

  wr::WheelsetContact<> model_;
  wr::WheelsetContact<>::History saved_;  // save_history's one slot
  bool has_saved_ = false;
  std::mutex calls_;  // evaluate changes the model's state
};

std::unique_ptr<PyWheelset> make_wheelset(const std::string& solver, Eigen::Index elements,
                                          std::optional<std::string> wheel_profile,
                                          std::optional<std::string> rail_profile, double nominal_radius,
                                          double gauge, double cant, const Material& material, bool stiffness,
                                          std::optional<int> max_iterations, std::optional<double> tolerance,
                                          std::optional<double> gap_tolerance, double distance_tolerance,
                                          double distance_node_spacing, bool distance_everywhere,
                                          std::optional<double> friction, const std::string& creep_method,
                                          int warm_solve_iterations) {
  wr::WheelsetOnTrack setup;
  setup.wheel_profile = wheel_profile.value_or("");
  setup.rail_profile = rail_profile.value_or("");
  setup.nominal_radius = nominal_radius;
  setup.gauge = gauge;
  setup.cant = cant;
  wr::WheelsetContactOptions options;
  options.solver = spec_of(solver, max_iterations, tolerance, gap_tolerance);
  options.grid.elements = elements;
  options.material = material;
  options.stiffness = stiffness;
  options.distance.tolerance = distance_tolerance;
  options.distance.node_spacing = distance_node_spacing;
  options.distance_everywhere = distance_everywhere;
  options.warm_solve_iterations = warm_solve_iterations;
  options.creep.friction = friction;
  if (creep_method == "fastsim") {
    options.creep.method = wr::CreepMethod::fastsim;
  } else if (creep_method != "strip_theory") {
    throw fastnorm::invalid_argument("creep_method must be 'strip_theory' or 'fastsim', not '" + creep_method + "'");
  }
  return std::make_unique<PyWheelset>(setup, options);
}

std::string version() {
  return std::to_string(FASTNORM_VERSION_MAJOR) + "." + std::to_string(FASTNORM_VERSION_MINOR) + "." +
         std::to_string(FASTNORM_VERSION_PATCH);
}

void bind_basics(py::module_& m) {
  py::class_<Grid>(m, "Grid",
                   "A regular grid of mx × my rectangles of dx_m × dy_m (m); (x0_m, y0_m) is the centre of element "
                   "(0, 0). x is the rolling direction; arrays over a grid have shape (my, mx).")
      .def(py::init<Eigen::Index, Eigen::Index, double, double, double, double>(), "mx"_a, "my"_a, "dx_m"_a,
           "dy_m"_a, "x0_m"_a = 0.0, "y0_m"_a = 0.0)
      .def_property_readonly("mx", &Grid::mx)
      .def_property_readonly("my", &Grid::my)
      .def_property_readonly("dx_m", &Grid::dx)
      .def_property_readonly("dy_m", &Grid::dy)
      .def_property_readonly("x0_m", &Grid::x0)
      .def_property_readonly("y0_m", &Grid::y0)
      .def_property_readonly("shape", [](const Grid& grid) { return py::make_tuple(grid.my(), grid.mx()); },
                             "(my, mx), the shape of arrays over the grid")
      .def("__repr__", [](const Grid& grid) {
        return "Grid(mx=" + std::to_string(grid.mx()) + ", my=" + std::to_string(grid.my()) +
               ", dx_m=" + number(grid.dx()) + ", dy_m=" + number(grid.dy()) +
               ", x0_m=" + number(grid.x0()) + ", y0_m=" + number(grid.y0()) +
               ")";
      });

  py::class_<Material>(m, "Material",
                       "Young's modulus (Pa) and Poisson's ratio of the wheel (body 1) and the rail (body 2); "
                       "Material(young_modulus_pa, poisson_ratio) gives both bodies the same.")
      .def(py::init<double, double>(), "young_modulus_pa"_a, "poisson_ratio"_a)
      .def(py::init<double, double, double, double>(), "young_modulus_1_pa"_a, "poisson_ratio_1"_a,
           "young_modulus_2_pa"_a, "poisson_ratio_2"_a)
      .def_property_readonly("young_modulus_1_pa", [](const Material& value) { return value.young_modulus(1); })
      .def_property_readonly("poisson_ratio_1", [](const Material& value) { return value.poisson_ratio(1); })
      .def_property_readonly("young_modulus_2_pa", [](const Material& value) { return value.young_modulus(2); })
      .def_property_readonly("poisson_ratio_2", [](const Material& value) { return value.poisson_ratio(2); })
      .def_property_readonly("combined_modulus_pa", &Material::combined_modulus, "E* (Pa), docs/design.md §2")
      .def("__repr__", [](const Material& value) {
        return "Material(young_modulus_1_pa=" + number(value.young_modulus(1)) +
               ", poisson_ratio_1=" + number(value.poisson_ratio(1)) + ", young_modulus_2_pa=" +
               number(value.young_modulus(2)) + ", poisson_ratio_2=" + number(value.poisson_ratio(2)) + ")";
      });

  py::class_<PySolution>(m, "Solution", "A solver's answer.")
      .def_readonly("status", &PySolution::status,
                    "'converged', 'no contact', 'iteration limit', 'cycled', 'budget reached', ...")
      .def_readonly("message", &PySolution::message, "why, when not converged")
      .def_readonly("ok", &PySolution::ok, "a usable answer ('converged', 'no contact', 'cycled' or 'budget reached')")
      .def_readonly("pressure_pa", &PySolution::pressure, "pressures (Pa), shape (my, mx)")
      .def_readonly("in_contact", &PySolution::in_contact, "the contact set, bool, shape (my, mx)")
      .def_readonly("normal_force_n", &PySolution::normal_force, "Fn (N)")
      .def_readonly("approach_m", &PySolution::approach, "the rigid approach found in force control (m)")
      .def_readonly("residual", &PySolution::residual, "the solver's relative measure of the Signorini conditions")
      .def_readonly("iterations", &PySolution::iterations, "active-set solves or CG iterations")
      .def_readonly("contact_count", &PySolution::contact_count, "elements in contact")
      .def_readonly("at_edge", &PySolution::at_edge, "contact touches the grid's boundary (make the grid larger)")
      .def("__repr__", [](const PySolution& s) {
        return "Solution(status='" + s.status + "', normal_force_n=" + number(s.normal_force) +
               ", contact_count=" + std::to_string(s.contact_count) + ")";
      });

  py::class_<PySolver>(m, "Solver",
                       "A solver on a grid and material, by name: 'norm', 'cg', 'elliptic', 'polynomial[:G]', "
                       "'elliptic-edge[:K]', 'polynomial-edge[:G[:K]]'. max_iterations: active-set solves (200) or "
                       "CG iterations (5000); tolerance: CG's stopping tolerance (1e-9), CG only; gap_tolerance: the "
                       "join tolerance of NORM and the reduced solvers (relative to max|h|; NORM 1000 eps, reduced "
                       "3e-5), not CG; None keeps the default. A tolerance for a solver it does not apply to raises.")
      .def(py::init<const std::string&, const Grid&, const Material&, std::optional<int>, std::optional<double>,
                    std::optional<double>>(),
           "name"_a, "grid"_a, "material"_a, py::kw_only(), "max_iterations"_a = py::none(),
           "tolerance"_a = py::none(), "gap_tolerance"_a = py::none())
      .def("solve", &PySolver::solve, "undeformed_distance_m"_a, py::kw_only(), "normal_force_n"_a = py::none(),
           "A cold solve on h (m, + = gap, shape (my, mx)). Without normal_force_n: approach control, h holds the "
           "approach; with it (N): force control. Threads may call it at once; the GIL is released.")
      .def("solve_next", &PySolver::solve_next, "undeformed_distance_m"_a, py::kw_only(),
           "normal_force_n"_a = py::none(),
           "The next problem of a sequence, started from the previous solve_next's contact set (NORM and CG: the "
           "cold answer, sooner; a reduced solver's may differ within its accuracy).")
      .def("normal_stiffness_n_per_m", &PySolver::normal_stiffness,
           "dFn/d(approach) (N/m) at the contact set of the last solve_next")
      .def_property_readonly("name", &PySolver::name)
      .def_property_readonly("grid", &PySolver::grid)
      .def("__repr__", [](const PySolver& solver) {
        return "Solver('" + solver.name() + "', grid=" + std::to_string(solver.grid().mx()) + "x" +
               std::to_string(solver.grid().my()) + ")";
      });
}

void bind_tangential(py::module_& m) {
  py::class_<PyTangentialSolution>(m, "TangentialSolution",
                                   "Steady rolling's answer: tractions and forces on the rail (body 1), docs/tangential.md.")
      .def_readonly("status", &PyTangentialSolution::status, "'converged' or 'iteration limit' ('no contact')")
      .def_readonly("message", &PyTangentialSolution::message)
      .def_readonly("ok", &PyTangentialSolution::ok, "converged")
      .def_readonly("traction_x_pa", &PyTangentialSolution::traction_x, "tractions along x (Pa), shape (my, mx)")
      .def_readonly("traction_y_pa", &PyTangentialSolution::traction_y, "tractions along y (Pa), shape (my, mx)")
      .def_readonly("state", &PyTangentialSolution::state, "0 exterior, 1 adhesion, 2 slip; int8, shape (my, mx)")
      .def_readonly("force_x_n", &PyTangentialSolution::force_x, "Fx (N): positive creepage_x gives a negative Fx")
      .def_readonly("force_y_n", &PyTangentialSolution::force_y, "Fy (N)")
      .def_readonly("spin_moment_nm", &PyTangentialSolution::spin_moment,
                    "Mz = sum dA (x p_y - y p_x) about the grid's origin (N m)")
      .def_readonly("frictional_power_per_speed_n", &PyTangentialSolution::frictional_power_per_speed,
                    "sum dA |p||s| over the slip area (N); times the rolling speed (m/s): W")
      .def_readonly("adhesion_elements", &PyTangentialSolution::adhesion_elements)
      .def_readonly("slip_elements", &PyTangentialSolution::slip_elements)
      .def_readonly("sweeps", &PyTangentialSolution::sweeps)
      .def_readonly("residual", &PyTangentialSolution::residual)
      .def("__repr__", [](const PyTangentialSolution& s) {
        return "TangentialSolution(status='" + s.status + "', force_x_n=" + number(s.force_x) +
               ", force_y_n=" + number(s.force_y) + ", spin_moment_nm=" + number(s.spin_moment) +
               ", adhesion_elements=" + std::to_string(s.adhesion_elements) +
               ", slip_elements=" + std::to_string(s.slip_elements) + ")";
      });
  m.def("solve_steady_rolling", &solve_steady_rolling, "grid"_a, "material"_a, "normal"_a, py::kw_only(),
        "friction"_a, "creepage_x"_a = 0.0, "creepage_y"_a = 0.0, "spin_per_m"_a = 0.0, "spin_centre_x_m"_a = 0.0,
        "spin_centre_y_m"_a = 0.0, "rolling"_a = "+x", "stop"_a = "largest_change", "tolerance"_a = py::none(),
        "max_sweeps"_a = py::none(),
        "Steady rolling with Coulomb friction on the normal solution `normal` (a Solution on `grid`), CONTACT's "
        "conventions: creepages of the rail (body 1) against the wheel, rigid slip (xi - phi (y - y0), eta + phi "
        "(x - x0)) about the spin centre (x0, y0) in the grid's coordinates, rolling towards '+x' or '-x' "
        "(docs/tangential.md). The sweeps stop by `stop`: 'largest_change' (no traction changing by more than "
        "tolerance * mu max p_n, default 1e-9) or 'rms_change' (CONTACT's rule: the rms of a sweep's traction "
        "changes at most tolerance times the tractions', its EPS; 1e-5 in its wheel-rail runs), or after "
        "max_sweeps (default 2000).");
}

void bind_case_files(py::module_& m) {
  py::class_<fastnorm::CaseResult<double>>(m, "CaseResult", "The solution part a .case file stores.")
      .def_readonly("normal_force_n", &fastnorm::CaseResult<double>::normal_force)
      .def_readonly("approach_m", &fastnorm::CaseResult<double>::approach)
      .def_readonly("contact_count", &fastnorm::CaseResult<double>::contact_count)
      .def_readonly("iterations", &fastnorm::CaseResult<double>::iterations)
      .def("__repr__", [](const fastnorm::CaseResult<double>& stored) {
        return "CaseResult(normal_force_n=" + number(stored.normal_force) + ", approach_m=" +
               number(stored.approach) + ", contact_count=" + std::to_string(stored.contact_count) + ")";
      });

  using Rolling = fastnorm::CaseRolling<double>;
  py::class_<Rolling>(m, "CaseRolling",
                      "A case's steady-rolling problem, its tangential line (docs/case-format.md): Coulomb's "
                      "friction, the creepages of the rail (body 1) against the wheel about the spin centre "
                      "(grid coordinates, m), and the rolling direction.")
      .def(py::init(&make_rolling), "friction"_a, py::kw_only(), "creepage_x"_a = 0.0, "creepage_y"_a = 0.0,
           "spin_per_m"_a = 0.0, "spin_centre_x_m"_a = 0.0, "spin_centre_y_m"_a = 0.0, "rolling"_a = "+x")
      .def_readonly("friction", &Rolling::friction)
      .def_property_readonly("creepage_x", [](const Rolling& r) { return r.creepage.longitudinal; })
      .def_property_readonly("creepage_y", [](const Rolling& r) { return r.creepage.lateral; })
      .def_property_readonly("spin_per_m", [](const Rolling& r) { return r.creepage.spin; })
      .def_property_readonly("spin_centre_x_m", [](const Rolling& r) { return r.creepage.spin_centre_x; })
      .def_property_readonly("spin_centre_y_m", [](const Rolling& r) { return r.creepage.spin_centre_y; })
      .def_property_readonly("rolling", [](const Rolling& r) {
        return std::string(r.direction == fastnorm::RollingDirection::positive_x ? "+x" : "-x");
      })
      .def("__repr__", [](const Rolling& r) {
        return "CaseRolling(friction=" + number(r.friction) + ", creepage_x=" + number(r.creepage.longitudinal) +
               ", creepage_y=" + number(r.creepage.lateral) + ", spin_per_m=" + number(r.creepage.spin) +
               ", rolling='" + (r.direction == fastnorm::RollingDirection::positive_x ? "+x" : "-x") + "')";
      });

  py::class_<Case>(m, "Case",
                   "A normal-contact problem as a .case file stores it (docs/case-format.md). Without "
                   "normal_force_n it is approach-controlled: h already holds the approach, stated_approach_m "
                   "is for information.")
      .def(py::init(&make_case), "name"_a, "grid"_a, "material"_a, "undeformed_distance_m"_a, py::kw_only(),
           "normal_force_n"_a = py::none(), "stated_approach_m"_a = 0.0, "rolling"_a = py::none())
      .def_readonly("name", &Case::name)
      .def_readonly("source", &Case::source)
      .def_readonly("grid", &Case::grid)
      .def_readonly("material", &Case::material)
      .def_property_readonly("normal_force_n",
                             [](const Case& problem) -> std::optional<double> {
                               if (problem.loading.control != fastnorm::Control::force) return std::nullopt;
                               return problem.loading.normal_force;
                             },
                             "Fn (N) in force control, None in approach control")
      .def_readonly("stated_approach_m", &Case::stated_approach)
      .def_property_readonly("undeformed_distance_m",
                             [](const Case& problem) { return map_of<double>(problem.grid, problem.undeformed_distance); },
                             "h (m, + = gap), shape (my, mx)")
      .def_property_readonly("rolling", [](const Case& problem) { return problem.rolling; },
                             "the steady-rolling problem of its tangential line (a CaseRolling), or None")
      .def_property_readonly("result", [](const Case& problem) { return problem.result; },
                             "the stored solution's numbers, or None")
      .def_property_readonly("result_pressure_pa",
                             [](const Case& problem) -> std::optional<py::array_t<double>> {
                               if (!problem.result) return std::nullopt;
                               return map_of<double>(problem.grid, problem.result->pressure);
                             },
                             "the stored pressures (Pa), shape (my, mx), or None")
      .def("__repr__", [](const Case& problem) {
        const bool force = problem.loading.control == fastnorm::Control::force;
        return "Case('" + problem.name + "', grid=" + std::to_string(problem.grid.mx()) + "x" +
               std::to_string(problem.grid.my()) +
               (force ? ", normal_force_n=" + number(problem.loading.normal_force) : std::string(", approach control")) +
               (problem.rolling ? ", with rolling" : "") + (problem.result ? ", with result" : "") + ")";
      });

  m.def("read_case", &fastnorm::read_case_file<double>, "path"_a, "Reads a .case file.");
  m.def("write_case", &write_case, "path"_a, "case"_a, "solution"_a = py::none(),
        "Writes a .case file at full precision, with a solution part when a Solution is given.");
}

void bind_wheelset(py::module_& m) {
  py::class_<wr::WheelsetPose>(m, "Pose",
                               "The wheelset's position on the track: lateral shift y (m), vertical z (m, down; 0 "
                               "puts the taping-line points in the track plane), roll about x (rad, > 0 lowers the "
                               "right wheel), yaw about the rolled z axis (rad).")
      .def(py::init([](double y, double z, double roll, double yaw) { return wr::WheelsetPose{y, z, roll, yaw}; }),
           py::kw_only(), "lateral_shift_m"_a = 0.0, "vertical_m"_a = 0.0, "roll_rad"_a = 0.0, "yaw_rad"_a = 0.0)
      .def_readonly("lateral_shift_m", &wr::WheelsetPose::y)
      .def_readonly("vertical_m", &wr::WheelsetPose::z)
      .def_readonly("roll_rad", &wr::WheelsetPose::roll)
      .def_readonly("yaw_rad", &wr::WheelsetPose::yaw)
      .def("__repr__", [](const wr::WheelsetPose& pose) {
        return "Pose(lateral_shift_m=" + number(pose.y) + ", vertical_m=" +
               number(pose.z) + ", roll_rad=" + number(pose.roll) +
               ", yaw_rad=" + number(pose.yaw) + ")";
      });

  py::class_<wr::WheelsetVelocity>(m, "Velocity",
                                   "The wheelset's velocities, the rates of its pose (docs/wheel-rail.md §10): forward "
                                   "speed V along the track (not 0), lateral and vertical (m/s), roll, yaw and pitch "
                                   "rates (rad/s; pitch -V/r rolling without slip on radius r, z down).")
      .def(py::init([](double forward, double lateral, double vertical, double roll_rate, double yaw_rate,
                       double pitch_rate) {
             return wr::WheelsetVelocity{forward, lateral, vertical, roll_rate, yaw_rate, pitch_rate};
           }),
           py::kw_only(), "forward_m_per_s"_a, "lateral_m_per_s"_a = 0.0, "vertical_m_per_s"_a = 0.0,
           "roll_rate_rad_per_s"_a = 0.0, "yaw_rate_rad_per_s"_a = 0.0, "pitch_rate_rad_per_s"_a = 0.0)
      .def_readonly("forward_m_per_s", &wr::WheelsetVelocity::forward)
      .def_readonly("lateral_m_per_s", &wr::WheelsetVelocity::lateral)
      .def_readonly("vertical_m_per_s", &wr::WheelsetVelocity::vertical)
      .def_readonly("roll_rate_rad_per_s", &wr::WheelsetVelocity::roll_rate)
      .def_readonly("yaw_rate_rad_per_s", &wr::WheelsetVelocity::yaw_rate)
      .def_readonly("pitch_rate_rad_per_s", &wr::WheelsetVelocity::pitch_rate)
      .def("__repr__", [](const wr::WheelsetVelocity& v) {
        return "Velocity(forward_m_per_s=" + number(v.forward) + ", lateral_m_per_s=" + number(v.lateral) +
               ", vertical_m_per_s=" + number(v.vertical) + ", roll_rate_rad_per_s=" + number(v.roll_rate) +
               ", yaw_rate_rad_per_s=" + number(v.yaw_rate) + ", pitch_rate_rad_per_s=" + number(v.pitch_rate) + ")";
      });

  py::class_<PyPatch>(m, "Patch", "One contact patch. Track frame: x forward, y right, z down.")
      .def_readonly("grid", &PyPatch::grid, "the patch's grid in its tangent plane")
      .def_readonly("solution", &PyPatch::solution, "pressures on grid and the solve's status")
      .def_readonly("undeformed_distance_m", &PyPatch::undeformed_distance, "h at approach 0 (m), shape (my, mx)")
      .def_readonly("reference_m", &PyPatch::reference,
                    "the grid's origin P on the rail (m): element [j, i] lies at reference_m + x_i e_x + s_j t_s")
      .def_readonly("e_x", &PyPatch::e_x, "the grid's x axis, the rolling direction")
      .def_readonly("t_s", &PyPatch::t_s, "the grid's y axis, lateral in the tangent plane")
      .def_readonly("normal", &PyPatch::normal, "n, the normal into the rail")
      .def_readonly("contact_elements", &PyPatch::contact_elements)
      .def_readonly("normal_force_n", &PyPatch::normal_force, "Fn (N)")
      .def_readonly("force_n", &PyPatch::force, "the contact force on the wheel, track frame (N): the normal force, "
                    "plus creep_force_n with a velocity")
      .def_readonly("moment_nm", &PyPatch::moment, "its moment about the wheelset centre (N m)")
      .def_readonly("centre_m", &PyPatch::centre, "the contact reference point (m)")
      .def_readonly("pressure_centre_m", &PyPatch::pressure_centre, "the centroid of the pressure (m)")
      .def_readonly("contact_angle_rad", &PyPatch::contact_angle, "of the normal from the vertical, + towards the "
                                                                   "track centre (rad)")
      .def_readonly("approach_m", &PyPatch::approach, "the rigid interpenetration (m)")
      .def_readonly("stiffness_n_per_m", &PyPatch::stiffness, "dFn/d(approach) (N/m); NaN when not asked for")
      .def_readonly("profile_y_m", &PyPatch::profile_y, "wheel profile coordinate y_w of the reference point (m)")
      .def_readonly("rolling_radius_m", &PyPatch::rolling_radius,
                    "the wheel's rolling radius at profile_y_m: the nominal radius plus the profile there (m)")
      .def_readonly("max_pressure_pa", &PyPatch::max_pressure)
      .def_readonly("flange_climb", &PyPatch::flange_climb, "the reference point is on the flange's steepest flank "
                                                            "or beyond")
      .def_readonly("history", &PyPatch::history, "'continued', 'appeared', 'merged' or 'split' since the last call")
      .def_readonly("traction", &PyPatch::traction,
                    "with a velocity: the tractions on the rail in the patch frame (x along e_x, y along t_s), "
                    "their force_x_n = Fx, force_y_n = Fs and spin_moment_nm = Mn about reference_m, the areas "
                    "(the model's creep_method, docs/wheel-rail.md §10); None without")
      .def_readonly("creepage_x", &PyPatch::creepage_x, "xi of the rail against the wheel at reference_m (0 without velocity)")
      .def_readonly("creepage_y", &PyPatch::creepage_y, "eta, along t_s")
      .def_readonly("spin_per_m", &PyPatch::spin, "phi (rad/m) about the normal")
      .def_readonly("creep_force_n", &PyPatch::creep_force,
                    "the creep force on the wheel, -(Fx e_x + Fs t_s), track frame (N); included in force_n")
      .def("__repr__", [](const PyPatch& patch) {
        return "Patch(normal_force_n=" + number(patch.normal_force) + ", contact_angle_rad=" +
               number(patch.contact_angle) + ", profile_y_m=" + number(patch.profile_y) + ", grid=" +
               std::to_string(patch.grid.mx()) + "x" + std::to_string(patch.grid.my()) + ", contact_elements=" +
               std::to_string(patch.contact_elements) + ", status='" + patch.solution.status + "', history='" +
               patch.history + "')";
      });

  py::class_<wr::StepStatus>(m, "StepStatus",
                             "How an evaluate ended: ok, or the first patch whose solve gave no usable answer.")
      .def_property_readonly("code", [](const wr::StepStatus& status) { return wr::to_string(status.code); },
                             "'ok', 'patch failed' or 'not solved'")
      .def_property_readonly("ok", &wr::StepStatus::ok)
      .def_property_readonly("wheel",
                             [](const wr::StepStatus& status) -> std::optional<std::string> {
                               if (status.patch < 0) return std::nullopt;
                               return wr::to_string(status.side);
                             },
                             "'left' or 'right' for the failed patch, else None")
      .def_property_readonly("patch",
                             [](const wr::StepStatus& status) -> std::optional<int> {
                               if (status.patch < 0) return std::nullopt;
                               return status.patch;
                             },
                             "the failed patch's index in its wheel's patches, else None")
      .def_property_readonly("solver_status",
                             [](const wr::StepStatus& status) { return fastnorm::to_string(status.solver_status); })
      .def_readonly("message", &wr::StepStatus::message)
      .def("__repr__", [](const wr::StepStatus& status) {
        return std::string("StepStatus('") + wr::to_string(status.code) + "'" +
               (status.message.empty() ? "" : ", '" + status.message + "'") + ")";
      });

  py::class_<PyWheel>(m, "Wheel", "One wheel's patches (tread first) and totals.")
      .def_readonly("side", &PyWheel::side)
      .def_readonly("patches", &PyWheel::patches)
      .def_readonly("force_n", &PyWheel::force)
      .def_readonly("moment_nm", &PyWheel::moment)
      .def_readonly("normal_force_n", &PyWheel::normal_force)
      .def_readonly("flange_climb", &PyWheel::flange_climb)
      .def_readonly("status", &PyWheel::status, "this wheel's StepStatus")
      .def_readonly("iterations", &PyWheel::iterations, "the solver iterations its patch solves spent")
      .def("__repr__", [](const PyWheel& wheel) {
        return "Wheel(side='" + wheel.side + "', patches=" + std::to_string(wheel.patches.size()) +
               ", normal_force_n=" + number(wheel.normal_force) + ", flange_climb=" +
               (wheel.flange_climb ? "True" : "False") + ", status='" + wr::to_string(wheel.status.code) + "')";
      });

  py::class_<PyWheelsetResult>(m, "WheelsetResult", "Both wheels at one pose.")
      .def_readonly("pose", &PyWheelsetResult::pose)
      .def_readonly("wheels", &PyWheelsetResult::wheels, "[left, right]")
      .def_readonly("force_n", &PyWheelsetResult::force, "on the wheelset, track frame (N)")
      .def_readonly("moment_nm", &PyWheelsetResult::moment, "about its centre (N m)")
      .def_readonly("iterations", &PyWheelsetResult::iterations,
                    "the solver iterations the step spent (what iteration_budget counts)")
      .def_readonly("status", &PyWheelsetResult::status,
                    "StepStatus: ok, or the first failed patch (wheel, patch, solver status, message)")
      .def_property_readonly("ok", [](const PyWheelsetResult& result) { return result.status.ok(); },
                             "every patch solved with a usable answer")
      .def("__repr__", [](const PyWheelsetResult& result) {
        return "WheelsetResult(patches=" + std::to_string(result.wheels[0].patches.size()) + "+" +
               std::to_string(result.wheels[1].patches.size()) + ", force_n=" + vector_text(result.force) +
               ", status='" + wr::to_string(result.status.code) + "')";
      });

  py::class_<PyEquilibrium>(m, "Equilibrium", "The static equilibrium of a loaded wheelset.")
      .def_readonly("status", &PyEquilibrium::status,
                    "'converged', 'lost contact', 'not converged', 'solver failed' or 'flange climb'")
      .def_readonly("message", &PyEquilibrium::message)
      .def_readonly("ok", &PyEquilibrium::ok)
      .def_readonly("pose", &PyEquilibrium::pose, "z and roll found; y and yaw as given")
      .def_readonly("wheels", &PyEquilibrium::wheels, "[left, right], their patches at pose")
      .def_readonly("vertical_force_n", &PyEquilibrium::vertical_force, "what the rails carry (N)")
      .def_readonly("lateral_force_n", &PyEquilibrium::lateral_force, "the lateral force needed to hold y (N)")
      .def_readonly("vertical_residual_n", &PyEquilibrium::vertical_residual)
      .def_readonly("roll_residual_nm", &PyEquilibrium::roll_residual)
      .def_readonly("iterations", &PyEquilibrium::iterations, "contact evaluations")
      .def("__repr__", [](const PyEquilibrium& found) {
        return "Equilibrium(status='" + found.status + "', vertical_m=" + number(found.pose.z) + ", roll_rad=" +
               number(found.pose.roll) + ", vertical_force_n=" + number(found.vertical_force) +
               ", lateral_force_n=" + number(found.lateral_force) + ", iterations=" +
               std::to_string(found.iterations) + ")";
      });

  py::class_<PyWheelset>(m, "WheelsetContact",
                         "The contact model of one wheelset on its track (docs/wheel-rail.md §9), kept between "
                         "calls. Profiles: files (SIMPACK .prw/.prr or 'y z' in mm), None for S1002 and UIC60. "
                         "elements: across the largest patch. distance_tolerance_m: h interpolated along rows within it "
                         "(0: exact at every element) between exact nodes distance_node_spacing_m apart; "
                         "distance_everywhere: h on every element of a patch's grid "
                         "(default: only where an element can interpenetrate, 1e-3 m elsewhere). friction: "
                         "Coulomb's mu of every patch, for creep forces when evaluate is given a Velocity; "
                         "creep_method: 'strip_theory' (default) or 'fastsim'. warm_solve_iterations: the iterations "
                         "after which each warm-started patch solve in an evaluate stops at its first settled iterate "
                         "(status 'budget reached', continued at the next evaluate; cold solves uncapped; 0: none; "
                         "docs/wheel-rail.md §9). max_iterations, "
                         "tolerance and gap_tolerance: each patch solver's, as for Solver. "
                         "Calls on one model run one at a time.")
      .def(py::init(&make_wheelset), py::kw_only(), "solver"_a = "norm", "elements"_a = 60,
           "wheel_profile"_a = py::none(), "rail_profile"_a = py::none(),
           "nominal_radius_m"_a = wr::WheelsetLayout().nominal_radius, "gauge_m"_a = wr::TrackLayout().gauge,
           "cant_rad"_a = wr::TrackLayout().cant, "material"_a = Material::steel(), "stiffness"_a = true,
           "max_iterations"_a = py::none(), "tolerance"_a = py::none(), "gap_tolerance"_a = py::none(),
           "distance_tolerance_m"_a = wr::DistanceAccuracy().tolerance,
           "distance_node_spacing_m"_a = wr::DistanceAccuracy().node_spacing, "distance_everywhere"_a = false,
           "friction"_a = py::none(), "creep_method"_a = "strip_theory", "warm_solve_iterations"_a = 0)
      .def(
          "evaluate",
          [](PyWheelset& model, double y, double z, double roll, double yaw,
             const std::optional<wr::WheelsetVelocity>& velocity) { return model.evaluate({y, z, roll, yaw}, velocity); },
          py::kw_only(), "lateral_shift_m"_a = 0.0, "vertical_m"_a = 0.0, "roll_rad"_a = 0.0, "yaw_rad"_a = 0.0,
          "velocity"_a = py::none(),
          "Every wheel's patches, forces and stiffness at a pose (see Pose); with a Velocity (and the model's "
          "friction), every patch's creepages and creep forces as well. result.status says whether every "
          "patch solve gave a usable answer, and if not which.")
      .def(
          "evaluate",
          [](PyWheelset& model, const wr::WheelsetPose& pose, const std::optional<wr::WheelsetVelocity>& velocity) {
            return model.evaluate(pose, velocity);
          },
          "pose"_a, py::kw_only(), "velocity"_a = py::none(), "The same at a Pose, e.g. an Equilibrium's.")
      .def("equilibrium", &PyWheelset::equilibrium, py::kw_only(), "load_n"_a, "lateral_shift_m"_a = 0.0,
           "yaw_rad"_a = 0.0, "force_tolerance"_a = wr::EquilibriumOptions().force_tolerance,
           "max_iterations"_a = wr::EquilibriumOptions().max_iterations,
           "z and roll at which the rails carry load_n (N) at the lateral shift and yaw, for this model as it "
           "is (its solver, elements, grids and starts): evaluate at the pose found carries the load to "
           "force_tolerance. Every pose tried is evaluated from the model's state before the call; the "
           "model's state is then that of the pose returned (when not ok, the pose of smallest residual, "
           "with its wheels and residuals).")
      .def(
          "reset",
          [](PyWheelset& model) { model.reset(); },
          "The next evaluate starts cold: no previous patches, contact sets or search.")
      .def("save_history", &PyWheelset::save_history,
           "Trial steps (docs/wheel-rail.md §9): saves what the next evaluate starts from (one slot, the "
           "last save overwritten). An integrator saves at the accepted step and restores before it "
           "evaluates again.")
      .def("restore_history", &PyWheelset::restore_history,
           "Back to the saved history: the next evaluate gives, bit for bit, what it would have given right "
           "after save_history, whatever was evaluated since. ValueError if nothing was saved.")
      .def("copy", &PyWheelset::copy,
           "A model of its own that answers as this one would (its patches, history, saved history and "
           "iteration budget copied) and shares this one's read-only tables, so that the copies of one model "
           "hold them once: the way to make the wheelset models of a vehicle (docs/wheel-rail.md §9, "
           "'Models of a vehicle'). A model and its copies may be evaluated on different threads at once.")
      .def("__copy__", &PyWheelset::copy, "copy.copy(model): model.copy()")
      .def(
          "__deepcopy__", [](PyWheelset& model, const py::dict&) { return model.copy(); }, "memo"_a,
          "copy.deepcopy(model): model.copy(), whose shared tables are never written")
      .def_property("iteration_budget", &PyWheelset::iteration_budget, &PyWheelset::set_iteration_budget,
                    "the most solver iterations an evaluate may spend over its patch solves, in order, each at "
                    "least one (docs/wheel-rail.md §9); a solve cut short ends at 'iteration limit' and the "
                    "status names it; 0 (default): none")
      .def_property_readonly("flange_angle_rad", &PyWheelset::flange_angle,
                             "the steepest angle of the wheel's flange face")
      .def("__repr__", [](const PyWheelset& model) { return model.description(); });
}

// Contact tables (docs/tables.md §4): arrays in, lookups out.
using Int32Array = py::array_t<std::int32_t, py::array::c_style | py::array::forcecast>;

std::vector<double> axis_of(const InputArray& array, const char* name) {
  FASTNORM_CHECK(array.ndim() == 1, std::string(name) + " must be a one-dimensional array");
  return {array.data(), array.data() + array.size()};
}

fastnorm::ContactTable make_table(const InputArray& lateral_shift_m, const InputArray& yaw_rad,
                                  const InputArray& load_n, std::vector<std::string> pair_names,
                                  std::vector<std::string> output_names, std::vector<std::string> output_units,
                                  const InputArray& values, const Int32Array& topology,
                                  const std::optional<InputArray>& measured_shift_derivatives) {
  fastnorm::TableAxes axes{axis_of(lateral_shift_m, "lateral_shift_m"), axis_of(yaw_rad, "yaw_rad"),
                           axis_of(load_n, "load_n")};
  const std::vector<py::ssize_t> cases{static_cast<py::ssize_t>(pair_names.size()),
                                       static_cast<py::ssize_t>(axes.load_n.size()),
                                       static_cast<py::ssize_t>(axes.yaw_rad.size()),
                                       static_cast<py::ssize_t>(axes.lateral_shift_m.size())};
  auto shape_text = [](const std::vector<py::ssize_t>& shape) {
    std::string text = "(";
    for (std::size_t d = 0; d < shape.size(); ++d) text += (d ? ", " : "") + std::to_string(shape[d]);
    return text + ")";
  };
  auto has_shape = [](const auto& array, const std::vector<py::ssize_t>& shape) {
    if (array.ndim() != static_cast<py::ssize_t>(shape.size())) return false;
    for (std::size_t d = 0; d < shape.size(); ++d)
      if (array.shape(static_cast<py::ssize_t>(d)) != shape[d]) return false;
    return true;
  };
  std::vector<py::ssize_t> value_shape = cases;
  value_shape.push_back(static_cast<py::ssize_t>(output_names.size()));
  FASTNORM_CHECK(has_shape(values, value_shape),
                 "values must have shape (pairs, loads, yaws, shifts, outputs) = " + shape_text(value_shape));
  FASTNORM_CHECK(has_shape(topology, cases),
                 "topology must have shape (pairs, loads, yaws, shifts) = " + shape_text(cases));
  std::vector<double> measured;
  if (measured_shift_derivatives) {
    FASTNORM_CHECK(has_shape(*measured_shift_derivatives, value_shape),
                   "measured_shift_derivatives must have the shape of values " + shape_text(value_shape));
    measured.assign(measured_shift_derivatives->data(),
                    measured_shift_derivatives->data() + measured_shift_derivatives->size());
  }
  return fastnorm::ContactTable(std::move(axes), std::move(pair_names), std::move(output_names),
                                std::move(output_units), {values.data(), values.data() + values.size()},
                                {topology.data(), topology.data() + topology.size()}, std::move(measured));
}

fastnorm::TableInterpolation interpolation_of(const std::string& name) {
  if (name == "multilinear") return fastnorm::TableInterpolation::multilinear;
  FASTNORM_CHECK(name == "pchip", "interpolation must be 'multilinear' or 'pchip' (got '" + name + "')");
  return fastnorm::TableInterpolation::pchip;
}

void bind_tables(py::module_& m) {
  py::class_<fastnorm::ContactTable>(
      m, "ContactTable",
      "A contact table over (pair, load, yaw, lateral shift) with named outputs, looked up by "
      "multilinear or monotone cubic (PCHIP) interpolation with a topology guard (docs/tables.md §4). "
      "values: shape (pairs, loads, yaws, shifts, outputs); topology: (pairs, loads, yaws, shifts), "
      "a code >= 0 per solved case (cases interpolate together only when equal), < 0 for a failed one; "
      "measured_shift_derivatives: None, or d(values)/dy (per m) of values' shape measured when the table was "
      "built, NaN where none: PCHIP takes them at their nodes along y, limited to keep monotone data monotone.")
      .def(py::init(&make_table), py::kw_only(), "lateral_shift_m"_a, "yaw_rad"_a, "load_n"_a, "pair_names"_a,
           "output_names"_a, "output_units"_a, "values"_a, "topology"_a, "measured_shift_derivatives"_a = py::none())
      .def_static("read", &fastnorm::read_contact_table, "path"_a, "Reads the file fastnorm-table export writes.")
      .def("write", [](const fastnorm::ContactTable& table, const std::string& path) {
            fastnorm::write_contact_table(table, path);
          }, "path"_a, "Writes the table's file (docs/tables.md §4).")
      .def_property_readonly("pair_names", &fastnorm::ContactTable::pair_names)
      .def_property_readonly("output_names", &fastnorm::ContactTable::output_names)
      .def_property_readonly("output_units", &fastnorm::ContactTable::output_units)
      .def_property_readonly("lateral_shift_m", [](const fastnorm::ContactTable& t) { return t.axes().lateral_shift_m; })
      .def_property_readonly("yaw_rad", [](const fastnorm::ContactTable& t) { return t.axes().yaw_rad; })
      .def_property_readonly("load_n", [](const fastnorm::ContactTable& t) { return t.axes().load_n; })
      .def(
          "lookup",
          [](const fastnorm::ContactTable& table, std::size_t pair, double y, double yaw, double load,
             const std::string& interpolation) -> py::tuple {
            py::array_t<double> out(static_cast<py::ssize_t>(table.outputs()));
            const auto found = table.lookup(pair, y, yaw, load, interpolation_of(interpolation), out.mutable_data());
            if (found != fastnorm::TableLookupStatus::ok) return py::make_tuple(fastnorm::to_string(found), py::none());
            return py::make_tuple("ok", out);
          },
          "pair"_a, "lateral_shift_m"_a, "yaw_rad"_a, "load_n"_a, py::kw_only(), "interpolation"_a = "pchip",
          "(status, outputs): 'ok' and the outputs in output_names' order, or 'out of range', "
          "'topology change' (evaluate directly) or 'failed case' and None.");
}

}  // namespace

PYBIND11_MODULE(_fastnorm, m) {
  m.doc() = "fastnorm's compiled core; import fastnorm instead.";
  m.attr("__version__") = version();
  py::register_exception<fastnorm::invalid_argument>(m, "FastnormError", PyExc_ValueError);
  bind_basics(m);
  bind_tangential(m);
  bind_case_files(m);
  bind_wheelset(m);
  bind_tables(m);
}
