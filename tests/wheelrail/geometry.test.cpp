// The wheelset on the track: rail placement, rigid contact, the contact locus with yaw, and
// the undeformed distance, against the numbers of ../shared/docs/profiles.md §3 and
// wheelset-geometry.md §4, §6 and against CONTACT's own h on the wr_* peer cases.
#include <catch2/catch.hpp>
#include <fastnorm/fastnorm.hpp>

#include <Eigen/Geometry>

#include <array>
#include <filesystem>

#include "support/wheelrail_cases.hpp"

namespace wr = fastnorm::wheelrail;
using Catch::Matchers::Contains;

TEST_CASE("Rails sit in the track as profiles.md §3 places them", "[wheelrail][geometry]") {
  const wr::Track mbench;
  // The uncanted top of the right rail (y_r = 0) lies on the surface at (753.0407, 0.09371) mm.
  const auto origin = mbench.rail_height(wr::Side::right, 753.0407e-3);
  REQUIRE(origin);
  CHECK(origin->value * 1e3 == Approx(0.09371).margin(1e-5));
  // The highest point of the canted head: Z = 0 with zero slope at y_tr = 760.5380 mm.
  const auto top = mbench.rail_height(wr::Side::right, 760.5380e-3);
  CHECK(std::abs(top->value) < 1e-9);
  CHECK(std::abs(top->slope) < 1e-5);
  // The gauge point, 14 mm below the top, at 717.5 mm; the left rail mirrors the right.
  CHECK(mbench.rail_height(wr::Side::right, 0.7175)->value * 1e3 == Approx(14).margin(1e-9));
  CHECK(mbench.rail_height(wr::Side::left, -0.7175)->value * 1e3 == Approx(14).margin(1e-9));
  CHECK(mbench.rail_height(wr::Side::left, -0.755)->slope == Approx(-mbench.rail_height(wr::Side::right, 0.755)->slope));
  // EN variant: origin at 753.0346 mm.
  const wr::Track en(wr::uic60_rail(wr::Uic60<double>::en13674()));
  CHECK(en.rail_height(wr::Side::right, 753.0346e-3)->value * 1e3 == Approx(0.09371).margin(1e-5));
  // Off the profile: no height; bad layouts are refused by name.
  CHECK_FALSE(mbench.rail_height(wr::Side::right, 0.70));
  CHECK_THROWS_WITH(wr::Track(wr::uic60_rail(), wr::TrackLayout{-1, 0.014, 0.025}), Contains("gauge"));
  CHECK_THROWS_WITH(wr::Track(wr::uic60_rail(), wr::TrackLayout{1.435, 0.014, 0.5}), Contains("cant"));
}

TEST_CASE("Rigid two-wheel contact reproduces wheelset-geometry.md §6.2", "[wheelrail][geometry]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  struct Row {
    double y, z, roll_mrad, right_yw, right_gamma_mrad, right_r, left_yw, left_gamma_mrad, left_r;
  };
  // The table as published (2–4 decimals); the flange-flank row y = 6.5 is left to §6.1's
  // CONTACT tolerance, 1.2e-3 mm.
  const Row rows[] = {{0, 0.1821, 0, 3.25, 24.3, 449.906, 3.25, 24.3, 449.906},
                      {0.5, 0.1750, -0.0242, -8.51, 66.8, 450.417, 5.12, 19.7, 449.865},
                      {1, 0.1618, -0.0541, -9.36, 71.0, 450.476, 6.54, 16.7, 449.839},
                      {2, 0.1298, -0.1161, -11.14, 80.5, 450.611, 8.73, 12.9, 449.807},
                      {3, 0.0905, -0.1836, -13.10, 92.2, 450.780, 10.45, 10.6, 449.787},
                      {4, 0.0431, -0.2593, -15.37, 107.6, 451.006, 11.88, 9.2, 449.772},
                      {4.5, 0.0155, -0.3017, -16.72, 118.2, 451.159, 12.53, 8.8, 449.766},
                      {5, -0.0311, -0.3688, -28.61, 300.2, 453.452, 13.16, 8.5, 449.761},
                      {6, -0.2356, -0.6487, -31.21, 421.6, 454.414, 14.40, 8.1, 449.750}};
  for (const auto& row : rows) {
    INFO("y = " << row.y << " mm");
    const auto pose = wr::rigid_contact_pose(track, wheelset, row.y * 1e-3, 0);
    const auto right = wr::smallest_gap(track, wheelset, wr::Side::right, pose);
    const auto left = wr::smallest_gap(track, wheelset, wr::Side::left, pose);
    CHECK(std::abs(right.gap) < 1e-12);
    CHECK(std::abs(left.gap) < 1e-12);
    CHECK(pose.z * 1e3 == Approx(row.z).margin(0.6e-4));
    CHECK(pose.roll * 1e3 == Approx(row.roll_mrad).margin(1.1e-4));
    CHECK(right.wheel.profile_y * 1e3 == Approx(row.right_yw).margin(0.011));
    CHECK(left.wheel.profile_y * 1e3 == Approx(row.left_yw).margin(0.011));
    CHECK(std::atan(std::abs(right.rail_slope)) * 1e3 == Approx(row.right_gamma_mrad).margin(0.11));
    CHECK(std::atan(std::abs(left.rail_slope)) * 1e3 == Approx(row.left_gamma_mrad).margin(0.11));
    CHECK(right.wheel.radius * 1e3 == Approx(row.right_r).margin(0.6e-3));
    CHECK(left.wheel.radius * 1e3 == Approx(row.left_r).margin(0.6e-3));
  }
  const auto flank = wr::rigid_contact_pose(track, wheelset, 6.5e-3, 0);
  CHECK(flank.z * 1e3 == Approx(-2.7386).margin(1.2e-3));
  // Two tread minima at y = 0: touching at 3.25 mm, the second 0.0082 mm open at −7.69 mm.
  const auto minima = wr::gap_minima(track, wheelset, wr::Side::right, wr::rigid_contact_pose(track, wheelset, 0, 0));
  const auto second = std::find_if(minima.begin(), minima.end(), [](const wr::GapSample& s) {
    return std::abs(s.wheel.profile_y + 7.69e-3) < 0.1e-3;
  });
  REQUIRE(second != minima.end());
  CHECK(second->gap * 1e3 == Approx(0.0082).margin(0.6e-4));
}

TEST_CASE("Yaw moves the contact along the locus as §6.3 states", "[wheelrail][geometry]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  for (double sign : {1.0, -1.0}) {
    const wr::WheelsetPose pose{0, 0, 0, sign * fastnorm::pi<> / 180};
    const auto right = wr::smallest_gap(track, wheelset, wr::Side::right, pose);
    const auto left = wr::smallest_gap(track, wheelset, wr::Side::left, pose);
    CHECK(right.gap * 1e3 == Approx(0.18481).margin(1e-5));
    // Positive yaw (nose to the right): the right contact lies behind, the left ahead.
    CHECK(right.wheel.point.x() * 1e3 == Approx(-sign * 12.973).margin(1e-3));
    CHECK(left.wheel.point.x() * 1e3 == Approx(sign * 12.973).margin(1e-3));
    CHECK(right.wheel.profile_y * 1e3 == Approx(3.714).margin(3e-3));
    CHECK(right.wheel.point.y() * 1e3 == Approx(753.603).margin(2e-3));
    CHECK(std::atan(-right.rail_slope) * 1e3 == Approx(23.1).margin(0.1));
  }
  const auto two_degrees = wr::smallest_gap(track, wheelset, wr::Side::right, {0, 0, 0, 2 * fastnorm::pi<> / 180});
  CHECK(two_degrees.wheel.point.x() * 1e3 == Approx(-26.027).margin(1e-3));
  CHECK(two_degrees.wheel.profile_y * 1e3 == Approx(4.897).margin(3e-3));
}

TEST_CASE("A locus point is where the wheel's surface normal has no forward component", "[wheelrail][geometry]") {
  // The wheel surface P(y_w, θ) = C + R·(ρ sin θ, y_ws, ρ cos θ); its normal by central
  // differences, independently of the closed form sin θ = −ρ'·tan ψ that locus() uses.
  const wr::Wheelset wheelset;
  for (const wr::Side side : {wr::Side::left, wr::Side::right}) {
    for (const double yaw : {-20e-3, 5e-3, 20e-3}) {
      const wr::WheelsetPose pose{2e-3, 1e-4, 1e-3, yaw};
      const Eigen::Matrix3d rotation = wr::Wheelset::rotation(pose);
      for (const double profile_y : {-30e-3, -10e-3, 0.0, 15e-3}) {
        const auto locus = wheelset.locus(side, profile_y, pose, rotation);
        auto surface = [&](double y_w, double angle) {
          const double rho = wheelset.radius(side, y_w).value;
          const Eigen::Vector3d on_wheel(rho * std::sin(angle), wheelset.axle_coordinate(side, y_w), rho * std::cos(angle));
          return Eigen::Vector3d(wheelset.centre(pose) + rotation * on_wheel);
        };
        const double angle = std::asin(locus.angle_sine), step = 1e-6;
        CHECK((surface(profile_y, angle) - locus.point).norm() < 1e-12);
        const Eigen::Vector3d along_profile = surface(profile_y + step, angle) - surface(profile_y - step, angle);
        const Eigen::Vector3d around = surface(profile_y, angle + step) - surface(profile_y, angle - step);
        const Eigen::Vector3d normal = along_profile.cross(around).normalized();
        CHECK(std::abs(normal.x()) < 1e-7);
      }
    }
  }
}

TEST_CASE("The exact h reproduces the regression table of §4", "[wheelrail][geometry]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  const wr::WheelsetPose pose{0, 0.18213e-3, 0, 0};
  // The reference as §4 defines it: the minimum point y_tr = 753.2526 mm on the rail, δ the
  // rail inclination there (the table prints δ = −0.02428 and z = 0.0885, rounded).
  const auto rail = track.rail_height(wr::Side::right, 753.2526e-3);
  REQUIRE(rail);
  CHECK(std::atan(rail->slope) == Approx(-0.02428).margin(1e-5));  // ours −0.024289
  CHECK(rail->value * 1e3 == Approx(0.0885).margin(5e-5));
  const wr::PatchFrame frame{wr::Side::right, {0, 753.2526e-3, rail->value}, std::atan(rail->slope)};
  const double s_values[] = {-14, -11, -8, -4, 0, 4, 8}, x_values[] = {0, 2, 4, 8};
  const double table[7][4] = {{0.04398, 0.04841, 0.06170, 0.11489}, {0.00816, 0.01260, 0.02590, 0.07913},
                              {0.00973, 0.01417, 0.02749, 0.08075}, {0.00424, 0.00868, 0.02200, 0.07531},
                              {0, 0.00444, 0.01778, 0.07111},       {0.00797, 0.01242, 0.02575, 0.07911},
                              {0.04040, 0.04484, 0.05819, 0.11155}};
  double worst = 0;  // mm
  for (int j = 0; j < 7; ++j) {
    for (int i = 0; i < 4; ++i) {
      const fastnorm::Grid<double> point(1, 1, 1e-3, 1e-3, x_values[i] * 1e-3, s_values[j] * 1e-3);
      const double h = wr::undeformed_distance(track, wheelset, pose, frame, point)(0) * 1e3;
      worst = std::max(worst, std::abs(h - table[j][i]));
    }
  }
  INFO("largest difference " << worst << " mm");
  // Measured 1.9e-5 mm at s = −14 mm: the differences grow linearly in s, a tilt of ~1e-6 rad
  // between the two implementations, on top of the table's ±0.5e-5 mm rounding.
  CHECK(worst <= 2.5e-5);
}

TEST_CASE("Our h on CONTACT's grids matches CONTACT's h on every wr_* peer case", "[wheelrail][geometry][peer]") {
  const auto files = fastnorm::test::wheelrail_peer_cases();
  if (files.empty()) return;
  const wr::Track track;
  const wr::Wheelset wheelset;
  double worst_h = 0, worst_y = 0, worst_delta = 0;
  for (const auto& path : files) {
    const auto setup = fastnorm::test::read_wheelrail_case(path);
    const auto problem = fastnorm::read_case_file<double>(path);
    const wr::WheelsetPose pose{setup.y_mm * 1e-3, setup.z_mm * 1e-3, setup.roll, setup.yaw};
    // CONTACT's h is h − min h − PEN; compare shapes (both minus their minimum).
    const wr::PatchFrame frame{setup.side, {setup.xcp * 1e-3, setup.ycp * 1e-3, setup.zcp * 1e-3}, setup.deltcp};
    const Eigen::VectorXd ours = wr::undeformed_distance(track, wheelset, pose, frame, problem.grid);
    const Eigen::VectorXd theirs = problem.undeformed_distance;
    const double difference =
        ((ours.array() - ours.minCoeff()) - (theirs.array() - theirs.minCoeff())).abs().maxCoeff();
    // Our contact reference at CONTACT's pose: one region, weighted centre and inclination.
    const auto regions = wr::contact_regions(track, wheelset, setup.side, pose);
    REQUIRE(regions.size() == 1);
    const auto ours_frame = wr::patch_frame(track, regions[0]);
    INFO(std::filesystem::path(path).filename().string() << ": max |dh| " << difference * 1e6 << " um, y_ref "
                                                         << ours_frame.reference.y() * 1e3 << " vs " << setup.ycp);
    CHECK(difference <= 0.4e-6);
    CHECK(ours_frame.reference.y() * 1e3 == Approx(setup.ycp).margin(0.01));
    CHECK(ours_frame.reference.x() * 1e3 == Approx(setup.xcp).margin(0.005));
    CHECK(ours_frame.inclination == Approx(setup.deltcp).margin(1.5e-4));
    worst_h = std::max(worst_h, difference);
    worst_y = std::max(worst_y, std::abs(ours_frame.reference.y() * 1e3 - setup.ycp));
    worst_delta = std::max(worst_delta, std::abs(ours_frame.inclination - setup.deltcp));
  }
  // Measured: h 0.33 um (wr_y5.0_psi0.0_right; the header z has 4 decimals), reference
  // 5.3 um laterally, inclination 1e-4 rad (CONTACT prints 4 decimals).
  WARN("wr_* peer cases: max |h - h_CONTACT| " << worst_h * 1e6 << " um, max |y_ref - YCP| " << worst_y
                                               << " mm, max |delta - DELTCP| " << worst_delta << " rad");
}

namespace {

// A region's reference quantities computed independently of the locus sampling: a
// quadrature uniform in lateral track position y, each y's locus point found by bisection
// on y_w, CONTACT's weight (16/15)·pen²·√(2ρ·pen) per unit of y (the constant dropped).
struct Reference {
  double x = 0, y = 0, inclination = 0, profile_y = 0;
};

Reference uniform_in_track_y(const wr::Track& track, const wr::Wheelset& wheelset, wr::Side side,
                             const wr::WheelsetPose& pose, const wr::ContactRegion& region) {
  const Eigen::Matrix3d rotation = wr::Wheelset::rotation(pose);
  auto locus_y = [&](double y_w) { return wheelset.locus(side, y_w, pose, rotation).point.y(); };
  const double first_w = region.slices.front().wheel.profile_y - 1e-3;
  const double last_w = region.slices.back().wheel.profile_y + 1e-3;
  const double low = std::min(locus_y(first_w), locus_y(last_w)), high = std::max(locus_y(first_w), locus_y(last_w));
  Reference sum;
  double total = 0;
  const int points = 20000;
  for (int i = 0; i <= points; ++i) {
    const double target = low + (high - low) * i / points;
    double a = first_w, b = last_w;  // locus y is monotone in y_w across a region
    const bool rising = locus_y(b) > locus_y(a);
    for (int step = 0; step < 60; ++step) {
      const double middle = (a + b) / 2;
      ((locus_y(middle) < target) == rising ? a : b) = middle;
    }
    const auto point = wheelset.locus(side, (a + b) / 2, pose, rotation);
    const auto rail = track.rail_height(side, point.point.y());
    if (!rail || point.point.z() <= rail->value) continue;
    const double penetration = point.point.z() - rail->value;
    const double weight = penetration * penetration * std::sqrt(2 * point.radius * penetration);
    sum.x += weight * point.point.x();
    sum.y += weight * point.point.y();
    sum.inclination += weight * std::atan(rail->slope);
    sum.profile_y += weight * point.profile_y;
    total += weight;
  }
  return {sum.x / total, sum.y / total, sum.inclination / total, sum.profile_y / total};
}

}  // namespace

TEST_CASE("At large yaw the reference point is CONTACT's weighting per lateral track length", "[wheelrail][geometry]") {
  // Flange-root and flank contact at ±10 and ±20 mrad, where y_track does not follow y_w
  // in proportion: weighting the profile samples equally put the inclination up to
  // 0.67 mrad off this quadrature (y = 6.2 mm, yaw 10 mrad). Per lateral length: ≤ 0.001
  // mrad on the flange root, 0.033 mrad and 0.14 µm on the flank at y = 6.2 mm, yaw 20 mrad,
  // where a narrow region has few samples of the 0.05 mm profile step.
  const wr::Track track;
  const wr::Wheelset wheelset;
  int regions = 0;
  double worst_inclination = 0, worst_y = 0, worst_x = 0;
  for (double yaw : {-20e-3, -10e-3, 10e-3, 20e-3}) {
    for (double y : {5e-3, 5.5e-3, 6e-3, 6.2e-3, -6e-3}) {
      wr::WheelsetPose pose = wr::rigid_contact_pose(track, wheelset, y, yaw);
      pose.z += 0.1e-3;
      for (wr::Side side : {wr::Side::left, wr::Side::right}) {
        for (const auto& region : wr::contact_regions(track, wheelset, side, pose)) {
          const Reference reference = uniform_in_track_y(track, wheelset, side, pose, region);
          INFO("yaw " << yaw << " rad, y " << y * 1e3 << " mm, " << wr::to_string(side) << ", y_w "
                      << region.profile_y * 1e3 << " mm");
          CHECK(std::abs(region.inclination - reference.inclination) <= 5e-5);
          CHECK(std::abs(region.centre.y() - reference.y) <= 0.3e-6);
          CHECK(std::abs(region.centre.x() - reference.x) <= 0.3e-6);
          CHECK(std::abs(region.profile_y - reference.profile_y) <= 0.3e-6);
          worst_inclination = std::max(worst_inclination, std::abs(region.inclination - reference.inclination));
          worst_y = std::max(worst_y, std::abs(region.centre.y() - reference.y));
          worst_x = std::max(worst_x, std::abs(region.centre.x() - reference.x));
          ++regions;
        }
      }
    }
  }
  CHECK(regions == 40);
  WARN("reference point vs quadrature in track y: inclination " << worst_inclination * 1e3 << " mrad, y "
                                                                << worst_y * 1e6 << " um, x " << worst_x * 1e6 << " um");
}

TEST_CASE("S1002's flange climbs from the start of its 70 degree flank", "[wheelrail][geometry]") {
  // wheelset-geometry.md §6.2: the rigid contact reaches the 70° flank at y_w = −38.43 mm.
  const wr::Wheelset wheelset;
  CHECK(wheelset.flange_angle() * 180 / fastnorm::pi<> == Approx(70).margin(1e-3));
  CHECK(wheelset.flange_climb_point() * 1e3 == Approx(-38.43).margin(0.02));
  CHECK_FALSE(wheelset.at_flange_climb(0));
  CHECK_FALSE(wheelset.at_flange_climb(-30e-3));
  CHECK(wheelset.at_flange_climb(-39e-3));
  CHECK(wheelset.at_flange_climb(-45e-3));  // the tip arc
}

TEST_CASE("The contact search samples near contact exactly as the full sampling", "[wheelrail][geometry]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  int poses = 0, penetrating = 0, different = 0;
  double largest = 0;
  for (double y = -8e-3; y <= 8e-3; y += 1e-3) {
    for (double yaw : {-8e-3, 0.0, 5e-3}) {
      const auto rigid = wr::rigid_contact_pose(track, wheelset, y, yaw);
      for (double lowered : {0.0, 0.05e-3, 0.2e-3, 0.5e-3}) {
        wr::WheelsetPose pose = rigid;
        pose.z += lowered;
        for (wr::Side side : {wr::Side::left, wr::Side::right}) {
          const auto full = wr::sample_gap(track, wheelset, side, pose);
          const auto near = wr::sample_gap_near_contact(track, wheelset, side, pose);
          REQUIRE(full.size() == near.size());
          ++poses;
          for (std::size_t k = 0; k < full.size(); ++k) {
            // Every penetrating sample is taken, and with the full sampling's value: to the
            // accuracy of the rail's table (1e-13 m; Track::rail_height_tabulated) and of its
            // inversion where the table does not answer, which continues from the neighbouring
            // sample there (one Newton step of at most 0.2 µm, error below 1e-12 m).
            if (full[k].gap < 0 || near[k].gap < 0) {
              ++penetrating;
              if (!(std::abs(near[k].gap - full[k].gap) <= 1e-12)) ++different;
              largest = std::max(largest, std::abs(near[k].gap - full[k].gap));
            }
          }
        }
      }
    }
  }
  CHECK(poses == 17 * 3 * 4 * 2);
  CHECK(penetrating > 1000);
  CHECK(different == 0);
  WARN("near-contact sampling against the full sampling: largest gap difference " << largest << " m");
}

TEST_CASE("The rail table answers within its tolerances, and not across an arc joint", "[wheelrail][geometry]") {
  // Against the exact rail (bracketed afresh at every point) every micrometre of the head:
  // 50 points an interval, so an interval answering across a joint of two arcs, where the
  // interpolant misses by ≈ ΔZ″·Δ²/8 (1e-8 m from R80 to R13), could not pass.
  wr::TrackLayout canted_file;
  canted_file.cant = 0;  // the MBench file is already canted 1:40
  std::vector<std::pair<std::string, wr::Track>> tracks{{"UIC60 MBench", wr::Track()},
                                                        {"UIC60 EN 13674", wr::Track(wr::uic60_rail(wr::Uic60<>::en13674()))}};
  const std::string file = fastnorm::test::shared_profile("MBench_UIC60_v3.prr");
  if (!file.empty()) {
    tracks.emplace_back("MBench UIC60 spline", wr::Track(wr::spline_curve(wr::SplineProfile(wr::read_profile_file(file))), canted_file));
  }
  for (const auto& [name, track] : tracks) {
    const auto& table = track.rail_table();
    const auto [first, last] = track.right_rail_span();
    double worst_height = 0, worst_slope = 0;
    long answered = 0, points = 0, mirrored_differ = 0;
    for (double y = first; y <= last; y += 1e-6, ++points) {
      const auto tabulated = table.at(y);
      if (!tabulated) continue;
      ++answered;
      const auto exact = track.rail_height(wr::Side::right, y);
      REQUIRE(exact);
      worst_height = std::max(worst_height, std::abs(tabulated->height - exact->value));
      worst_slope = std::max(worst_slope, std::abs(tabulated->slope - exact->slope));
      double start = std::nan("");
      const auto left = track.rail_height_tabulated(wr::Side::left, -y, start);
      mirrored_differ += !(left && left->value == tabulated->height && left->slope == -tabulated->slope);
    }
    WARN("rail table, " << name << ": " << table.vouched() << " of " << table.intervals()
                        << " intervals answer; largest errors " << worst_height << " m, " << worst_slope << " in slope");
    CHECK(worst_height <= wr::RailTable::height_tolerance);
    CHECK(worst_slope <= wr::RailTable::slope_tolerance);
    CHECK(mirrored_differ == 0);
    // Most of a closed-form head answers (all but its R13 gauge corner and the joints); a
    // spline's third derivative jumps at every knot, so less of it.
    const bool spline = name.find("spline") != std::string::npos;
    CHECK(static_cast<double>(answered) / static_cast<double>(points) >= (spline ? 0.25 : 0.6));
  }
}

TEST_CASE("The contact search continued from step to step samples as the full sampling", "[wheelrail][geometry]") {
  // Along time histories (a time loop's steps, faster ones and jumps) a GapSampler keeps
  // the coarse samples that cannot have come near contact: every penetrating sample must
  // still be the full sampling's, and most coarse samples must be kept.
  const wr::Track track;
  const wr::Wheelset wheelset;
  const auto base = wr::rigid_contact_pose(track, wheelset, 0, 0);
  int poses = 0, penetrating = 0, different = 0, outside_stretches = 0, stretches_not_apart = 0;
  std::size_t taken = 0, taken_cold = 0;
  for (double speed : {1.0, 5.0, 40.0}) {  // the benchmark's motion, 5× and 40× as fast per step
    std::array<wr::GapSampler, 2> samplers;
    for (int step = 0; step < 400; ++step) {
      const double t = speed * step * 1e-3;
      wr::WheelsetPose pose{8e-3 * std::sin(2 * fastnorm::pi<> * t), base.z + 0.2e-3 + 50e-6 * std::sin(2 * fastnorm::pi<> * 8 * t),
                            2e-3 * std::sin(2 * fastnorm::pi<> * 3 * t), 5e-3 * std::cos(2 * fastnorm::pi<> * t)};
      if (step == 200) pose.y += 3e-3;  // a jump
      for (wr::Side side : {wr::Side::left, wr::Side::right}) {
        auto& sampler = samplers[side == wr::Side::right];
        const auto& near = sampler.sample(track, wheelset, side, pose, {});
        const auto full = wr::sample_gap(track, wheelset, side, pose);
        const auto cold = wr::sample_gap_near_contact(track, wheelset, side, pose);
        REQUIRE(full.size() == near.size());
        ++poses;
        // Every sample below candidate_gap lies in a stretch the sampler refined (all that
        // contact_regions scans), and the stretches come in order, apart.
        const auto& stretches = sampler.refined();
        for (std::size_t s = 1; s < stretches.size(); ++s) {
          stretches_not_apart += !(stretches[s].first > stretches[s - 1].second);
        }
        std::size_t s = 0;
        for (std::size_t k = 0; k < full.size(); ++k) {
          while (s < stretches.size() && stretches[s].second < k) ++s;
          const bool inside = s < stretches.size() && stretches[s].first <= k;
          outside_stretches += !inside && full[k].gap < wr::GapSampler::candidate_gap;
        }
        for (std::size_t k = 0; k < full.size(); ++k) {
          taken += near[k].wheel.radius > 0;
          taken_cold += cold[k].wheel.radius > 0;
          if (full[k].gap < 0 || near[k].gap < 0) {  // taken, and to 1e-12 m (as above)
            ++penetrating;
            if (!(std::abs(near[k].gap - full[k].gap) <= 1e-12)) ++different;
          }
        }
      }
    }
  }
  CHECK(poses == 3 * 400 * 2);
  CHECK(penetrating > 100000);
  CHECK(different == 0);
  CHECK(outside_stretches == 0);
  CHECK(stretches_not_apart == 0);
  CHECK(taken < taken_cold);
  WARN("continued search: " << static_cast<double>(taken) / poses << " samples per wheel and pose, "
                            << static_cast<double>(taken_cold) / poses << " from scratch");
}

namespace {

// h at one element by plain bisection of G(t) = √(x_w² + z_w²) − ρ(y_w) along the normal
// (docs/wheel-rail.md §4), independent of undeformed_distance's Newton and bracketing.
double bisected_distance(const wr::Track& track, const wr::Wheelset& wheelset, const wr::WheelsetPose& pose,
                         const wr::PatchFrame& frame, double x, double s) {
  const Eigen::Vector3d normal = frame.normal();
  const Eigen::Vector3d point = frame.reference + x * Eigen::Vector3d::UnitX() + s * frame.lateral_axis();
  const auto rail = track.distance_to_rail(frame.side, point.y(), point.z(), normal.y(), normal.z());
  const Eigen::Matrix3d rotation = wr::Wheelset::rotation(pose);
  auto excess = [&](double t) {
    const Eigen::Vector3d p = rotation.transpose() * (point + t * normal - wheelset.centre(pose));
    const auto profile_y = wheelset.profile_coordinate(frame.side, p.y());
    return profile_y ? std::hypot(p.x(), p.z()) - wheelset.radius(frame.side, *profile_y).value : std::nan("");
  };
  double low = wr::NormalSearch::below, high = wr::NormalSearch::above;
  if (!rail || !(excess(low) < 0) || !(excess(high) > 0)) return std::nan("");
  for (int step = 0; step < 200 && high - low > 1e-15; ++step) {
    const double middle = (low + high) / 2;
    (excess(middle) < 0 ? low : high) = middle;
  }
  return *rail - (low + high) / 2;
}

}  // namespace

TEST_CASE("The undeformed distance is exact to 1 nm on many poses", "[wheelrail][geometry]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  double worst = 0;
  long elements = 0;
  for (double y : {-6e-3, -2e-3, 0.0, 3e-3, 7e-3}) {
    for (double yaw : {-5e-3, 0.0, 8e-3}) {
      auto pose = wr::rigid_contact_pose(track, wheelset, y, yaw);
      pose.z += 0.1e-3;
      for (wr::Side side : {wr::Side::left, wr::Side::right}) {
        for (const auto& region : wr::contact_regions(track, wheelset, side, pose)) {
          const auto frame = wr::patch_frame(track, region);
          const auto extent = wr::patch_extent(frame, region);
          const auto grid = wr::patch_grid(extent, (extent.x_high - extent.x_low) / 20, (extent.s_high - extent.s_low) / 20);
          const Eigen::VectorXd h = wr::undeformed_distance(track, wheelset, pose, frame, grid);
          for (Eigen::Index k = 0; k < grid.size(); ++k) {
            const double expected = bisected_distance(track, wheelset, pose, frame, grid.x_of(k), grid.y_of(k));
            if (std::isnan(expected)) {
              CHECK(h(k) == wr::no_surface_gap);
              continue;
            }
            worst = std::max(worst, std::abs(h(k) - expected));
            ++elements;
          }
        }
      }
    }
  }
  CHECK(elements > 5000);
  CHECK(worst <= 1e-9);
  WARN("undeformed distance against bisection on " << elements << " elements: largest difference " << worst << " m");
}

TEST_CASE("The geometry refuses a pose that is not finite or out of range", "[wheelrail][geometry]") {
  // Issue #15: a NaN or huge z in the wheel-rail pieces gave no regions, no force, no error.
  const wr::Track track;
  const wr::Wheelset wheelset;
  const wr::WheelsetPose nan_z{0, std::nan(""), 0, 0}, huge_z{0, 1e6, 0, 0};
  for (const auto& pose : {nan_z, huge_z}) {
    CHECK_THROWS_WITH(wr::contact_regions(track, wheelset, wr::Side::right, pose), Contains("z must lie within"));
    CHECK_THROWS_WITH(wr::sample_gap(track, wheelset, wr::Side::right, pose), Contains("z must lie within"));
    Eigen::VectorXd h;
    CHECK_THROWS_WITH(wr::undeformed_distance(track, wheelset, pose, wr::PatchFrame{}, fastnorm::Grid<>(2, 2, 1e-4, 1e-4), h),
                      Contains("undeformed_distance: z must lie within"));
  }
}
