// The track and wheelset that fastnorm-wheelrail, the C API and the Python module build
// from their settings: the closed-form S1002 and UIC60 profiles unless a profile file is
// given, and the wheelset's taping lines 65 mm wider than the gauge (1500 mm over 1435 mm);
// and how the C API and the Python module run the static equilibrium on a contact model.
#pragma once

#include <fastnorm/wheelrail.hpp>

#include <cstddef>
#include <string>

namespace fastnorm_example {

// Lengths in m, the cant in rad.
struct WheelsetSetup {
  std::string wheel_profile;  // profile file (SIMPACK .prw, or "y z" in mm); empty: S1002
  std::string rail_profile;   // profile file (.prr, or "y z" in mm); empty: UIC60 (MBench)
  double nominal_radius = fastnorm::wheelrail::WheelsetLayout().nominal_radius;
  double gauge = fastnorm::wheelrail::TrackLayout().gauge;
  double cant = fastnorm::wheelrail::TrackLayout().cant;
};

// Between the gauge and the distance of the taping lines, as 1500 mm over 1435 mm.
inline constexpr double taping_lines_over_gauge = 0.065;

inline fastnorm::wheelrail::ProfileCurve profile_or(const std::string& path,
                                                    fastnorm::wheelrail::ProfileCurve closed_form) {
  namespace wr = fastnorm::wheelrail;
  return path.empty() ? closed_form : wr::spline_curve(wr::SplineProfile(wr::read_profile_file(path)));
}

// @throws fastnorm::invalid_argument for a bad profile file or layout
inline fastnorm::wheelrail::Track track_of(const WheelsetSetup& setup) {
  fastnorm::wheelrail::TrackLayout layout;
  layout.gauge = setup.gauge;
  layout.cant = setup.cant;
  return fastnorm::wheelrail::Track(profile_or(setup.rail_profile, fastnorm::wheelrail::uic60_rail()), layout);
}

inline fastnorm::wheelrail::Wheelset wheelset_of(const WheelsetSetup& setup) {
  fastnorm::wheelrail::WheelsetLayout layout;
  layout.nominal_radius = setup.nominal_radius;
  layout.taping_line_half_distance = (setup.gauge + taping_lines_over_gauge) / 2;
  return fastnorm::wheelrail::Wheelset(profile_or(setup.wheel_profile, fastnorm::wheelrail::s1002_wheel()), layout);
}

// The wheel a patch of the equilibrium belongs to: 0 the left (its rail lies at y < 0), 1 the right.
inline std::size_t wheel_index_of(const fastnorm::wheelrail::PatchContact& patch) {
  return patch.centre.y() < 0 ? 0 : 1;
}

}  // namespace fastnorm_example
