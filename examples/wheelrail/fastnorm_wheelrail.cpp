// fastnorm-wheelrail: an S1002 wheelset on UIC60 rails (1:40, gauge 1435 mm, r0 = 450 mm,
// taping lines 1500 mm apart, E = 210 GPa, ν = 0.3) brought to static equilibrium, one
// line per contact patch.
//
//   fastnorm-wheelrail [--y MM] [--yaw DEG] [--load N | --fz N --wheel left|right]
//                      [--roll RAD] [--elements N] [--solver NAME] [--compare]
//                      [--wheel-profile FILE] [--rail-profile FILE] [--cant RAD]
//                      [--write-case PREFIX] [--svg PREFIX] [--help]
//
// --wheel-profile, --rail-profile: measured or worn profiles (SIMPACK .prw/.prr or plain
// 'y z' text in mm; docs/wheel-rail.md §1) instead of the closed-form S1002 and UIC60 (MB);
// --cant: the rails' inclination (default atan(1/40) rad; 0 for a rail file that is already
// canted, as the Manchester benchmark's UIC60).
//
// Defaults: y = 0, yaw = 0, load = 200 kN on the wheelset (z and roll found), 60 elements
// across the largest patch, solver norm. --fz with --wheel: CONTACT's single-wheel mode
// (vertical force on that wheel, roll fixed by --roll, default 0). Each patch line:
//   wheel=<left|right> patch=<k> fn=<N> ncontact=<n> pmax=<Pa> x_track=<mm> y_track=<mm>
//   contact_angle=<rad> approach=<m>
// (contact reference point in the track frame; approach = the patch's rigid
// interpenetration), plus rel_fn_err_vs_norm=<x> with --compare (full NORM on the same
// patch). A first line starting with '#' states the pose and status. --write-case writes
// PREFIX_<wheel>_<k>.case (h, approach control, solution); --svg writes PREFIX_<wheel>_<k>.svg
// (pressure map; contact outlines of NORM and of the chosen solver).
// Exit status: 0 equilibrium found, 1 not found (status on the '#' line), 2 bad input.
#include <fastnorm/fastnorm.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "support/arguments.hpp"
#include "svg.hpp"

namespace {

namespace wr = fastnorm::wheelrail;
using fastnorm_example::UsageError;

struct Arguments {
  double y_mm = 0, yaw_deg = 0, load = 2e5, fz = 0, roll = 0;
  std::string wheel;
  long elements = 60;
  std::string solver = "norm";
  bool compare = false;
  std::string case_prefix, svg_prefix;
  std::string wheel_profile, rail_profile;
  double cant = std::atan(1.0 / 40);
};

fastnorm_example::CommandLine command_line(Arguments& a) {
  using namespace fastnorm_example;
  constexpr double degrees_per_radian = 180 / M_PI;
  const double y_limit = wr::PoseLimits::lateral_shift * 1e3, yaw_limit = wr::PoseLimits::yaw * degrees_per_radian;
  CommandLine line("fastnorm-wheelrail",
                   "An S1002 wheelset on UIC60 rails (or measured profiles) in static equilibrium; one line per contact patch.");
  line.option("--y", a.y_mm, "MM", "lateral shift of the wheelset", strictly_within(-y_limit, y_limit));
  line.option("--yaw", a.yaw_deg, "DEG", "yaw angle of the wheelset", strictly_within(-yaw_limit, yaw_limit));
  line.option("--load", a.load, "N", "vertical load on the wheelset (z and roll found)", positive());
  line.option("--fz", a.fz, "N", "single-wheel mode: vertical force on the wheel --wheel", positive());
  line.choice("--wheel", a.wheel, {"left", "right"}, "single-wheel mode: the loaded wheel");
  line.option("--roll", a.roll, "RAD", "single-wheel mode: the fixed roll angle",
              strictly_within(-wr::PoseLimits::roll, wr::PoseLimits::roll));
  line.option("--elements", a.elements, "N", "elements across the largest patch, each direction", at_least(4));
  line.option("--solver", a.solver, "NAME", std::string("the patch solver: ") + fastnorm::SolverSpec<double>::grammar);
  line.flag("--compare", a.compare, "also solve each patch with full NORM and print rel_fn_err_vs_norm");
  line.option("--wheel-profile", a.wheel_profile, "FILE", "measured wheel profile (.prw or 'y z' in mm)");
  line.option("--rail-profile", a.rail_profile, "FILE", "measured rail profile (.prr or 'y z' in mm)");
  line.option("--cant", a.cant, "RAD", "the rails' inclination (0 for a rail file already canted)", within(-0.1, 0.1));
  line.option("--write-case", a.case_prefix, "PREFIX", "write PREFIX_<wheel>_<k>.case per patch");
  line.option("--svg", a.svg_prefix, "PREFIX", "draw PREFIX_<wheel>_<k>.svg per patch");
  return line;
}

// The modes exclude each other: the wheelset load, or one wheel's vertical force.
void check_mode(const fastnorm_example::CommandLine& line, const Arguments& a) {
  if (line.given("--fz") || line.given("--wheel")) {
    if (line.given("--load")) throw UsageError("--load and --fz exclude each other");
    if (!line.given("--wheel")) throw UsageError("--fz needs --wheel left|right");
    if (!line.given("--fz")) throw UsageError("--wheel needs --fz N (> 0)");
  } else if (line.given("--roll") && a.roll != 0) {
    throw UsageError("--roll applies to the single-wheel mode (--fz, --wheel) only");
  }
}

wr::ProfileCurve measured_or(const std::string& path, wr::ProfileCurve closed_form) {
  return path.empty() ? closed_form : wr::spline_curve(wr::SplineProfile(wr::read_profile_file(path)));
}

wr::Equilibrium solve(const Arguments& a, const wr::EquilibriumOptions& options) {
  wr::TrackLayout layout;
  layout.cant = a.cant;
  const wr::Track track(measured_or(a.rail_profile, wr::uic60_rail()), layout);
  const wr::Wheelset wheelset(measured_or(a.wheel_profile, wr::s1002_wheel()));
  const double y = a.y_mm * 1e-3, yaw = a.yaw_deg * M_PI / 180;
  if (a.fz > 0) {
    const auto side = a.wheel == "left" ? wr::Side::left : wr::Side::right;
    return wr::solve_single_wheel(track, wheelset, side, y, yaw, a.fz, options, a.roll);
  }
  return wr::solve_equilibrium(track, wheelset, y, yaw, a.load, options);
}

void print_pose(const Arguments& a, const wr::EquilibriumOptions& options, const wr::Equilibrium& result) {
  std::printf("# status=%s solver=%s y=%.4f mm yaw=%.4f deg z=%.6f mm roll=%.6e rad vertical_force=%.3f N "
              "lateral_force=%.3f N iterations=%d%s%s\n",
              to_string(result.status), options.solver.name().c_str(), a.y_mm, a.yaw_deg, result.pose.z * 1e3,
              result.pose.roll, result.vertical_force, result.lateral_force, result.iterations,
              result.message.empty() ? "" : " message=", result.message.c_str());
}

void print_patch(const char* wheel, int k, const wr::ContactPatch& patch, const fastnorm::Solution<double>& solution) {
  std::printf("wheel=%s patch=%d fn=%.6g ncontact=%ld pmax=%.6g x_track=%.4f y_track=%.4f contact_angle=%.6f "
              "approach=%.6e",
              wheel, k, solution.normal_force, static_cast<long>(solution.contact_count()), solution.pressure.maxCoeff(),
              patch.frame.reference.x() * 1e3, patch.frame.reference.y() * 1e3, patch.frame.contact_angle(),
              -patch.undeformed_distance.minCoeff());
}

void write_patch_case(const std::string& path, const std::string& title, const std::string& solver,
                      const wr::ContactPatch& patch, const fastnorm::Material<double>& material,
                      const fastnorm::Solution<double>& solution) {
  const fastnorm::Case<double> problem{title, "fastnorm-wheelrail " + solver, patch.grid, material,
                                       fastnorm::Loading<double>::approach(), 0, patch.undeformed_distance,
                                       fastnorm::CaseResult<double>{solution.normal_force, 0, solution.contact_count(),
                                                                    solution.iterations, 0, solution.pressure}};
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write '" + path + "'");
  fastnorm::write_case(out, problem);
}

// One line per patch, and its case file and drawing when asked for.
void report_patches(const Arguments& a, const wr::EquilibriumOptions& options, const wr::Equilibrium& result) {
  const fastnorm::Material<double> material(options.young_modulus, options.poisson_ratio);
  const bool solved_by_norm = options.solver.kind == fastnorm::SolverSpec<double>::Kind::norm;
  int number_on_side[2] = {0, 0};
  for (const auto& [patch, solution] : result.patches) {
    const int k = ++number_on_side[patch.frame.side == wr::Side::right];
    const char* wheel = wr::to_string(patch.frame.side);
    print_patch(wheel, k, patch, solution);
    // Full NORM on the same patch, for --compare and the outline in --svg.
    fastnorm::Solution<double> norm = solution;
    if (!solved_by_norm && (a.compare || !a.svg_prefix.empty())) {
      norm = fastnorm::NormSolver<double>(patch.grid, material)
                 .solve(patch.undeformed_distance, fastnorm::Loading<double>::approach());
    }
    if (a.compare) std::printf(" rel_fn_err_vs_norm=%.3e", solution.normal_force / norm.normal_force - 1);
    std::printf("\n");
    const std::string title = wheel + std::string(" wheel, patch ") + std::to_string(k);
    const std::string stem = std::string("_") + wheel + "_" + std::to_string(k);
    if (!a.case_prefix.empty()) {
      write_patch_case(a.case_prefix + stem + ".case", title, options.solver.name(), patch, material, solution);
    }
    if (!a.svg_prefix.empty()) {
      using fastnorm_example::number;
      fastnorm_example::write_patch_svg(a.svg_prefix + stem + ".svg",
                                        title + ": y = " + number(a.y_mm) + " mm, yaw = " + number(a.yaw_deg) +
                                            " deg, Fn = " + number(solution.normal_force / 1e3, "%.1f") + " kN",
                                        patch.grid, norm, "NORM", solved_by_norm ? nullptr : &solution,
                                        options.solver.name());
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  Arguments arguments;
  auto line = command_line(arguments);
  return fastnorm_example::run_tool(line, argc, argv, [&] {
    check_mode(line, arguments);
    wr::EquilibriumOptions options;
    options.solver = fastnorm::SolverSpec<double>::parse(arguments.solver);
    options.grid.elements = arguments.elements;
    const auto result = solve(arguments, options);
    print_pose(arguments, options, result);
    if (!result.ok()) return 1;
    report_patches(arguments, options, result);
    return 0;
  });
}
