#pragma once
/// @file strips.hpp
/// Strips and segments of a contact set (docs/design.md §4, docs/method.md §1): a strip
/// is a line of constant lateral index j; in a contact set each strip's elements form
/// contiguous runs, the segments.

#include <Eigen/Core>
#include <vector>

#include "fastnorm/error.hpp"
#include "fastnorm/grid.hpp"

namespace fastnorm {

/// A contiguous run of contact elements along the rolling direction in one strip.
struct Segment {
  Eigen::Index strip = 0;        ///< lateral index j
  Eigen::Index first = 0;        ///< rolling index i of the first element
  Eigen::Index count = 0;        ///< number of elements
  Eigen::Index set_position = 0; ///< position of the first element in the sorted set

  Eigen::Index last() const { return first + count - 1; }
  /// Centre x_c (m) of the segment.
  template <typename Scalar>
  Scalar centre(const Grid<Scalar>& grid) const {
    return (grid.x(first) + grid.x(last())) / 2;
  }
  /// Half-length L = count·dx/2 (m).
  template <typename Scalar>
  Scalar half_length(const Grid<Scalar>& grid) const {
    return static_cast<Scalar>(count) * grid.dx() / 2;
  }
  bool operator==(const Segment& other) const {
    return strip == other.strip && first == other.first && count == other.count;
  }
};

/// Local coordinates ξ = (x − x_c)/L of the element centres of a segment of `count`
/// elements: ξ_m = (2m − count + 1)/count, in (−1, 1). They depend on the count only.
template <typename Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, 1> segment_coordinates(Eigen::Index count) {
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> xi(count);
  for (Eigen::Index m = 0; m < count; ++m) {
    xi(m) = static_cast<Scalar>(2 * m - count + 1) / static_cast<Scalar>(count);
  }
  return xi;
}

/// The segments of a contact set, in the order of the set, into `segments` (cleared first;
/// its storage is reused).
/// @param set element numbers k = i + mx·j, sorted ascending, each < grid.size()
/// @throws fastnorm::invalid_argument if `set` is not sorted or out of range
template <typename Scalar>
void segment_strips(const Grid<Scalar>& grid, const std::vector<Eigen::Index>& set, std::vector<Segment>& segments) {
  segments.clear();
  const std::size_t size = set.size();
  std::size_t position = 0;
  while (position < size) {
    const Eigen::Index k = set[position];
    FASTNORM_CHECK(k >= 0 && k < grid.size(), detail::describe("segment_strips: element out of the grid", k));
    FASTNORM_CHECK(position == 0 || set[position - 1] < k, "segment_strips: set must be sorted and unique");
    const Eigen::Index j = grid.j_of(k);  // a division per segment, not per element
    const Eigen::Index strip_end = (j + 1) * grid.mx();
    // The run continues while each element follows its predecessor within the strip (such
    // an element is in range and in order, so only a segment's first needs the checks).
    std::size_t end = position + 1;
    while (end < size && set[end] == set[end - 1] + 1 && set[end] < strip_end) ++end;
    segments.push_back(Segment{j, k - j * grid.mx(), static_cast<Eigen::Index>(end - position),
                               static_cast<Eigen::Index>(position)});
    position = end;
  }
}

/// The segments of a contact set, in the order of the set (see above).
template <typename Scalar>
std::vector<Segment> segment_strips(const Grid<Scalar>& grid, const std::vector<Eigen::Index>& set) {
  std::vector<Segment> segments;
  segment_strips(grid, set, segments);
  return segments;
}

}  // namespace fastnorm
