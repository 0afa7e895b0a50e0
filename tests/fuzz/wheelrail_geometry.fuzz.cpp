// libFuzzer target: the wheel–rail geometry from profile files to forces. The input is a
// header of four 16-bit numbers (lateral shift, yaw, roll, approach), then the wheel's
// profile text, a NUL byte and the rail's profile text (either may be empty: the built-in
// S1002 or UIC60). The target builds the track and wheelset, a contact model with NORM on
// small grids, its rigid contact pose and three poses around it, and evaluates them.
// Properties: nothing but fastnorm::invalid_argument escapes; every answer is finite (forces,
// moments, pressures) or carries a status that says why not.

#include <fastnorm/norm_solver.hpp>
#include <fastnorm/wheelrail.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>

#include "fuzz_check.hpp"

namespace {

namespace wr = fastnorm::wheelrail;
using fastnorm::fuzz::require;

// A 16-bit number of the header mapped onto [low, high].
double header_value(const std::uint8_t* data, int index, double low, double high) {
  const unsigned raw = static_cast<unsigned>(data[2 * index]) | static_cast<unsigned>(data[2 * index + 1]) << 8;
  return low + (high - low) * raw / 65535.0;
}

wr::ProfileCurve profile_or(const std::string& text, wr::ProfileCurve built_in) {
  if (text.empty()) return built_in;
  std::istringstream in(text);
  return wr::spline_curve(wr::SplineProfile(wr::read_profile(in, "fuzz")));
}

void check_finite(const wr::WheelsetContactResult& result) {
  require(result.force.allFinite() && result.moment.allFinite(), "the wheelset's force and moment are finite");
  for (const auto& wheel : result.wheels) {
    for (const auto& patch : wheel.patches) {
      require(std::isfinite(patch.normal_force) && patch.normal_force >= 0, "Fn is finite and >= 0");
      require(patch.force.allFinite() && patch.moment.allFinite() && patch.centre.allFinite(),
              "a patch's force, moment and centre are finite");
      require(patch.patch.undeformed_distance.allFinite(), "h is finite");
      if (patch.ok()) require(patch.solution.pressure.allFinite(), "a usable answer's pressures are finite");
    }
  }
  require(result.ok() == (result.status.code == wr::StepStatus::Code::ok), "ok() is the step status");
  if (!result.ok()) require(!result.status.message.empty(), "a failed step says why");
}

void evaluate_around(const wr::Track& track, const wr::Wheelset& wheelset, const std::uint8_t* header) {
  wr::WheelsetContactOptions options;
  options.grid.elements = 8;
  options.stiffness = false;
  const double y = header_value(header, 0, -12e-3, 12e-3), yaw = header_value(header, 1, -30e-3, 30e-3);
  wr::WheelsetPose pose = wr::rigid_contact_pose(track, wheelset, y, yaw);
  pose.roll = header_value(header, 2, -5e-3, 5e-3);
  const double approach = header_value(header, 3, -0.2e-3, 0.6e-3);
  options.reference_pose = pose;
  options.reference_pose->z += std::abs(approach) + 1e-5;
  wr::WheelsetContact<fastnorm::NormSolver<>> model(track, wheelset, options);
  for (int step = 0; step < 3; ++step) {
    wr::WheelsetPose moved = pose;
    moved.z += approach * (1 + 0.5 * step);
    moved.y += 0.2e-3 * step;
    check_finite(model.evaluate(moved));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 8) return 0;
  const std::string rest(reinterpret_cast<const char*>(data + 8), size - 8);
  const std::size_t split = rest.find('\0');
  const std::string wheel_text = rest.substr(0, split);
  const std::string rail_text = split == std::string::npos ? std::string() : rest.substr(split + 1);
  try {
    const wr::Track track(profile_or(rail_text, wr::uic60_rail()));
    const wr::Wheelset wheelset(profile_or(wheel_text, wr::s1002_wheel()));
    evaluate_around(track, wheelset, data);
  } catch (const fastnorm::invalid_argument&) {
    // bad profiles, poses beyond PoseLimits, no contact at the reference pose: named errors
  }
  return 0;
}
