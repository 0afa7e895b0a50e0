// fastnorm-wheelrail: an S1002 wheelset on UIC60 rails (1:40, gauge 1435 mm, r0 = 450 mm,
// taping lines 1500 mm apart, E = 210 GPa, ν = 0.3) brought to static equilibrium, one
// line per contact patch.
//
//   fastnorm-wheelrail [--y MM] [--yaw DEG] [--load N | --fz N --wheel left|right | --z MM]
//                      [--roll RAD] [--elements N | --element-size MM] [--solver NAME] [--compare]
//                      [--wheel-profile FILE] [--rail-profile FILE] [--cant RAD]
//                      [--radius MM] [--gauge MM] [--young GPA | --shear GPA] [--poisson NU]
//                      [--rail-young GPA] [--rail-poisson NU]
//                      [--friction MU [--creepage-x XI] [--creepage-y ETA] [--spin PHI] [--tangential exact|strip|fastsim]]
//                      [--patch-fn N,...] [--write-case PREFIX] [--svg PREFIX] [--help]
//
// --wheel-profile, --rail-profile: measured or worn profiles (SIMPACK .prw/.prr or plain
// 'y z' text in mm; docs/wheel-rail.md §1) instead of the closed-form S1002 and UIC60 (MB);
// --cant: the rails' inclination (default atan(1/40) rad; 0 for a rail file that is already
// canted, as the Manchester benchmark's UIC60). --radius, --gauge (the wheelset's taping
// lines follow, 65 mm wider), --young or --shear and --poisson for both bodies, --rail-young
// and --rail-poisson for the rail alone: the Manchester benchmark's set-up is
// --radius 460 --shear 82 --poisson 0.28 (docs/validation.md).
//
// Defaults: y = 0, yaw = 0, load = 200 kN on the wheelset (z and roll found), 60 elements
// across the largest patch, solver norm. --fz with --wheel: CONTACT's single-wheel mode
// (vertical force on that wheel, roll fixed by --roll, default 0). --z: contact at the pose
// (y, z, roll, yaw) as given, no equilibrium (WheelsetContact, docs/wheel-rail.md §9).
// --element-size: square elements of that size instead of --elements. Each patch line:
//   wheel=<left|right> patch=<k> fn=<N> ncontact=<n> pmax=<Pa> x_track=<mm> y_track=<mm>
//   contact_angle=<rad> approach=<m> stiffness=<N/m> at_edge=<0|1>
// (contact reference point in the track frame; approach = the patch's rigid
// interpenetration; stiffness = dFn/dδ at the final contact set; at_edge = 1 when contact
// reaches the grid's boundary), plus rel_fn_err_vs_norm=<x> with --compare (full NORM on the
// same patch), and with --friction the steady-rolling creep forces of the patch
// (docs/tangential.md §5): fx=<N> fs=<N> mn=<N m> nadh=<n> nslip=<n> sweeps=<k>
// tangential=<status>, forces on the rail in the patch frame (x forward along the track, s
// towards +y_track on both wheels, n into the rail), mn about the patch reference point, for
// the creepages of the rail against the wheel given in that frame (CONTACT's definition: a
// positive --creepage-x gives a negative fx; --spin in rad/m), the wheelset rolling forward.
// A first line starting with '#' states the pose and status. --write-case writes
// PREFIX_<wheel>_<k>.case (h, approach control, solution, and with --friction the tangential
// line of its creepages); --svg writes PREFIX_<wheel>_<k>.svg
// (pressure map; contact outlines of NORM and of the chosen solver).
// --patch-fn N,... prescribes each printed patch's normal force, in order (CONTACT's
// per-patch Fn): its normal problem is solved again in force control by the same solver
// (approach= then adds the solve's own approach; stiffness=nan), and the creep forces and
// written cases follow that solution (the case in force control).
// Exit status: 0 equilibrium found, 1 not found or at flange climb (status on the '#' line;
// at flange climb the equilibrium's patches are printed when one was found), 2 bad input.
#include <fastnorm/fastnorm.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/arguments.hpp"
#include "support/tangential_arguments.hpp"
#include "svg.hpp"

namespace {

namespace wr = fastnorm::wheelrail;
using fastnorm_example::UsageError;

struct Arguments {
  double y_mm = 0, yaw_deg = 0, load = 2e5, fz = 0, roll = 0, z_mm = 0;
  std::string wheel;
  long elements = 60;
  double element_size_mm = 0;  // 0: from `elements`
  std::string solver = "norm";
  bool compare = false;
  std::string case_prefix, svg_prefix;
  std::vector<double> patch_fn;  // N per printed patch, in order: their normal problems in force control
  std::string wheel_profile, rail_profile;
  double cant = std::atan(1.0 / 40);
  double radius_mm = 450, gauge_mm = 1435;
  double young_gpa = 210, poisson = 0.3, shear_gpa = 0;  // --shear instead of --young
  double rail_young_gpa = 0, rail_poisson = 0;           // the rail's, when given
  fastnorm_example::TangentialArguments tangential;
};

fastnorm_example::CommandLine command_line(Arguments& a) {
  using namespace fastnorm_example;
  constexpr double degrees_per_radian = 180 / fastnorm::pi<>;
  const double y_limit = wr::PoseLimits::lateral_shift * 1e3, yaw_limit = wr::PoseLimits::yaw * degrees_per_radian;
  CommandLine line("fastnorm-wheelrail",
                   "An S1002 wheelset on UIC60 rails (or measured profiles) in static equilibrium; one line per contact patch.");
  line.option("--y", a.y_mm, "MM", "lateral shift of the wheelset", strictly_within(-y_limit, y_limit));
  line.option("--yaw", a.yaw_deg, "DEG", "yaw angle of the wheelset", strictly_within(-yaw_limit, yaw_limit));
  const fastnorm_example::Range load_range{0, wr::max_equilibrium_load, true, false};
  line.option("--load", a.load, "N", "vertical load on the wheelset (z and roll found)", load_range);
  line.option("--fz", a.fz, "N", "single-wheel mode: vertical force on the wheel --wheel", load_range);
  line.choice("--wheel", a.wheel, {"left", "right"}, "single-wheel mode: the loaded wheel");
  line.option("--z", a.z_mm, "MM", "contact at this vertical position of the wheelset (down), no equilibrium",
              strictly_within(-wr::PoseLimits::vertical * 1e3, wr::PoseLimits::vertical * 1e3));
  line.option("--roll", a.roll, "RAD", "the fixed roll angle (single-wheel mode and --z)",
              strictly_within(-wr::PoseLimits::roll, wr::PoseLimits::roll));
  line.option("--elements", a.elements, "N", "elements across the largest patch, each direction",
              within(4, static_cast<double>(wr::PatchGridOptions::max_elements)));
  line.option("--element-size", a.element_size_mm, "MM", "square elements of this size instead of --elements",
              positive());
  line.option("--solver", a.solver, "NAME", std::string("the patch solver: ") + fastnorm::SolverSpec<double>::grammar);
  line.flag("--compare", a.compare, "also solve each patch with full NORM and print rel_fn_err_vs_norm");
  line.option("--wheel-profile", a.wheel_profile, "FILE", "measured wheel profile (.prw or 'y z' in mm)");
  line.option("--rail-profile", a.rail_profile, "FILE", "measured rail profile (.prr or 'y z' in mm)");
  line.option("--cant", a.cant, "RAD", "the rails' inclination (0 for a rail file already canted)", within(-0.1, 0.1));
  line.option("--radius", a.radius_mm, "MM", "nominal rolling radius of the wheels", within(200, 800));
  line.option("--gauge", a.gauge_mm, "MM", "track gauge; the wheelset's taping lines stay 65 mm wider",
              within(1000, 1700));
  line.option("--young", a.young_gpa, "GPA", "Young's modulus of both bodies", within(1, 2000));
  line.option("--shear", a.shear_gpa, "GPA", "shear modulus of both bodies (E = 2G(1 + nu)), instead of --young", within(0.5, 1000));
  line.option("--poisson", a.poisson, "", "Poisson's ratio of both bodies", within(0, 0.5));
  line.option("--rail-young", a.rail_young_gpa, "GPA", "the rail's Young's modulus, if not the wheel's",
              within(1, 2000));
  line.option("--rail-poisson", a.rail_poisson, "", "the rail's Poisson's ratio, if not the wheel's", within(0, 0.5));
  line.option("--patch-fn", a.patch_fn, "N,...",
              "prescribe each patch's normal force, in the order printed: its normal problem solved again "
              "in force control (CONTACT's per-patch Fn)",
              strictly_within(0, 1e8));
  line.option("--write-case", a.case_prefix, "PREFIX", "write PREFIX_<wheel>_<k>.case per patch");
  line.option("--svg", a.svg_prefix, "PREFIX", "draw PREFIX_<wheel>_<k>.svg per patch");
  a.tangential.add_to(line, "the patch's s (body 1 the rail)");
  return line;
}

// The modes exclude each other: the wheelset load, or one wheel's vertical force.
void check_mode(const fastnorm_example::CommandLine& line, const Arguments& a) {
  if (line.given("--z")) {
    for (const char* other : {"--load", "--fz", "--wheel"}) {
      if (line.given(other)) throw UsageError(std::string("--z and ") + other + " exclude each other");
    }
  } else if (line.given("--fz") || line.given("--wheel")) {
    if (line.given("--load")) throw UsageError("--load and --fz exclude each other");
    if (!line.given("--wheel")) throw UsageError("--fz needs --wheel left|right");
    if (!line.given("--fz")) throw UsageError("--wheel needs --fz N (> 0)");
  } else if (line.given("--roll") && a.roll != 0) {
    throw UsageError("--roll applies to the single-wheel mode (--fz, --wheel) and to --z only");
  }
  if (line.given("--young") && line.given("--shear")) throw UsageError("--young and --shear exclude each other");
  a.tangential.check(line);
}

// Wheel (body 1) and rail (body 2) from --young or --shear, --poisson and the rail's own.
fastnorm::Material<double> material_of(const fastnorm_example::CommandLine& line, const Arguments& a) {
  const double wheel_young = line.given("--shear") ? 2 * a.shear_gpa * (1 + a.poisson) : a.young_gpa;
  const double rail_young = line.given("--rail-young") ? a.rail_young_gpa : wheel_young;
  const double rail_poisson = line.given("--rail-poisson") ? a.rail_poisson : a.poisson;
  return {wheel_young * 1e9, a.poisson, rail_young * 1e9, rail_poisson};
}

// The track and wheelset of the command line, with the closed-form profiles by default.
struct Setup {
  wr::Track track;
  wr::Wheelset wheelset;
};

Setup setup_of(const Arguments& a) {
  wr::WheelsetOnTrack setup;
  setup.wheel_profile = a.wheel_profile;
  setup.rail_profile = a.rail_profile;
  setup.nominal_radius = a.radius_mm * 1e-3;
  setup.gauge = a.gauge_mm * 1e-3;
  setup.cant = a.cant;
  return {setup.track(), setup.wheelset()};
}

wr::PatchGridOptions grid_options(const Arguments& a) {
  wr::PatchGridOptions grid;
  grid.elements = a.elements;
  grid.element_length = grid.element_width = a.element_size_mm * 1e-3;
  return grid;
}

void report_patches(const Arguments& a, const fastnorm::SolverSpec<double>& solver,
                    const fastnorm::Material<double>& material, const std::vector<const wr::PatchContact*>& patches);

// The equilibrium modes: the wheelset under --load, or one wheel under --fz.
int run_equilibrium(const Arguments& a, const Setup& setup, const fastnorm::SolverSpec<double>& solver,
                    const fastnorm::Material<double>& material) {
  wr::EquilibriumOptions options;
  options.contact.solver = solver;
  options.contact.grid = grid_options(a);
  options.contact.material = material;
  const double y = a.y_mm * 1e-3, yaw = a.yaw_deg * fastnorm::pi<> / 180;
  const auto result = a.fz > 0 ? wr::solve_single_wheel(setup.track, setup.wheelset,
                                                         a.wheel == "left" ? wr::Side::left : wr::Side::right, y, yaw,
                                                         a.fz, options, a.roll)
                               : wr::solve_equilibrium(setup.track, setup.wheelset, y, yaw, a.load, options);
  std::printf("# status=%s solver=%s y=%.4f mm yaw=%.4f deg z=%.6f mm roll=%.6e rad vertical_force=%.3f N "
              "lateral_force=%.3f N iterations=%d%s%s\n",
              to_string(result.status), solver.name().c_str(), a.y_mm, a.yaw_deg, result.pose.z * 1e3,
              result.pose.roll, result.vertical_force, result.lateral_force, result.iterations,
              result.message.empty() ? "" : " message=", result.message.c_str());
  // At flange climb the equilibrium found, if any, is shown, with exit status 1.
  std::vector<const wr::PatchContact*> patches;
  for (const auto& patch : result.patches) patches.push_back(&patch);
  report_patches(a, solver, material, patches);
  return result.ok() ? 0 : 1;
}

// --z: contact at the pose as given (grids centred on the contact reference points, as
// CONTACT's; element sizes from the patches at this pose).
int run_fixed_pose(const Arguments& a, const Setup& setup, const fastnorm::SolverSpec<double>& solver,
                   const fastnorm::Material<double>& material) {
  wr::WheelsetContactOptions options;
  options.solver = solver;
  options.grid = grid_options(a);
  options.material = material;
  options.snap_to_lattice = false;
  const wr::WheelsetPose pose{a.y_mm * 1e-3, a.z_mm * 1e-3, a.roll, a.yaw_deg * fastnorm::pi<> / 180};
  options.reference_pose = pose;  // --elements across the largest patch at this pose
  wr::WheelsetContact<> contact(setup.track, setup.wheelset, options);
  const auto& result = contact.evaluate(pose);
  std::printf("# status=%s solver=%s y=%.4f mm yaw=%.4f deg z=%.6f mm roll=%.6e rad vertical_force=%.3f N "
              "lateral_force=%.3f N mode=fixed-pose\n",
              !result.ok() ? "solver failed" : result.flange_climb() ? "flange climb" : "converged", solver.name().c_str(),
              a.y_mm, a.yaw_deg, a.z_mm, a.roll,
              -result.force.z(), result.force.y());
  std::vector<const wr::PatchContact*> patches;
  for (const auto& wheel : result.wheels) {
    for (const auto& patch : wheel.patches) patches.push_back(&patch);
  }
  report_patches(a, solver, material, patches);
  return result.ok() && !result.flange_climb() ? 0 : 1;
}

void print_patch(const char* wheel, int k, const wr::ContactPatch& patch, const fastnorm::Solution<double>& solution) {
  // The patch's h holds the pose's interpenetration; a solve in force control adds its own
  // approach (0 in approach control).
  std::printf("wheel=%s patch=%d fn=%.6g ncontact=%ld pmax=%.6g x_track=%.4f y_track=%.4f contact_angle=%.6f "
              "approach=%.6e",
              wheel, k, solution.normal_force, static_cast<long>(solution.contact_count()), solution.pressure.maxCoeff(),
              patch.frame.reference.x() * 1e3, patch.frame.reference.y() * 1e3, patch.frame.contact_angle(),
              -patch.undeformed_distance.minCoeff() + solution.approach);
}

void write_patch_case(const std::string& path, const std::string& title, const std::string& solver,
                      const wr::ContactPatch& patch, const fastnorm::Material<double>& material,
                      const fastnorm::Solution<double>& solution, const fastnorm::Loading<double>& loading,
                      const std::optional<fastnorm::CaseRolling<double>>& rolling) {
  const fastnorm::Case<double> problem{title,
                                       "fastnorm-wheelrail " + solver,
                                       patch.grid,
                                       material,
                                       loading,
                                       0,
                                       patch.undeformed_distance,
                                       fastnorm::CaseResult<double>{solution.normal_force, solution.approach,
                                                                    solution.contact_count(), solution.iterations, 0,
                                                                    solution.pressure},
                                       rolling};
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write '" + path + "'");
  fastnorm::write_case(out, problem);
}

// One line per patch, and its case file and drawing when asked for.
void report_patches(const Arguments& a, const fastnorm::SolverSpec<double>& solver,
                    const fastnorm::Material<double>& material, const std::vector<const wr::PatchContact*>& patches) {
  const bool solved_by_norm = solver.kind == fastnorm::SolverSpec<double>::Kind::norm;
  if (!a.patch_fn.empty() && a.patch_fn.size() != patches.size()) {
    throw UsageError("--patch-fn gives " + std::to_string(a.patch_fn.size()) + " forces for " +
                     std::to_string(patches.size()) + " patches");
  }
  int number_on_side[2] = {0, 0};
  for (std::size_t n = 0; n < patches.size(); ++n) {
    const wr::PatchContact* contact = patches[n];
    const auto& patch = contact->patch;
    const auto solution =
        a.patch_fn.empty() ? contact->solution
                           : fastnorm::AnySolver<double>(solver, patch.grid, material)
                                 .solve(patch.undeformed_distance, fastnorm::Loading<double>::force(a.patch_fn[n]));
    const int k = ++number_on_side[patch.frame.side == wr::Side::right];
    const char* wheel = wr::to_string(patch.frame.side);
    print_patch(wheel, k, patch, solution);
    // The model's stiffness is its own contact's: none for a force prescribed by --patch-fn.
    std::printf(" stiffness=%.6e at_edge=%d", a.patch_fn.empty() ? contact->stiffness : std::nan(""),
                solution.at_edge ? 1 : 0);
    // Full NORM on the same patch, for --compare and the outline in --svg.
    fastnorm::Solution<double> norm = solution;
    if (!solved_by_norm && (a.compare || !a.svg_prefix.empty())) {
      norm = fastnorm::NormSolver<double>(patch.grid, material)
                 .solve(patch.undeformed_distance, a.patch_fn.empty() ? fastnorm::Loading<double>::approach()
                                                                      : fastnorm::Loading<double>::force(a.patch_fn[n]));
    }
    if (a.compare) std::printf(" rel_fn_err_vs_norm=%.3e", solution.normal_force / norm.normal_force - 1);
    if (a.tangential.wanted() && solution.ok()) {
      std::printf("%s", a.tangential.solve_fields(patch.grid, material, solution).c_str());
    }
    std::printf("\n");
    const std::string title = wheel + std::string(" wheel, patch ") + std::to_string(k);
    const std::string stem = std::string("_") + wheel + "_" + std::to_string(k);
    if (!a.case_prefix.empty()) {
      write_patch_case(a.case_prefix + stem + ".case", title, solver.name(), patch, material, solution,
                       a.patch_fn.empty() ? fastnorm::Loading<double>::approach()
                                          : fastnorm::Loading<double>::force(a.patch_fn[n]),
                       a.tangential.wanted() ? std::optional(a.tangential.as_case()) : std::nullopt);
    }
    if (!a.svg_prefix.empty()) {
      using fastnorm_example::number;
      fastnorm_example::write_patch_svg(a.svg_prefix + stem + ".svg",
                                        title + ": y = " + number(a.y_mm) + " mm, yaw = " + number(a.yaw_deg) +
                                            " deg, Fn = " + number(solution.normal_force / 1e3, "%.1f") + " kN",
                                        patch.grid, norm, "NORM", solved_by_norm ? nullptr : &solution,
                                        solver.name());
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  Arguments arguments;
  auto line = command_line(arguments);
  return fastnorm_example::run_tool(line, argc, argv, [&] {
    check_mode(line, arguments);
    const auto solver = fastnorm::SolverSpec<double>::parse(arguments.solver);
    const Setup setup = setup_of(arguments);
    const auto material = material_of(line, arguments);
    return line.given("--z") ? run_fixed_pose(arguments, setup, solver, material)
                             : run_equilibrium(arguments, setup, solver, material);
  });
}
