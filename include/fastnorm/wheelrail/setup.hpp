#pragma once
/// @file setup.hpp
/// A wheelset on its track as the tools and bindings describe it (fastnorm-wheelrail, the C
/// API, the Python module): profiles from files or the built-in S1002 and UIC60, gauge,
/// cant and rolling radius, and the wheelset's taping lines 65 mm wider than the gauge
/// (1500 mm over 1435 mm; docs/wheel-rail.md §2).

#include <string>

#include "fastnorm/error.hpp"
#include "fastnorm/wheelrail/profile_curve.hpp"
#include "fastnorm/wheelrail/profile_file.hpp"
#include "fastnorm/wheelrail/s1002.hpp"
#include "fastnorm/wheelrail/track.hpp"
#include "fastnorm/wheelrail/uic60.hpp"
#include "fastnorm/wheelrail/wheelset.hpp"

namespace fastnorm::wheelrail {

/// Between the gauge and the distance of the taping lines (m), as 1500 mm over 1435 mm.
inline constexpr double taping_lines_over_gauge = 0.065;

/// The profile read from `path` (SIMPACK .prw/.prr, or "y z" in mm) and splined, or
/// `built_in` when the path is empty.
/// @throws fastnorm::invalid_argument for a file that cannot be read or is malformed
inline ProfileCurve profile_from_file_or(const std::string& path, ProfileCurve built_in) {
  return path.empty() ? built_in : spline_curve(SplineProfile(read_profile_file(path)));
}

/// Lengths in m, the cant in rad.
struct WheelsetOnTrack {
  std::string wheel_profile;  ///< profile file; empty: S1002
  std::string rail_profile;   ///< profile file; empty: UIC60 (MBench)
  double nominal_radius = WheelsetLayout().nominal_radius;
  double gauge = TrackLayout().gauge;
  double cant = TrackLayout().cant;

  /// @throws fastnorm::invalid_argument for a bad profile file, gauge or cant
  Track track() const {
    TrackLayout layout;
    layout.gauge = gauge;
    layout.cant = cant;
    return Track(profile_from_file_or(rail_profile, uic60_rail()), layout);
  }

  /// @throws fastnorm::invalid_argument for a bad profile file, radius or gauge (named as
  ///         the gauge, which the taping lines are derived from)
  Wheelset wheelset() const {
    check_positive(gauge, "WheelsetOnTrack: gauge");
    WheelsetLayout layout;
    layout.nominal_radius = nominal_radius;
    layout.taping_line_half_distance = (gauge + taping_lines_over_gauge) / 2;
    return Wheelset(profile_from_file_or(wheel_profile, s1002_wheel()), layout);
  }
};

}  // namespace fastnorm::wheelrail
