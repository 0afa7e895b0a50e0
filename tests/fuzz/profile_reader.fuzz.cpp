// libFuzzer target: the profile reader (profile_file.hpp) and the spline through what it
// read, on arbitrary bytes. Properties: the reader either throws fastnorm::invalid_argument
// or returns at least 3 finite points within 1 m; a spline either refuses the points or
// gives a finite value and slope everywhere on its interval.

#include <fastnorm/wheelrail/profile_file.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using fastnorm::fuzz::require;
  namespace wr = fastnorm::wheelrail;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  wr::ProfilePoints points;
  try {
    points = wr::read_profile(in, "fuzz");
  } catch (const fastnorm::invalid_argument&) {
    return 0;
  }
  require(points.y.size() == points.z.size() && points.y.size() >= 3, "at least 3 points, y and z alike");
  for (std::size_t k = 0; k < points.y.size(); ++k) {
    require(std::abs(points.y[k]) <= wr::max_profile_coordinate && std::abs(points.z[k]) <= wr::max_profile_coordinate,
            "every point finite and within 1 m");
  }
  try {
    const wr::SplineProfile spline(points);
    const int samples = 64;
    for (int n = 0; n <= samples; ++n) {
      const double y = spline.y_min() + (spline.y_max() - spline.y_min()) * n / samples;
      const auto at = spline.evaluate(std::min(y, spline.y_max()));
      require(std::isfinite(at.value) && std::isfinite(at.slope), "the spline is finite on its interval");
    }
  } catch (const fastnorm::invalid_argument&) {
  }
  return 0;
}
