// fastnorm-wheelrail: an S1002 wheelset on UIC60 rails (1:40, gauge 1435 mm, r0 = 450 mm,
// taping lines 1500 mm apart, E = 210 GPa, ν = 0.3) brought to static equilibrium, one
// line per contact patch.
//
//   fastnorm-wheelrail [--y MM] [--yaw DEG] [--load N | --fz N --wheel left|right]
//                      [--roll RAD] [--elements N] [--solver NAME] [--compare]
//                      [--wheel-profile FILE] [--rail-profile FILE] [--cant RAD]
//                      [--write-case PREFIX] [--svg PREFIX]
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
#include <iostream>
#include <string>

#include "svg.hpp"

namespace {

const char* const usage =
    "usage: fastnorm-wheelrail [--y MM] [--yaw DEG] [--load N | --fz N --wheel left|right] [--roll RAD]\n"
    "                          [--elements N] [--solver NAME] [--compare] [--write-case PREFIX] [--svg PREFIX]\n"
    "                          [--wheel-profile FILE] [--rail-profile FILE] [--cant RAD]\n"
    "       NAME: norm | cg | elliptic | polynomial[:G] | elliptic-edge[:K] | polynomial-edge[:G[:K]]\n";

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

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

double parse_number(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || used == 0 || !std::isfinite(value)) {
    throw UsageError(option + " needs a number, not '" + text + "'");
  }
  return value;
}

Arguments parse(int argc, char** argv) {
  Arguments a;
  bool load_given = false;
  for (int n = 1; n < argc; ++n) {
    const std::string word = argv[n];
    auto value = [&]() -> std::string {
      if (n + 1 >= argc) throw UsageError("option " + word + " needs a value");
      return argv[++n];
    };
    if (word == "--y") a.y_mm = parse_number(word, value());
    else if (word == "--yaw") a.yaw_deg = parse_number(word, value());
    else if (word == "--load") a.load = parse_number(word, value()), load_given = true;
    else if (word == "--fz") a.fz = parse_number(word, value());
    else if (word == "--roll") a.roll = parse_number(word, value());
    else if (word == "--wheel") a.wheel = value();
    else if (word == "--elements") {
      const double count = parse_number(word, value());
      if (count != std::floor(count)) throw UsageError("--elements needs a whole number");
      a.elements = static_cast<long>(count);
    } else if (word == "--solver") a.solver = value();
    else if (word == "--compare") a.compare = true;
    else if (word == "--write-case") a.case_prefix = value();
    else if (word == "--svg") a.svg_prefix = value();
    else if (word == "--wheel-profile") a.wheel_profile = value();
    else if (word == "--rail-profile") a.rail_profile = value();
    else if (word == "--cant") a.cant = parse_number(word, value());
    else if (word == "--help" || word == "-h") {
      std::cout << usage;
      std::exit(0);
    } else {
      throw UsageError("unknown option '" + word + "'");
    }
  }
  if (a.fz != 0 || !a.wheel.empty()) {
    if (load_given) throw UsageError("--load and --fz exclude each other");
    if (a.wheel != "left" && a.wheel != "right") throw UsageError("--fz needs --wheel left|right");
    if (!(a.fz > 0)) throw UsageError("--wheel needs --fz N (> 0)");
  } else if (a.roll != 0) {
    throw UsageError("--roll applies to the single-wheel mode (--fz, --wheel) only");
  }
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  namespace wr = fastnorm::wheelrail;
  Arguments arguments;
  try {
    arguments = parse(argc, argv);
  } catch (const UsageError& error) {
    std::cerr << "fastnorm-wheelrail: " << error.what() << '\n' << usage;
    return 2;
  }
  try {
    auto measured = [](const std::string& path) { return wr::spline_curve(wr::SplineProfile(wr::read_profile_file(path))); };
    wr::TrackLayout layout;
    layout.cant = arguments.cant;
    const wr::Track track(arguments.rail_profile.empty() ? wr::uic60_rail() : measured(arguments.rail_profile), layout);
    const wr::Wheelset wheelset(arguments.wheel_profile.empty() ? wr::s1002_wheel() : measured(arguments.wheel_profile));
    wr::EquilibriumOptions options;
    options.solver = fastnorm::SolverSpec<double>::parse(arguments.solver);
    options.grid.elements = arguments.elements;
    const double y = arguments.y_mm * 1e-3, yaw = arguments.yaw_deg * M_PI / 180;
    const bool single = arguments.fz > 0;
    const auto result = single ? wr::solve_single_wheel(track, wheelset,
                                                        arguments.wheel == "left" ? wr::Side::left : wr::Side::right,
                                                        y, yaw, arguments.fz, options, arguments.roll)
                               : wr::solve_equilibrium(track, wheelset, y, yaw, arguments.load, options);
    std::printf("# status=%s solver=%s y=%.4f mm yaw=%.4f deg z=%.6f mm roll=%.6e rad vertical_force=%.3f N "
                "lateral_force=%.3f N iterations=%d%s%s\n",
                to_string(result.status), options.solver.name().c_str(), arguments.y_mm, arguments.yaw_deg, result.pose.z * 1e3,
                result.pose.roll, result.vertical_force, result.lateral_force, result.iterations,
                result.message.empty() ? "" : " message=", result.message.c_str());
    if (!result.ok()) return 1;
    const fastnorm::Material<double> material(options.young_modulus, options.poisson_ratio);
    int number_on_left = 0, number_on_right = 0;
    for (const auto& [patch, solution] : result.patches) {
      const bool left = patch.frame.side == wr::Side::left;
      const int k = left ? ++number_on_left : ++number_on_right;
      const char* wheel = wr::to_string(patch.frame.side);
      std::printf("wheel=%s patch=%d fn=%.6g ncontact=%ld pmax=%.6g x_track=%.4f y_track=%.4f contact_angle=%.6f "
                  "approach=%.6e",
                  wheel, k, solution.normal_force, static_cast<long>(solution.contact_count()),
                  solution.pressure.maxCoeff(), patch.frame.reference.x() * 1e3, patch.frame.reference.y() * 1e3,
                  patch.frame.contact_angle(), -patch.undeformed_distance.minCoeff());
      // Full NORM on the same patch, for --compare and the outline in --svg.
      const bool solved_by_norm = options.solver.name() == "norm";
      fastnorm::Solution<double> norm = solution;
      if (!solved_by_norm && (arguments.compare || !arguments.svg_prefix.empty())) {
        norm = fastnorm::NormSolver<double>(patch.grid, material)
                   .solve(patch.undeformed_distance, fastnorm::Loading<double>::approach());
      }
      if (arguments.compare) std::printf(" rel_fn_err_vs_norm=%.3e", solution.normal_force / norm.normal_force - 1);
      std::printf("\n");
      const std::string stem = std::string("_") + wheel + "_" + std::to_string(k);
      if (!arguments.case_prefix.empty()) {
        fastnorm::Case<double> problem{wheel + std::string(" wheel, patch ") + std::to_string(k),
                                       "fastnorm-wheelrail " + options.solver.name(), patch.grid, material,
                                       fastnorm::Loading<double>::approach(), 0, patch.undeformed_distance,
                                       fastnorm::CaseResult<double>{solution.normal_force, 0, solution.contact_count(),
                                                                    solution.iterations, 0, solution.pressure}};
        std::ofstream out(arguments.case_prefix + stem + ".case");
        if (!out) throw std::runtime_error("cannot write '" + arguments.case_prefix + stem + ".case'");
        fastnorm::write_case(out, problem);
      }
      if (!arguments.svg_prefix.empty()) {
        fastnorm_example::write_patch_svg(
            arguments.svg_prefix + stem + ".svg",
            std::string(wheel) + " wheel, patch " + std::to_string(k) + ": y = " +
                fastnorm_example::number(arguments.y_mm) + " mm, yaw = " + fastnorm_example::number(arguments.yaw_deg) +
                " deg, Fn = " + fastnorm_example::number(solution.normal_force / 1e3, "%.1f") + " kN",
            patch.grid, norm, "NORM", solved_by_norm ? nullptr : &solution, options.solver.name());
      }
    }
    return 0;
  } catch (const fastnorm::invalid_argument& error) {
    std::cerr << error.what() << '\n';
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "fastnorm-wheelrail: " << error.what() << '\n';
    return 2;
  }
}
