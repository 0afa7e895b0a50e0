// The steady-rolling options of the command-line tools (fastnorm-solve, fastnorm-wheelrail):
// --friction MU [--creepage-x XI] [--creepage-y ETA] [--spin PHI] [--tangential exact|strip|fastsim]
// [--contact-eps EPS],
// and the fields a tool prints for a patch's answer (docs/tangential.md §5, §9, §10).
#pragma once

#include <fastnorm/case_file.hpp>
#include <fastnorm/fastsim.hpp>
#include <fastnorm/strip_theory.hpp>
#include <fastnorm/tangential_solver.hpp>

#include <cstdio>
#include <optional>
#include <string>

#include "support/arguments.hpp"

namespace fastnorm_example {

struct TangentialArguments {
  double friction = 0;  // 0: no tangential problem
  double creepage_x = 0, creepage_y = 0, spin = 0;
  double spin_centre_x = 0, spin_centre_y = 0;  // a case's tangential line's; the options' are 0
  fastnorm::RollingDirection direction = fastnorm::RollingDirection::positive_x;
  std::string method = "exact";  // the exact path, "strip": strip theory, "fastsim": FASTSIM
  double contact_eps = 0;        // > 0: the exact path stops by CONTACT's rule at this EPS

  /// Adds the options; `lateral` says what y is in this tool.
  void add_to(CommandLine& line, const std::string& lateral) {
    line.option("--friction", friction, "MU",
                "also solve steady rolling with this friction coefficient (rolling towards +x): fx fs mn per patch",
                strictly_within(0, 10));
    line.option("--creepage-x", creepage_x, "XI", "longitudinal creepage of body 1 against body 2 (--friction)",
                within(-1, 1));
    line.option("--creepage-y", creepage_y, "ETA", "lateral creepage, along " + lateral + " (--friction)",
                within(-1, 1));
    line.option("--spin", spin, "PHI", "spin creepage, rad/m, about the grid's origin (--friction)",
                within(-1000, 1000));
    line.option("--tangential", method, "exact|strip|fastsim",
                "the exact steady-rolling solver (default), strip theory, or FASTSIM with Kalker's flexibilities "
                "of the equivalent ellipse (--friction)");
    line.option("--contact-eps", contact_eps, "EPS",
                "stop the exact solver by CONTACT's rule: the rms of a sweep's traction changes at most EPS times "
                "the tractions' (CONTACT's wheel-rail runs: 1e-5); default: no traction changing by more than "
                "1e-9 mu max p_n (--friction)",
                strictly_within(0, 1));
  }

  /// The creepages or the method without --friction, and an unknown method, are usage errors;
  /// the method alone is not where a case's tangential line may pose the problem
  /// (`case_may_pose`, then see adopt).
  void check(const CommandLine& line, bool case_may_pose = false) const {
    for (const char* creepage : {"--creepage-x", "--creepage-y", "--spin", "--tangential", "--contact-eps"}) {
      if (case_may_pose && (std::string(creepage) == "--tangential" || std::string(creepage) == "--contact-eps")) continue;
      if (line.given(creepage) && !line.given("--friction")) {
        throw UsageError(std::string(creepage) + " needs --friction MU");
      }
    }
    if (method != "exact" && method != "strip" && method != "fastsim") {
      throw UsageError("--tangential must be exact, strip or fastsim, not '" + method + "'");
    }
    if (line.given("--contact-eps") && method != "exact") throw UsageError("--contact-eps needs --tangential exact");
  }

  bool wanted() const { return friction > 0; }

  /// A case's steady-rolling problem (its tangential line) where --friction gave none.
  void adopt(const std::optional<fastnorm::CaseRolling<double>>& stored) {
    if (wanted() || !stored) return;
    friction = stored->friction;
    creepage_x = stored->creepage.longitudinal;
    creepage_y = stored->creepage.lateral;
    spin = stored->creepage.spin;
    spin_centre_x = stored->creepage.spin_centre_x;
    spin_centre_y = stored->creepage.spin_centre_y;
    direction = stored->direction;
  }

  /// The problem as a case's tangential line holds it.
  fastnorm::CaseRolling<double> as_case() const { return {friction, creepage(), direction}; }

  fastnorm::Creepage<double> creepage() const {
    return {creepage_x, creepage_y, spin, spin_centre_x, spin_centre_y};
  }

  /// The exact path's options: the defaults, or CONTACT's stopping rule at --contact-eps.
  fastnorm::TangentialOptions<double> exact_options() const {
    fastnorm::TangentialOptions<double> options;
    if (contact_eps > 0) {
      options.stop = fastnorm::TangentialStop::rms_change;
      options.tolerance = contact_eps;
    }
    return options;
  }

  /// Steady rolling on `normal` (a solution on `grid`) by the chosen method, as the fields
  /// a tool appends to its line:
  /// ` fx=<N> fs=<N> mn=<N m> nadh=<n> nslip=<n> sweeps=<k> tangential=<status>` (the fast
  /// paths: 1 sweep).
  std::string solve_fields(const fastnorm::Grid<double>& grid, const fastnorm::Material<double>& material,
                           const fastnorm::Solution<double>& normal) const {
    const auto answer =
        method == "fastsim"
            ? fastnorm::solve_fastsim(grid, material, normal, friction, creepage(), direction)
        : method == "strip"
            ? fastnorm::StripTheory<double>(material).solve(grid, normal, friction, creepage(), direction)
            : fastnorm::SteadyRollingSolver<double>(grid, material, direction, exact_options())
                  .solve(normal, friction, creepage());
    char text[256];
    std::snprintf(text, sizeof text, " fx=%.6g fs=%.6g mn=%.6g nadh=%ld nslip=%ld sweeps=%d tangential=%s",
                  answer.force_x, answer.force_y, answer.spin_moment, static_cast<long>(answer.adhesion_elements),
                  static_cast<long>(answer.slip_elements), answer.sweeps, fastnorm::to_string(answer.status));
    return text;
  }
};

}  // namespace fastnorm_example
