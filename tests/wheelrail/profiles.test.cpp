// The analytic S1002 and UIC60 profiles against the verification points of
// ../shared/docs/profiles.md (values published to 1e-7 and 1e-6 mm).
#include <catch2/catch.hpp>
#include <fastnorm/wheelrail/profile_curve.hpp>
#include <fastnorm/wheelrail/s1002.hpp>
#include <fastnorm/wheelrail/profile_file.hpp>
#include <fastnorm/wheelrail/uic60.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/peer_cases.hpp"
#include "support/scratch_directory.hpp"

using Catch::Matchers::Contains;

TEST_CASE("S1002 matches the verification points", "[wheelrail][profiles]") {
  struct Point {
    double y, height, slope;  // mm, mm, −
  };
  const Point points[] = {
      {-69, 15.8438146, 3.083221}, {-66, 21.6847844, 1.356292},  {-60, 26.9087121, 0.458349},
      {-55, 28.0000000, 0},        {-52, 27.6189500, -0.258199}, {-45, 23.5377057, -0.922161},
      {-42, 20.0519570, -1.476177}, {-39, 13.5749519, -2.747477}, {-37.5, 10.0000001, -1.751371},
      {-35, 6.8673854, -0.917603}, {-30, 3.9215713, -0.369793},  {-26, 2.7410434, -0.241693},
      {-20, 1.5965630, -0.149686}, {-10, 0.5227590, -0.074408},  {0, 0, -0.033585},
      {10, -0.2084009, -0.011271}, {20, -0.3117646, -0.015271},  {30, -0.6462299, -0.056587},
      {40, -1.3023430, -0.066667}, {60, -2.6356764, -0.066667}};
  const fastnorm::wheelrail::S1002<> wheel;
  for (const Point& point : points) {
    const auto at = wheel.evaluate(point.y / 1000);
    INFO("y = " << point.y << " mm: F = " << at.value * 1000 << " mm, slope " << at.slope);
    CHECK(std::abs(at.value * 1000 - point.height) <= 1e-6);  // the table's 7 decimals: ≤ 5e-8 + rounding
    CHECK(std::abs(at.slope - point.slope) <= 1e-6);
  }
  // Facts: flange tip at y = −55, F = 28; flange thickness 32.5 at F = 10 from the back.
  CHECK(wheel.evaluate(-0.055).slope == Approx(0).margin(1e-12));
  CHECK_THROWS_WITH(wheel.evaluate(-0.0705), Contains("S1002"));
  CHECK_THROWS_WITH(wheel.evaluate(0.0601), Contains("y must lie"));
}

TEST_CASE("S1002 is continuous across its sections", "[wheelrail][profiles]") {
  // Value and slope jumps below 1e-6 mm except D|C (1.2e-4 mm, slope 1e-5) and C|B
  // (3.6e-5 mm; its slope jump, not listed there, measures 3.2e-6), inherent in the
  // published coefficients (profiles.md §1).
  const fastnorm::wheelrail::S1002<> wheel;
  struct Break {
    double y, value_jump_mm, slope_jump;
  };
  for (const Break& at : {Break{32.15796, 1e-6, 1e-6}, Break{-26, 4e-5, 5e-6}, Break{-35, 1.3e-4, 2e-5},
                          Break{-38.426669071, 1e-6, 1e-6}, Break{-39.764473993, 1e-6, 1e-6},
                          Break{-49.662510381, 1e-6, 1e-6}, Break{-62.764705882, 1e-6, 1e-6}}) {
    const double step = 1e-9;  // mm
    const auto left = wheel.evaluate((at.y - step) / 1000), right = wheel.evaluate((at.y + step) / 1000);
    INFO("break at y = " << at.y << " mm");
    CHECK(std::abs(left.value - right.value) * 1000 <= at.value_jump_mm);
    CHECK(std::abs(left.slope - right.slope) <= at.slope_jump);
  }
}

TEST_CASE("UIC60 head matches the verification points of both variants", "[wheelrail][profiles]") {
  const double y[] = {0, 5, 10, 15, 20, 25, 28, 30, 32, 34, 35, 35.9};
  const double en[] = {0,        0.041670, 0.166713, 0.480184, 1.110409, 2.065302,
                       2.942480, 3.984469, 5.552962, 7.995557, 9.910846, 13.216136};
  const double mb[] = {0,        0.041670, 0.166713, 0.468550, 1.086009, 2.027749,
                       2.902181, 3.944128, 5.512561, 7.955038, 9.870176, 13.174510};
  const auto mbench = fastnorm::wheelrail::Uic60<>::mbench();
  const auto en13674 = fastnorm::wheelrail::Uic60<>::en13674();
  for (int n = 0; n < 12; ++n) {
    INFO("|y_r| = " << y[n] << " mm");
    CHECK(std::abs(mbench.evaluate(y[n] / 1000).value * 1000 - mb[n]) <= 1e-6);
    CHECK(std::abs(en13674.evaluate(y[n] / 1000).value * 1000 - en[n]) <= 1e-6);
    CHECK(mbench.evaluate(-y[n] / 1000).value == mbench.evaluate(y[n] / 1000).value);  // symmetric
  }
  // The MB R13 arc ends at 36.000 mm with the flank's slope 20 (1:20 in y per z).
  CHECK(mbench.flank_start() * 1000 == Approx(36).epsilon(1e-12));
  CHECK(en13674.flank_start() * 1000 == Approx(35.999811).margin(1e-6));
  CHECK(mbench.evaluate(0.0362).slope == Approx(20));
  CHECK(mbench.evaluate(-0.0362).slope == Approx(-20));
  // Half-width at z_r = 14 mm: 35.98441 (MB), 35.98133 (EN): the profile crosses 14 mm there.
  CHECK(mbench.evaluate(0.03598441).value * 1000 == Approx(14).margin(2e-4));
  CHECK(en13674.evaluate(0.03598133).value * 1000 == Approx(14).margin(2e-4));
  CHECK_THROWS_WITH(mbench.evaluate(0.040), Contains("below the rail head"));
}

TEST_CASE("The MBench S1002 file is the analytic S1002", "[wheelrail][profiles][peer]") {
  const std::string path = fastnorm::test::shared_profile("MBench_S1002_v3.prw");
  if (path.empty()) {
    fastnorm::test::reference_data_missing("MBench_S1002_v3.prw not found in ../shared/profiles");
    return;
  }
  const auto points = fastnorm::wheelrail::read_profile_file(path);
  REQUIRE(points.y.size() == 399);  // the first of the 400 points is commented out
  const fastnorm::wheelrail::S1002<> wheel;
  double worst = 0;  // mm
  for (std::size_t k = 0; k < points.y.size(); ++k) {
    worst = std::max(worst, std::abs(wheel.evaluate(points.y[k]).value - points.z[k]) * 1000);
  }
  INFO("max |F(y) - z_file| = " << worst << " mm");
  CHECK(worst <= 2e-6);  // profiles.md: 1.6e-6 mm (flange, section D)

  // The spline through the file's points reproduces the analytic profile between them,
  // the steep flange back included (slopes checked where y > −69 mm, slope < 3.1).
  const fastnorm::wheelrail::SplineProfile spline(points);
  double worst_between = 0, worst_slope = 0;
  for (double y = spline.y_min(); y <= spline.y_max(); y += 0.013e-3) {
    if (y < fastnorm::wheelrail::S1002<>::y_min) continue;
    const auto exact = wheel.evaluate(y);
    const auto interpolated = spline.evaluate(y);
    worst_between = std::max(worst_between, std::abs(interpolated.value - exact.value) * 1000);
    if (y > -0.069) worst_slope = std::max(worst_slope, std::abs(interpolated.slope - exact.slope));
  }
  // Measured: 5.2e-4 mm and 0.022 in slope, both at y ≈ −38.4 mm where the curvature of
  // S1002 jumps (R13 arc into the straight 70° flank), which no cubic spline follows.
  INFO("spline: max value error " << worst_between << " mm, max slope error " << worst_slope);
  CHECK(worst_between <= 1e-3);
  CHECK(worst_slope <= 0.03);
}

TEST_CASE("The MBench UIC60 file is the MB variant, canted 1:40", "[wheelrail][profiles][peer]") {
  const std::string path = fastnorm::test::shared_profile("MBench_UIC60_v3.prr");
  if (path.empty()) {
    fastnorm::test::reference_data_missing("MBench_UIC60_v3.prr not found in ../shared/profiles");
    return;
  }
  const auto points = fastnorm::wheelrail::read_profile_file(path);
  REQUIRE(points.y.size() == 495);
  // Back into uncanted rail coordinates (profiles.md §2): the file's R300 centre is at
  // (0.00596, 300) mm; undo the rotation by θ = atan(1/40) about it.
  const double theta = std::atan(1.0 / 40), c = std::cos(theta), s = std::sin(theta);
  auto worst_distance = [&](const fastnorm::wheelrail::Uic60<>& rail) {
    double worst = 0;  // mm, normal distance
    for (std::size_t k = 0; k < points.y.size(); ++k) {
      const double dy = points.y[k] * 1000 - 0.00596, dz = points.z[k] * 1000 - 300;
      const double y_r = c * dy - s * dz, z_r = 300 + s * dy + c * dz;  // Rᵀ of profiles.md §3
      if (z_r > 30) continue;  // below the head's contact surface
      const auto at = rail.evaluate(y_r / 1000);
      worst = std::max(worst, std::abs(z_r - at.value * 1000) / std::sqrt(1 + at.slope * at.slope));
    }
    return worst;
  };
  const double mbench = worst_distance(fastnorm::wheelrail::Uic60<>::mbench());
  const double en = worst_distance(fastnorm::wheelrail::Uic60<>::en13674());
  INFO("max normal distance to the file: MB " << mbench << " mm, EN " << en << " mm");
  CHECK(mbench <= 5e-5);              // profiles.md: 4.5e-5 mm
  CHECK((en > 0.03 && en < 0.045));   // profiles.md: the EN variant deviates up to 0.039 mm
}

TEST_CASE("Profile files: plain text, SIMPACK flags and errors", "[wheelrail][profiles]") {
  namespace fs = std::filesystem;
  const fastnorm::test::ScratchDirectory scratch_dir("fastnorm_profiles_");
  const fs::path& dir = scratch_dir.path();
  // A circle of radius 20 mm sampled in mm, written both ways.
  std::ofstream(dir / "plain.txt") << "# y z (mm)\n-3 0.2254\n-1 0.0250\n0 0\n1 0.0250\n3 0.2254 1.0\n";
  std::ofstream(dir / "flags.prr") << "  mirror.y = 1 ! flip\n  inversion = 1\n  shift.z = +1.0e+00\n"
                                      "  units.len.f = +1.0e+03\n  point.begin\n 1 2\n 2 3\n 4 5\n  point.end\n";
  std::ofstream(dir / "bad.txt") << "1 2\n3 x\n";
  std::ofstream(dir / "rotated.prr") << "  rotate = 0.1\n  point.begin\n 1 2\n 2 3\n 4 5\n  point.end\n";

  const auto plain = fastnorm::wheelrail::read_profile_file((dir / "plain.txt").string());
  REQUIRE(plain.y.size() == 5);
  CHECK(plain.y[0] == Approx(-3e-3));
  CHECK(plain.z[4] == Approx(0.2254e-3));

  const auto flagged = fastnorm::wheelrail::read_profile_file((dir / "flags.prr").string());
  REQUIRE(flagged.y.size() == 3);  // mirrored, reversed, shifted, in mm
  CHECK(flagged.y[0] == Approx(-4e-3));
  CHECK(flagged.z[0] == Approx(6e-3));
  CHECK(flagged.y[2] == Approx(-1e-3));

  CHECK_THROWS_WITH(fastnorm::wheelrail::read_profile_file((dir / "bad.txt").string()), Contains("bad.txt:2"));
  CHECK_THROWS_WITH(fastnorm::wheelrail::read_profile_file((dir / "rotated.prr").string()), Contains("rotate"));
  CHECK_THROWS_WITH(fastnorm::wheelrail::read_profile_file((dir / "missing.txt").string()), Contains("missing.txt"));

  // From a stream; points beyond 1 m (here a file in mm read as metres, or a unit that
  // overflows) are refused at their line instead of giving infinite chord lengths.
  std::istringstream in_metres("-0.003 0.0002\n-0.001 0.00002\n1500 0\n");
  CHECK_THROWS_WITH(fastnorm::wheelrail::read_profile(in_metres, "stream", 1.0),
                    Contains("stream:3") && Contains("more than 1 m"));
  std::istringstream overflow("  units.len.f = 1e-300\n  point.begin\n 1 2\n 2 3\n 4 5\n  point.end\n");
  CHECK_THROWS_WITH(fastnorm::wheelrail::read_profile(overflow, "stream"), Contains("stream:3"));
  std::istringstream plain_stream("-3 0.2254\n-1 0.0250\n0 0\n");
  CHECK(fastnorm::wheelrail::read_profile(plain_stream, "stream").z[1] == Approx(0.025e-3));
  std::istringstream any;
  CHECK_THROWS_WITH(fastnorm::wheelrail::read_profile(any, "stream", 0.0), Contains("plain_length_unit"));

  const fastnorm::wheelrail::SplineProfile spline(flagged);  // decreasing y is reordered
  CHECK(spline.y_min() == Approx(-4e-3));
  CHECK(spline.evaluate(-2e-3).value == Approx(4e-3));  // a knot: exact
  CHECK_THROWS_WITH(spline.evaluate(0.0), Contains("outside"));
  fastnorm::wheelrail::ProfilePoints zigzag{{0, 1e-3, 0.5e-3}, {0, 0, 0}};
  CHECK_THROWS_WITH(fastnorm::wheelrail::SplineProfile(zigzag), Contains("monotone"));
  // Points 5e-77 m apart (found by tests/fuzz/profile_reader) overflowed the spline.
  fastnorm::wheelrail::ProfilePoints crowded{{-3e-5, -5e-77, 0}, {-0.04, 0, 0}};
  CHECK_THROWS_WITH(fastnorm::wheelrail::SplineProfile(crowded), Contains("closer than 1 nm, at point") && Contains("got 2"));
}

TEST_CASE("ProfileCurve: built-in kinds, a spline and a function of one's own; bad curves refused",
          "[wheelrail][profiles]") {
  namespace wr = fastnorm::wheelrail;
  const wr::S1002<double> s1002;
  const auto rail = wr::Uic60<double>::mbench();
  const wr::ProfileCurve wheel = wr::s1002_wheel(), head = wr::uic60_rail(rail);
  const wr::ProfileCurve own([&](double y) { return s1002.evaluate(y); }, wr::S1002<double>::y_min, wr::S1002<double>::y_max);
  CHECK(wheel.y_min() == wr::S1002<double>::y_min);
  CHECK(wheel.y_max() == wr::S1002<double>::y_max);
  CHECK(head.y_max() == rail.flank_start());
  CHECK(head.y_min() == -rail.flank_start());
  // Held as itself or behind std::function: the same numbers, bit for bit.
  for (double y = -0.0699; y <= 0.06; y += 1.3e-4) {
    CHECK(wheel.evaluate(y).value == own.evaluate(y).value);
    CHECK(wheel.evaluate(y).slope == own.evaluate(y).slope);
    CHECK(wheel.evaluate(y).value == s1002.evaluate(y).value);
  }
  CHECK(head.evaluate(0.02).value == rail.evaluate(0.02).value);
  CHECK_FALSE(head.contains(0.04));

  // A spline keeps its points' interval and its errors.
  const wr::ProfileCurve spline =
      wr::spline_curve(wr::SplineProfile(wr::ProfilePoints{{-3e-3, -1e-3, 0, 1e-3, 3e-3}, {2.254e-4, 2.5e-5, 0, 2.5e-5, 2.254e-4}}));
  CHECK(spline.y_min() == -3e-3);
  CHECK(spline.y_max() == 3e-3);
  CHECK(spline.evaluate(1e-3).value == Approx(2.5e-5));
  CHECK_THROWS_WITH(spline.evaluate(4e-3), Contains("outside"));

  CHECK_THROWS_WITH(wr::ProfileCurve(wr::ProfileCurve::Function(), -1e-3, 1e-3), Contains("function is empty"));
  CHECK_THROWS_WITH(wr::ProfileCurve([](double) { return wr::ProfileValue<double>{}; }, 1e-3, -1e-3),
                    Contains("y_min < y_max"));
  CHECK_THROWS_WITH(wr::ProfileCurve([](double) { return wr::ProfileValue<double>{}; }, 0, std::nan("")),
                    Contains("y_min < y_max"));
}
