// h interpolated along rows between exact nodes (docs/wheel-rail.md §4, item 7) against the
// exact undeformed_distance at every element.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "fastnorm/wheelrail.hpp"
#include "support/peer_cases.hpp"

namespace wr = fastnorm::wheelrail;

namespace {

// The largest difference between interpolated and exact h over the patches of `poses` random
// poses (lateral shift in [y_low, y_high], |yaw| ≤ 20 mrad, 0.02–0.2 mm lowered), on boxes
// 1.5 times each patch's extent (as the time loop's) with about `elements` across. Counts
// the elements compared and the poses with a patch on the flange side of the flange root's
// curvature jump (S1002 at y_w = −26 mm) and on the tread side. The same with h computed only
// where an element can interpenetrate (docs/wheel-rail.md §4, item 8): the largest
// difference from the exact h of an element that interpenetrates, how many such elements
// were left out (none may be, but those of another region's patch that reaches into this
// box, counted apart), and the share of the grid computed.
struct Comparison {
  double worst = 0;
  long elements = 0;
  int root_patches = 0, tread_patches = 0;
  double spans_worst = 0;
  long interpenetrating = 0, left_out = 0, other_patch = 0, computed = 0, grid_elements = 0;
};

Comparison compare(const wr::Track& track, const wr::Wheelset& wheelset, int poses, double y_low, double y_high,
                   double elements, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> lateral(y_low, y_high), yaw(-0.02, 0.02), lowered(0.02e-3, 0.2e-3);
  Comparison result;
  Eigen::VectorXd exact, interpolated, where_touching;
  std::vector<wr::RowSpan> spans, other_spans;
  for (int n = 0; n < poses; ++n) {
    const double y = lateral(random), psi = yaw(random);
    auto pose = wr::rigid_contact_pose(track, wheelset, y, psi);
    pose.z += lowered(random);
    for (wr::Side side : {wr::Side::left, wr::Side::right}) {
      const auto regions = wr::contact_regions(track, wheelset, side, pose);
      for (const auto& region : regions) {
        const auto frame = wr::patch_frame(track, region);
        auto extent = wr::patch_extent(frame, region);
        const double length = extent.x_high - extent.x_low, width = extent.s_high - extent.s_low;
        extent.x_low -= length / 4, extent.x_high += length / 4, extent.s_low -= width / 4, extent.s_high += width / 4;
        const auto grid = wr::patch_grid(extent, length / elements, std::max(width, 1e-4) / elements);
        wr::undeformed_distance(track, wheelset, pose, frame, grid, exact);
        wr::undeformed_distance(track, wheelset, pose, frame, grid, wr::DistanceAccuracy{}, interpolated);
        for (Eigen::Index k = 0; k < grid.size(); ++k) {
          if (exact(k) == wr::no_surface_gap) {
            CHECK(interpolated(k) == wr::no_surface_gap);
            continue;
          }
          result.worst = std::max(result.worst, std::abs(interpolated(k) - exact(k)));
          ++result.elements;
        }
        wr::touching_spans(frame, region, grid, spans);
        wr::undeformed_distance(track, wheelset, pose, frame, grid, wr::DistanceAccuracy{}, spans, where_touching);
        // Whether element k lies where another region of the wheel can interpenetrate.
        auto of_another_region = [&](Eigen::Index k) {
          for (const auto& other : regions) {
            if (&other == &region) continue;
            wr::touching_spans(frame, other, grid, other_spans);
            const auto& span = other_spans[static_cast<std::size_t>(grid.j_of(k))];
            if (grid.i_of(k) >= span.first && grid.i_of(k) <= span.last) return true;
          }
          return false;
        };
        for (Eigen::Index k = 0; k < grid.size(); ++k) {
          result.computed += where_touching(k) != wr::not_computed_gap ? 1 : 0;
          if (exact(k) > 0) continue;
          ++result.interpenetrating;
          if (where_touching(k) == wr::not_computed_gap) {
            ++(of_another_region(k) ? result.other_patch : result.left_out);
          } else {
            result.spans_worst = std::max(result.spans_worst, std::abs(where_touching(k) - exact(k)));
          }
        }
        result.grid_elements += grid.size();
        (region.profile_y < -0.026 ? result.root_patches : result.tread_patches) += 1;
      }
    }
  }
  return result;
}

// S1002 with its published sections shifted by constants so that they meet: the published
// polynomials leave value steps of 37 nm at y_w = −26 mm and 118 nm at −35 mm, where h is
// defined only to the step's height (docs/wheel-rail.md §4, item 7). Its slopes and
// curvatures still jump at every section end: the kinks the interpolation must detect.
wr::ProfileCurve continuous_s1002() {
  const double ends[] = {32.15796e-3, -26e-3, -35e-3, -38.426669071e-3, -39.764473993e-3, -49.662510381e-3,
                         -62.764705882e-3};
  const wr::S1002<double> s1002;
  double shift[8] = {0};
  for (int k = 0; k < 7; ++k) {
    shift[k + 1] = shift[k] + s1002.evaluate(ends[k] + 1e-12).value - s1002.evaluate(ends[k] - 1e-12).value;
  }
  return {[=](double y) {
            auto at = s1002.evaluate(y);
            int section = 0;
            while (section < 7 && y < ends[section]) ++section;
            at.value += shift[section];
            return at;
          },
          wr::S1002<double>::y_min, wr::S1002<double>::y_max};
}

}  // namespace

TEST_CASE("h interpolated along rows is within 1 nm of the exact h: tread, flange, yaw to 20 mrad",
          "[wheelrail][geometry]") {
  const wr::Track track;
  const wr::Wheelset wheelset;
  // Tread (and two-point contact); then shifts that put the right wheel's patch on the
  // flange root, across S1002's curvature jump at −26 mm, and on the flank.
  const auto tread = compare(track, wheelset, 800, -5e-3, 5e-3, 60, 1);
  const auto flange = compare(track, wr::Wheelset(continuous_s1002()), 800, 5e-3, 8.5e-3, 60, 2);
  CHECK(tread.elements > 1000000);
  CHECK(flange.root_patches > 300);
  CHECK(tread.worst <= 1e-9);
  CHECK(flange.worst <= 1e-9);
  // The published S1002 itself, flange side: where a normal line meets the wheel within one
  // of its value steps, the exact h is defined only to the step's height (118 nm at most);
  // elsewhere the same bound holds as on the continuous profile.
  const auto published = compare(track, wheelset, 200, 5e-3, 8.5e-3, 60, 3);
  CHECK(published.worst <= 0.12e-6);
  // Computed only where an element can interpenetrate: every interpenetrating element is
  // computed, to the same bound, and a good part of the 1.5-times box is left out.
  for (const auto* run : {&tread, &flange, &published}) {
    CHECK(run->interpenetrating > 100000);
    CHECK(run->left_out == 0);
    CHECK(static_cast<double>(run->computed) < 0.8 * static_cast<double>(run->grid_elements));
  }
  CHECK(tread.spans_worst <= 1e-9);
  CHECK(flange.spans_worst <= 1e-9);
  CHECK(published.spans_worst <= 0.12e-6);
  WARN("h only where touching: computed " << tread.computed << " and " << flange.computed << " of "
                                          << tread.grid_elements << " and " << flange.grid_elements
                                          << " elements (tread, flange), largest difference from the exact h "
                                          << tread.spans_worst << " and " << flange.spans_worst
                                          << " m; interpenetrating elements of another patch left out: "
                                          << tread.other_patch + flange.other_patch + published.other_patch);
  WARN("interpolated h against exact: tread " << tread.worst << " m on " << tread.elements << " elements, flange "
                                              << flange.worst << " m on " << flange.elements << " elements ("
                                              << flange.root_patches << " patches past the flange root); published S1002 "
                                              << published.worst << " m");
}

TEST_CASE("h interpolated along rows on a measured wheel (spline) is within 1 nm of the exact h",
          "[wheelrail][geometry][peer]") {
  const std::string path = fastnorm::test::shared_profile("MBench_S1002_v3.prw");
  if (path.empty()) {
    fastnorm::test::reference_data_missing("MBench_S1002_v3.prw not found in ../shared/profiles");
    return;
  }
  // A cubic spline through 399 points: its third derivative jumps at every knot.
  const wr::Wheelset wheelset(wr::spline_curve(wr::SplineProfile(wr::read_profile_file(path))));
  const wr::Track track;
  const auto tread = compare(track, wheelset, 200, -5e-3, 5e-3, 60, 4);
  const auto flange = compare(track, wheelset, 200, 5e-3, 8.5e-3, 60, 5);
  CHECK(flange.root_patches > 50);
  CHECK(tread.worst <= 1e-9);
  CHECK(flange.worst <= 1e-9);
  for (const auto* run : {&tread, &flange}) {
    CHECK(run->left_out == 0);
    CHECK(run->spans_worst <= 1e-9);
  }
  WARN("measured wheel: interpolated h against exact: tread " << tread.worst << " m, flange " << flange.worst << " m");
}
