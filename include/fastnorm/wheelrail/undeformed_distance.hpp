#pragma once
/// @file undeformed_distance.hpp
/// The undeformed distance h(x, s) between wheel and rail on a patch grid
/// (docs/wheel-rail.md §4, item 6): exact at every element, or exact at nodes along each row
/// and interpolated between them within a stated bound (docs/wheel-rail.md §4, item 7).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "fastnorm/error.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/wheelrail/patch.hpp"
#include "fastnorm/wheelrail/track.hpp"
#include "fastnorm/wheelrail/wheelset.hpp"

namespace fastnorm::wheelrail {

/// Where undeformed_distance looks for the wheel surface along the normal line through a
/// rail point (m, + into the rail): docs/wheel-rail.md §4.
struct NormalSearch {
  static constexpr double below = -0.020;  ///< farthest out of the rail
  static constexpr double above = 0.005;   ///< farthest into it
  static constexpr double tolerance = 1e-13;
};

/// Gap value where a grid point has no wheel or rail surface along its normal (m).
inline constexpr double no_surface_gap = 1.0;

/// Along a row, the wheel's root is extrapolated from the previous elements' roots and
/// accepted after one Newton step that moves it by at most this much (m). Newton's error
/// after that step is about |G''/2G'|·step², and |G''/2G'| stays below about 100 /m for the
/// profiles' curvatures: at most 4e-12 m (docs/wheel-rail.md §4, tested against bisection).
inline constexpr double one_step_acceptance = 2e-7;

/// A node of h by rows (interpolate_row) takes its slope dt/di from the last evaluation of
/// Newton's method when the last step moved the root by at most this much (m), instead of
/// evaluating once more at the root: the slope then differs from the root's by about
/// |∂(G_i/G_t)/∂t|·step, and the interpolated h by about that times a quarter interval
/// (docs/wheel-rail.md §4, item 7).
inline constexpr double slope_reuse_step = 1e-8;

/// How h is computed on a patch grid: exactly at every element (tolerance 0), or exactly at
/// nodes about `node_spacing` apart along each row and by cubic Hermite interpolation
/// between them wherever the interpolation error, estimated from the row's own fourth
/// derivative, stays below `tolerance`; exactly elsewhere (docs/wheel-rail.md §4, item 7).
struct DistanceAccuracy {
  double tolerance = 1e-10;     ///< bound on the interpolation error (m); 0: every element exactly
  double node_spacing = 4e-3;   ///< distance between nodes along a row (m)

  /// @throws fastnorm::invalid_argument naming the offending field
  void validate() const {
    FASTNORM_CHECK(std::isfinite(tolerance) && tolerance >= 0,
                   fastnorm::detail::describe("DistanceAccuracy: tolerance must be >= 0 (m)", tolerance));
    fastnorm::detail::check_positive(node_spacing, "DistanceAccuracy: node_spacing (m)");
  }
};

namespace detail {

/// The normal lines of a patch grid: for element (i, j) the line q_ij + t·n, q_ij =
/// P_ref + x_i e_x + s_j t_s, on which the rail lies at one t for the whole row (the rail is
/// a prism along x) and the wheel at the root of G(i, t) = √(x_w² + z_w²) − ρ(y_w), in
/// wheelset coordinates (docs/wheel-rail.md §4, item 6). i may be fractional.
class NormalLines {
 public:
  /// G and its partial derivatives in t (along n) and in i (one element along the row).
  struct Excess {
    double value = 0, along_normal = 0, along_row = 0;
    bool off_profile = false;  ///< the point lies beyond the wheel profile
  };

  NormalLines(const Track& track, const Wheelset& wheelset, const WheelsetPose& pose, const PatchFrame& frame,
              const Grid<double>& grid)
      : track_(track), wheelset_(wheelset), frame_(frame), grid_(grid) {
    check_pose(pose, "undeformed_distance");
    FASTNORM_CHECK(frame.reference.allFinite() && std::isfinite(frame.inclination),
                   "undeformed_distance: the patch frame's reference point and inclination must be finite");
    rotation_ = Wheelset::rotation(pose);
    centre_ = wheelset.centre(pose);
    normal_ = frame.normal();
    normal_in_wheelset_ = rotation_.transpose() * normal_;
    step_in_wheelset_ = grid.dx() * rotation_.row(0).transpose();  // R^T e_x dx
  }

  /// Moves to row j; the rail's distance along the row's normal lines, empty if it has none.
  std::optional<double> start_row(Eigen::Index j) {
    const Eigen::Vector3d row_point = frame_.reference + grid_.y(j) * frame_.lateral_axis();
    Eigen::Vector3d offset = row_point - centre_;  // of the row's first element, track frame
    offset.x() += grid_.x(0);
    row_start_ = rotation_.transpose() * offset;
    return track_.distance_to_rail(frame_.side, row_point.y(), row_point.z(), normal_.y(), normal_.z(), rail_profile_y_);
  }

  /// G at (i, t) of the current row: negative inside the wheel, rising along n.
  Excess excess(double i, double t) const {
    const Eigen::Vector3d p = row_start_ + i * step_in_wheelset_ + t * normal_in_wheelset_;
    const auto profile_y = wheelset_.profile_coordinate(frame_.side, p.y());
    if (!profile_y) return {0, 1, 0, true};
    const double distance = std::sqrt(p.x() * p.x() + p.z() * p.z());  // metres: no overflow
    const auto rho = wheelset_.radius(frame_.side, *profile_y);
    auto derivative = [&](const Eigen::Vector3d& direction) {
      return (p.x() * direction.x() + p.z() * direction.z()) / distance - rho.slope * direction.y();
    };
    return {distance - rho.value, derivative(normal_in_wheelset_), derivative(step_in_wheelset_), false};
  }

  /// The wheel's root t at element i found by Newton's method, with the evaluation its last
  /// step started from and how far that step moved (interpolate_row's nodes take their slope
  /// from it when the step was short).
  struct RootNear {
    double t = 0;
    Excess last;
    double last_step = 0;
  };

  /// The wheel's root at element i from a close `guess`: Newton, accepted after one step of at
  /// most one_step_acceptance or when it converges; empty if it does not (then
  /// root_bracketed).
  std::optional<RootNear> root_near(double i, double guess) const {
    bool off_profile = false;
    RootNear near;
    double last_t = guess;
    const auto root = fastnorm::wheelrail::detail::newton_root(
        [&](double t) {
          last_t = t;
          return along_normal(i, t, off_profile, near.last);
        },
        guess, NormalSearch::below, NormalSearch::above, NormalSearch::tolerance, one_step_acceptance);
    if (off_profile || !root) return std::nullopt;
    near.t = *root;
    near.last_step = std::abs(*root - last_t);
    return near;
  }

  /// The wheel's root at element i anywhere in the search interval (`guess` inside it);
  /// empty where the line meets no wheel surface.
  std::optional<double> root_bracketed(double i, double guess) const {
    bool off_profile = false;
    Excess evaluated;
    auto f = [&](double t) { return along_normal(i, t, off_profile, evaluated); };
    const double at_low = f(NormalSearch::below).value, at_high = f(NormalSearch::above).value;
    if (off_profile || (at_low < 0) == (at_high < 0)) return std::nullopt;
    const double root = fastnorm::wheelrail::detail::bracketed_root(f, NormalSearch::below, at_low, NormalSearch::above,
                                                                    guess, NormalSearch::tolerance);
    if (off_profile) return std::nullopt;
    return root;
  }

  /// Elements [first, last] of the current row exactly into `h` (rail distance `rail`),
  /// continuing from `seed`, the root at element first − 1 (NaN: none): each root
  /// extrapolated from the last three and accepted by root_near, bracketed where that fails.
  void exact_elements(Eigen::Index first, Eigen::Index last, Eigen::Index j, double rail, double seed,
                      Eigen::VectorXd& h) const {
    std::array<double, 3> roots{seed, 0, 0};  // the last roots, newest first
    int known = std::isnan(seed) ? 0 : 1;      // how many of them are valid
    for (Eigen::Index i = first; i <= last; ++i) {
      const auto at = static_cast<double>(i);
      std::optional<double> root;
      if (known > 0) {
        const double guess = known == 3 ? 3 * roots[0] - 3 * roots[1] + roots[2]
                             : known == 2 ? 2 * roots[0] - roots[1]
                                          : roots[0];
        if (const auto near = root_near(at, guess)) root = near->t;
      }
      if (!root) root = root_bracketed(at, known > 0 ? roots[0] : rail);
      if (!root) {
        h(grid_.index(i, j)) = no_surface_gap;
        known = 0;
        continue;
      }
      roots = {*root, roots[0], roots[1]};
      known = std::min(known + 1, 3);
      h(grid_.index(i, j)) = rail - *root;
    }
  }

  const Grid<double>& grid() const { return grid_; }

 private:
  /// G and G_t at (i, t), the whole evaluation into `at`; `off_profile` set if it lies
  /// beyond the profile.
  fastnorm::wheelrail::ProfileValue<double> along_normal(double i, double t, bool& off_profile, Excess& at) const {
    at = excess(i, t);
    off_profile = off_profile || at.off_profile;
    return {at.value, at.along_normal};
  }

  const Track& track_;
  const Wheelset& wheelset_;
  const PatchFrame& frame_;
  const Grid<double>& grid_;
  Eigen::Matrix3d rotation_;
  Eigen::Vector3d centre_, normal_, normal_in_wheelset_, step_in_wheelset_, row_start_;
  double rail_profile_y_ = std::numeric_limits<double>::quiet_NaN();  // where the last row met the rail
};

/// Columns [first, last] of row j of h by nodes and cubic Hermite interpolation
/// (docs/wheel-rail.md §4, item 7). Nodes every `span` elements from `first_column` (the last
/// interval may be shorter) carry the exact root t and
/// its slope dt/di. On an interval of L elements the Hermite cubic is within L⁴/384·max|t⁗|
/// of t; t⁗ is estimated from the jumps of the cubics' third derivatives between
/// neighbouring intervals, and an interval whose bound, times a safety factor of 4, exceeds
/// `tolerance` is computed exactly. `first_root` holds the previous row's first node root
/// (NaN: none), where this row's first node starts, and receives this row's. Returns false
/// if a node has no wheel surface (the caller then computes the row exactly).
inline bool interpolate_row(const NormalLines& lines, Eigen::Index j, Eigen::Index first_column, Eigen::Index last,
                            double rail, Eigen::Index span, double tolerance, double& first_root, Eigen::VectorXd& h) {
  struct Node {
    double i = 0, t = 0, slope = 0;  // position (elements), root (m), dt/di (m per element)
  };
  const Grid<double>& grid = lines.grid();
  if (last <= first_column) return false;
  const Eigen::Index intervals = (last - first_column + span - 1) / span;
  std::array<Node, 4> ring;  // nodes q − 1 … q + 2 of interval q, at (q mod 4)
  auto node_position = [&](Eigen::Index q) { return static_cast<double>(std::min(first_column + q * span, last)); };
  // Node q exact: Newton from the previous nodes' extrapolation (the previous row's first
  // node for the first: rows move smoothly too), bracketed where that fails; the slope
  // −G_i/G_t from Newton's last evaluation where it lay close to the root, else from one
  // correction at the root.
  auto compute_node = [&](Eigen::Index q) -> bool {
    const double i = node_position(q);
    std::optional<NormalLines::RootNear> near;
    if (q > 0) {
      const Node& previous = ring[static_cast<std::size_t>((q - 1) % 4)];
      const double length = i - previous.i;
      double guess = previous.t + previous.slope * length;
      if (q > 1) {
        const Node& before = ring[static_cast<std::size_t>((q - 2) % 4)];
        guess += (previous.slope - before.slope) / (previous.i - before.i) * length * length / 2;
      }
      near = lines.root_near(i, guess);
    } else if (!std::isnan(first_root)) {
      near = lines.root_near(i, first_root);
    }
    Node& node = ring[static_cast<std::size_t>(q % 4)];
    if (near && near->last_step <= slope_reuse_step) {
      node = {i, near->t, -near->last.along_row / near->last.along_normal};
      return true;
    }
    std::optional<double> root;
    if (near) root = near->t;
    if (!root) root = lines.root_bracketed(i, q > 0 ? ring[static_cast<std::size_t>((q - 1) % 4)].t : rail);
    if (!root) return false;
    const auto at = lines.excess(i, *root);
    if (at.off_profile || at.along_normal == 0) return false;
    node = {i, *root - at.value / at.along_normal, -at.along_row / at.along_normal};
    return true;
  };
  // The interpolation error at an interval's midpoint, where a smooth t's error peaks: one
  // Newton correction −G/G_t from the interpolated root (infinite off the profile).
  auto midpoint_error = [&](double start, double t, double slope, double c2, double c3, double length) {
    const double d = length / 2;
    const auto at = lines.excess(start + d, t + d * (slope + d * (c2 + d * c3)));
    if (at.off_profile || at.along_normal == 0) return std::numeric_limits<double>::infinity();
    return std::abs(at.value / at.along_normal);
  };
  // Third derivative of interval q's cubic (constant on it), per element³.
  auto third_derivative = [&](Eigen::Index q) {
    const Node& a = ring[static_cast<std::size_t>(q % 4)];
    const Node& b = ring[static_cast<std::size_t>((q + 1) % 4)];
    const double length = b.i - a.i;
    return 6 * (2 * (a.t - b.t) + length * (a.slope + b.slope)) / (length * length * length);
  };
  if (!compute_node(0)) return false;
  first_root = ring[0].t;
  if (!compute_node(1)) return false;
  if (intervals > 1 && !compute_node(2)) return false;
  double previous_third = 0, this_third = third_derivative(0);
  for (Eigen::Index q = 0; q < intervals; ++q) {
    if (q + 2 <= intervals && q > 0 && !compute_node(q + 2)) return false;
    const Node& a = ring[static_cast<std::size_t>(q % 4)];
    const Node& b = ring[static_cast<std::size_t>((q + 1) % 4)];
    const double length = b.i - a.i;
    const double next_third = q + 1 < intervals ? third_derivative(q + 1) : this_third;
    // |t⁗| from the jumps to the neighbours' third derivatives (each over the distance of the
    // intervals' midpoints); a row of one interval has no estimate and is computed exactly.
    double fourth = 0;
    if (q > 0) {
      const double before = ring[static_cast<std::size_t>((q + 3) % 4)].i;  // node q − 1
      fourth = std::max(fourth, std::abs(this_third - previous_third) / ((b.i - before) / 2));
    }
    if (q + 1 < intervals) {
      const double after = ring[static_cast<std::size_t>((q + 2) % 4)].i;  // node q + 2
      fourth = std::max(fourth, std::abs(next_third - this_third) / ((after - a.i) / 2));
    }
    // The Hermite cubic in powers of d = i − i_a: t = t_a + m_a d + c₂ d² + c₃ d³.
    const double secant = (b.t - a.t) / length;
    const double c2 = (3 * secant - 2 * a.slope - b.slope) / length;
    const double c3 = (a.slope + b.slope - 2 * secant) / (length * length);
    const double bound = 4 * fourth * length * length * length * length / 384;
    const auto first = static_cast<Eigen::Index>(a.i), end = static_cast<Eigen::Index>(b.i);
    h(grid.index(first, j)) = rail - a.t;
    if (intervals > 1 && bound <= tolerance && midpoint_error(a.i, a.t, a.slope, c2, c3, length) <= tolerance / 2) {
      double* row = h.data() + grid.index(0, j);
      for (Eigen::Index i = first + 1; i < end; ++i) {
        const double d = static_cast<double>(i - first);
        row[i] = rail - (a.t + d * (a.slope + d * (c2 + d * c3)));
      }
    } else if (end > first + 1) {
      lines.exact_elements(first + 1, end - 1, j, rail, a.t, h);
    }
    previous_third = this_third;
    this_third = next_third;
  }
  h(grid.index(last, j)) = rail - ring[static_cast<std::size_t>(intervals % 4)].t;
  return true;
}

/// h to `accuracy` on the rows of a patch grid, one row at a time (NormalLines kept).
class RowDistance {
 public:
  RowDistance(const Track& track, const Wheelset& wheelset, const WheelsetPose& pose, const PatchFrame& frame,
              const Grid<double>& grid, const DistanceAccuracy& accuracy)
      : lines_(track, wheelset, pose, frame, grid),
        span_(static_cast<Eigen::Index>(std::floor(accuracy.node_spacing / grid.dx()))),
        tolerance_(accuracy.tolerance),
        by_rows_(accuracy.tolerance > 0 && span_ >= 2) {}

  /// Columns [first, last] of row j into h.
  void row(Eigen::Index j, Eigen::Index first, Eigen::Index last, Eigen::VectorXd& h) {
    const Grid<double>& grid = lines_.grid();
    const auto rail = lines_.start_row(j);
    if (!rail) {
      for (Eigen::Index i = first; i <= last; ++i) h(grid.index(i, j)) = no_surface_gap;
      first_root_ = none;
      return;
    }
    // The previous row's first node starts this one's only where both start at one column.
    if (first != first_column_) first_root_ = none;
    first_column_ = first;
    if (!(by_rows_ && interpolate_row(lines_, j, first, last, *rail, span_, tolerance_, first_root_, h))) {
      first_root_ = none;
      lines_.exact_elements(first, last, j, *rail, none, h);
    }
  }

 private:
  static constexpr double none = std::numeric_limits<double>::quiet_NaN();
  NormalLines lines_;
  Eigen::Index span_;
  double tolerance_;
  bool by_rows_;
  double first_root_ = none;  // of the last row interpolated: where the next row's first node starts
  Eigen::Index first_column_ = 0;
};

}  // namespace detail

/// h to `accuracy` (docs/wheel-rail.md §4, item 7): along each row exact at nodes and
/// interpolated between them where the estimated error is below accuracy.tolerance, exact
/// elsewhere; every element exactly if the tolerance is 0 or the nodes would be less than
/// two elements apart. `h` is resized to the grid.
/// @throws fastnorm::invalid_argument for a pose outside PoseLimits, a non-finite frame or
///         a bad accuracy
inline void undeformed_distance(const Track& track, const Wheelset& wheelset, const WheelsetPose& pose,
                                const PatchFrame& frame, const Grid<double>& grid, const DistanceAccuracy& accuracy,
                                Eigen::VectorXd& h) {
  accuracy.validate();
  detail::RowDistance rows(track, wheelset, pose, frame, grid, accuracy);
  h.resize(grid.size());
  for (Eigen::Index j = 0; j < grid.my(); ++j) rows.row(j, 0, grid.mx() - 1, h);
}

/// h at an element that undeformed_distance(…, spans, h) leaves out because it cannot
/// interpenetrate: a positive placeholder (m), not a distance (docs/wheel-rail.md §4, item 8).
inline constexpr double not_computed_gap = 1e-3;

/// h to `accuracy` only where an element can interpenetrate (docs/wheel-rail.md §4, item 8):
/// on the columns of `spans` (touching_spans of the patch's region; one per row) and
/// wherever these checks lead, not_computed_gap elsewhere. A span is widened to its whole
/// row unless h is positive at both its ends and rises outwards there (h is convex along a
/// row: x²/2ρ dominates); a row left out is computed whole when a neighbour interpenetrates.
/// On return `spans` holds what was computed and `touches` which rows interpenetrate. Every
/// interpenetrating element of the region is then computed, to the bound of the overload
/// above (its nodes start at each span's first column; tested on thousands of poses); one
/// of another region whose interpenetration reaches into the grid may be left out. `h` is
/// resized to the grid.
/// @throws fastnorm::invalid_argument as the overload above, or for spans of another grid
inline void undeformed_distance(const Track& track, const Wheelset& wheelset, const WheelsetPose& pose,
                                const PatchFrame& frame, const Grid<double>& grid, const DistanceAccuracy& accuracy,
                                std::vector<RowSpan>& spans, Eigen::VectorXd& h) {
  accuracy.validate();
  FASTNORM_CHECK(static_cast<Eigen::Index>(spans.size()) == grid.my(),
                 "undeformed_distance: spans must hold one span per grid row");
  detail::RowDistance rows(track, wheelset, pose, frame, grid, accuracy);
  h.setConstant(grid.size(), not_computed_gap);
  const Eigen::Index last_column = grid.mx() - 1;
  auto at = [&](Eigen::Index i, Eigen::Index j) { return h(grid.index(i, j)); };
  // Computes `span` of row j and notes whether it interpenetrates.
  auto compute = [&](RowSpan& span, Eigen::Index j) {
    rows.row(j, span.first, span.last, h);
    span.touches = h.segment(grid.index(span.first, j), span.last - span.first + 1).minCoeff() <= 0;
  };
  // Positive and rising outwards at both ends (an end on the grid's edge needs neither).
  auto closed = [&](const RowSpan& span, Eigen::Index j) {
    const bool left = span.first == 0 || (span.first < span.last && at(span.first, j) > 0 &&
                                          at(span.first, j) >= at(span.first + 1, j));
    const bool right = span.last == last_column || (span.first < span.last && at(span.last, j) > 0 &&
                                                    at(span.last, j) >= at(span.last - 1, j));
    return left && right;
  };
  for (Eigen::Index j = 0; j < grid.my(); ++j) {
    RowSpan& span = spans[static_cast<std::size_t>(j)];
    if (span.empty()) continue;
    FASTNORM_CHECK(span.first >= 0 && span.last <= last_column, "undeformed_distance: a span leaves the grid");
    compute(span, j);
    if (!closed(span, j)) {
      span = {0, last_column};
      compute(span, j);
    }
  }
  auto touches = [&](Eigen::Index j) { return j >= 0 && j < grid.my() && spans[static_cast<std::size_t>(j)].touches; };
  for (bool grew = true; grew;) {
    grew = false;
    for (Eigen::Index j = 0; j < grid.my(); ++j) {
      RowSpan& span = spans[static_cast<std::size_t>(j)];
      if (!span.empty() || !(touches(j - 1) || touches(j + 1))) continue;
      span = {0, last_column};
      compute(span, j);
      grew = true;
    }
  }
}

/// The exact undeformed distance h = n_rail − n_wheel at every element centre of `grid`
/// (docs/wheel-rail.md §4, item 6): the rail along the normal line through
/// q = P_ref + x e_x + s t_s by a 2-D intersection, the wheel by solving
/// √(x_w² + z_w²) = ρ(y_w) in wheelset coordinates. `h` is resized to the grid.
/// @throws fastnorm::invalid_argument for a pose outside PoseLimits or a non-finite frame
inline void undeformed_distance(const Track& track, const Wheelset& wheelset, const WheelsetPose& pose,
                                const PatchFrame& frame, const Grid<double>& grid, Eigen::VectorXd& h) {
  DistanceAccuracy exact;
  exact.tolerance = 0;
  undeformed_distance(track, wheelset, pose, frame, grid, exact, h);
}

/// The same, returned.
inline Eigen::VectorXd undeformed_distance(const Track& track, const Wheelset& wheelset, const WheelsetPose& pose,
                                           const PatchFrame& frame, const Grid<double>& grid) {
  Eigen::VectorXd h;
  undeformed_distance(track, wheelset, pose, frame, grid, h);
  return h;
}

}  // namespace fastnorm::wheelrail
