#pragma once
/// @file patch.hpp
/// A contact patch: its reference point and tangent plane and the grid of the potential
/// contact area (docs/wheel-rail.md §4); the undeformed distance on it is in
/// undeformed_distance.hpp.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "fastnorm/error.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/wheelrail/contact_search.hpp"

namespace fastnorm::wheelrail {

/// Element sizes of the patch grids (m). Zero sizes are chosen so that the largest
/// interpenetration region is covered by about `elements` × `elements`.
struct PatchGridOptions {
  Eigen::Index elements = 60;  ///< elements across the largest region, each direction
  /// The most `elements` allowed: 2000² = 4·10⁶ elements on the largest patch, beyond what
  /// any solver here finishes in reasonable time (full NORM stops being practical near 10⁴).
  static constexpr Eigen::Index max_elements = 2000;
  double element_length = 0;   ///< dx, rolling direction (0: from `elements`)
  double element_width = 0;    ///< ds, lateral in the tangent plane (0: from `elements`)

  /// @throws fastnorm::invalid_argument naming the offending field
  void validate() const {
    FASTNORM_CHECK(elements >= 4 && elements <= max_elements,
                   fastnorm::detail::describe("PatchGridOptions: elements must lie in [4, " +
                                                  std::to_string(max_elements) + "]",
                                              elements));
    FASTNORM_CHECK(std::isfinite(element_length) && element_length >= 0,
                   fastnorm::detail::describe("PatchGridOptions: element_length must be >= 0 (m)", element_length));
    FASTNORM_CHECK(std::isfinite(element_width) && element_width >= 0,
                   fastnorm::detail::describe("PatchGridOptions: element_width must be >= 0 (m)", element_width));
  }
};

/// Where and how a patch lies: reference point on the rail, inclination, grid.
struct PatchFrame {
  Side side = Side::right;
  Eigen::Vector3d reference = Eigen::Vector3d::Zero();  ///< P_ref on the rail (track frame, m)
  double inclination = 0;  ///< δ: rail inclination dZ/dy at P_ref as an angle (rad)

  /// Lateral axis t_s = (0, cos δ, sin δ): the grid's y, towards +y_track on both sides.
  Eigen::Vector3d lateral_axis() const { return {0, std::cos(inclination), std::sin(inclination)}; }
  /// Normal n = e_x × t_s = (0, −sin δ, cos δ), into the rail.
  Eigen::Vector3d normal() const { return {0, -std::sin(inclination), std::cos(inclination)}; }
  /// Contact angle of the normal from the vertical, positive leaning to the track centre.
  double contact_angle() const { return -side_sign(side) * inclination; }
};

/// A patch ready for a solver: frame, grid (x rolling, y = s lateral, relative to P_ref)
/// and the undeformed distance h on it (m, negative = interpenetration; approach 0).
struct ContactPatch {
  PatchFrame frame;
  Grid<double> grid;
  Eigen::VectorXd undeformed_distance;
};

/// The frame of a region: its weighted centre projected to the rail, weighted inclination.
inline PatchFrame patch_frame(const Track& track, const ContactRegion& region) {
  PatchFrame frame{region.side, region.centre, region.inclination};
  if (const auto rail = track.rail_height(region.side, region.centre.y())) frame.reference.z() = rail->value;
  return frame;
}

/// Extent of a region in its frame (m): rolling [x_lo, x_hi] from the overlap half-length
/// √(2ρ·pen) of every slice, lateral [s_lo, s_hi] from its rail points.
struct PatchExtent {
  double x_low = 0, x_high = 0, s_low = 0, s_high = 0;
};

namespace detail {

/// Where a slice of a region reaches in its patch's frame (m): lateral s of its rail point,
/// and rolling x_low…x_high, its locus x ± the overlap half-length √(2ρ·pen).
struct SliceReach {
  double s, x_low, x_high;
};

inline SliceReach slice_reach(const PatchFrame& frame, const GapSample& slice) {
  const double half_length = std::sqrt(2 * slice.wheel.radius * -slice.gap);
  const double x = slice.wheel.point.x() - frame.reference.x();
  const Eigen::Vector3d rail_point(slice.wheel.point.x(), slice.wheel.point.y(), slice.rail_z);
  return {(rail_point - frame.reference).dot(frame.lateral_axis()), x - half_length, x + half_length};
}

}  // namespace detail

inline PatchExtent patch_extent(const PatchFrame& frame, const ContactRegion& region) {
  PatchExtent extent{1e300, -1e300, 1e300, -1e300};
  for (const auto& slice : region.slices) {
    const auto reach = detail::slice_reach(frame, slice);
    extent.x_low = std::min(extent.x_low, reach.x_low);
    extent.x_high = std::max(extent.x_high, reach.x_high);
    extent.s_low = std::min(extent.s_low, reach.s);
    extent.s_high = std::max(extent.s_high, reach.s);
  }
  return extent;
}

/// The columns [first, last] of one row of a patch grid on which h is computed (none when
/// first > last), and whether an element there interpenetrates (h ≤ 0): what
/// touching_spans and undeformed_distance fill in (docs/wheel-rail.md §4, item 8).
struct RowSpan {
  Eigen::Index first = 0, last = -1;
  bool touches = false;
  bool empty() const { return first > last; }
};

/// For every row of `grid` (the patch of `region` in `frame`), the columns where an element
/// can interpenetrate, into `spans` (resized to grid.my()): every pair of neighbouring
/// slices covers the rows within one element of its lateral stretch and the columns within
/// one element of both slices' overlap √(2ρ·pen) around their locus x, as patch_extent.
/// The overlap of a slice bounds its section's: the wheel rises faster than the parabola
/// x²/2ρ along x, and its gap normal to an inclined rail is below the vertical gap pen.
inline void touching_spans(const PatchFrame& frame, const ContactRegion& region, const Grid<double>& grid,
                           std::vector<RowSpan>& spans) {
  spans.assign(static_cast<std::size_t>(grid.my()), RowSpan{});
  using detail::SliceReach;
  auto cover = [&](const SliceReach& a, const SliceReach& b) {
    const double s_low = std::min(a.s, b.s) - grid.dy(), s_high = std::max(a.s, b.s) + grid.dy();
    const auto first_j = std::max<Eigen::Index>(0, static_cast<Eigen::Index>(std::ceil((s_low - grid.y0()) / grid.dy())));
    const auto last_j =
        std::min<Eigen::Index>(grid.my() - 1, static_cast<Eigen::Index>(std::floor((s_high - grid.y0()) / grid.dy())));
    const double x_low = std::min(a.x_low, b.x_low) - grid.dx(), x_high = std::max(a.x_high, b.x_high) + grid.dx();
    const auto first_i = std::max<Eigen::Index>(0, static_cast<Eigen::Index>(std::floor((x_low - grid.x0()) / grid.dx())));
    const auto last_i =
        std::min<Eigen::Index>(grid.mx() - 1, static_cast<Eigen::Index>(std::ceil((x_high - grid.x0()) / grid.dx())));
    for (Eigen::Index j = first_j; j <= last_j && first_i <= last_i; ++j) {
      RowSpan& span = spans[static_cast<std::size_t>(j)];
      if (span.empty()) {
        span.first = first_i, span.last = last_i;
      } else {
        span.first = std::min(span.first, first_i), span.last = std::max(span.last, last_i);
      }
    }
  };
  if (region.slices.empty()) return;
  SliceReach before = detail::slice_reach(frame, region.slices.front());
  cover(before, before);
  for (std::size_t k = 1; k < region.slices.size(); ++k) {
    const SliceReach next = detail::slice_reach(frame, region.slices[k]);
    cover(before, next);
    before = next;
  }
}

/// The grid over an extent: element centres at whole multiples of (dx, ds) from P_ref, as
/// in CONTACT, with one guard element beyond the extent on every side.
inline Grid<double> patch_grid(const PatchExtent& extent, double dx, double ds) {
  FASTNORM_CHECK(std::isfinite(dx) && dx > 0, fastnorm::detail::describe("patch grid: dx must be positive (m)", dx));
  FASTNORM_CHECK(std::isfinite(ds) && ds > 0, fastnorm::detail::describe("patch grid: ds must be positive (m)", ds));
  const auto first_i = static_cast<Eigen::Index>(std::floor(extent.x_low / dx)) - 1;
  const auto last_i = static_cast<Eigen::Index>(std::ceil(extent.x_high / dx)) + 1;
  const auto first_j = static_cast<Eigen::Index>(std::floor(extent.s_low / ds)) - 1;
  const auto last_j = static_cast<Eigen::Index>(std::ceil(extent.s_high / ds)) + 1;
  return Grid<double>(last_i - first_i + 1, last_j - first_j + 1, dx, ds, static_cast<double>(first_i) * dx,
                      static_cast<double>(first_j) * ds);
}

/// Element sizes for a set of regions: the user's, or the largest extent over `elements`.
inline std::pair<double, double> element_sizes(const std::vector<PatchExtent>& extents, const PatchGridOptions& options) {
  options.validate();
  double length = 0, width = 0;
  for (const auto& extent : extents) {
    length = std::max(length, extent.x_high - extent.x_low);
    width = std::max(width, extent.s_high - extent.s_low);
  }
  const auto count = static_cast<double>(options.elements);
  return {options.element_length > 0 ? options.element_length : length / count,
          options.element_width > 0 ? options.element_width : std::max(width, 1e-6) / count};
}

}  // namespace fastnorm::wheelrail
