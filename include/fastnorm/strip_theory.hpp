#pragma once
/// @file strip_theory.hpp
/// Strip theory of steady rolling on a normal solution (docs/tangential.md §10): each run
/// of contact elements along a row is a two-dimensional rolling contact of its own length
/// and load, solved in closed form (Carter's adhesion zone at the leading edge, widened to
/// a lateral slip that grows along the strip with the spin), with compliances that give
/// Kalker's linear theory in full adhesion on each connected region of the contact. Its
/// slip zones carry μ p_n, turned towards the rigid slip by FASTSIM's step. The fast
/// tangential path: no grid dependence in adhesion, Carter's creep curve on long strips.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "fastnorm/constants.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/fastsim.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/kalker_coefficients.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/solution.hpp"
#include "fastnorm/tangential_problem.hpp"

namespace fastnorm {

/// Strip theory's constants for one connected region of a contact area
/// (docs/tangential.md Eq. (T15)): a strip's surface strain per unit traction (1/Pa) for the
/// longitudinal rigid slip, the lateral one and the lateral slip's growth along the strip
/// with the spin, and the flexibility (m/Pa) with which FASTSIM's step turns the traction
/// of a slip zone.
template <typename Scalar = double>
struct StripCompliance {
  Scalar longitudinal = 0;  ///< c_x
  Scalar lateral = 0;       ///< c_y
  Scalar spin = 0;          ///< c_φ
  Scalar turning = 0;       ///< L1 of (T10)
};

namespace detail {

/// ∫₀ˢ √(1 − σ²) dσ for s in [−1, 1].
template <typename Scalar>
Scalar ellipse_integral(Scalar s) {
  return (s * std::sqrt(std::max(Scalar(0), 1 - s * s)) + std::asin(s)) / 2;
}

/// The smallest root s ≥ 0 of a s² + b s + c = 0 with c ≤ 0, or 1 if it has none below 1.
template <typename Scalar>
Scalar smallest_root_below_one(Scalar a, Scalar b, Scalar c) {
  if (c == 0) return 0;
  if (a == 0) return b > 0 ? std::min(Scalar(1), -c / b) : Scalar(1);
  const Scalar discriminant = b * b - 4 * a * c;
  if (discriminant < 0) return 1;
  // The roots q/a and c/q, q = −(b + sign(b)√D)/2, without cancellation.
  const Scalar q = -(b + std::copysign(std::sqrt(discriminant), b)) / 2;
  Scalar smallest = 1;
  for (const Scalar root : {q / a, c / q})
    if (root >= 0 && root < smallest) smallest = root;
  return smallest;
}

}  // namespace detail

/// Steady rolling by strip theory (docs/tangential.md §10). The object keeps the material
/// and the workspace of the regions and strips, so that solving again allocates nothing once
/// it has met a contact of as many strips and regions.
template <typename Scalar = double>
class StripTheory {
 public:
  explicit StripTheory(const Material<Scalar>& material) : material_(material) {}

  /// Steady rolling on the normal solution `normal` of `grid` with Coulomb friction
  /// `friction` and the creepages `creepage`, into `answer` (whose storage it reuses).
  /// Each run of elements carrying pressure along a row is a strip of half-length a and
  /// amplitude P = 4 Σp/(π n), n its elements; with s = 1 at its leading edge and −1 at its
  /// trailing one, its rigid slip in traction units is v(s) = (w_x/c_x, w_y(centre)/c_y +
  /// (φ a/c_φ) s) (T13), and its adhesion zone [2s_c − 1, 1] carries
  ///
  ///     p = μP √(1 − s²) ê − A √(1 − t²),   t = (s − s_c)/(1 − s_c),
  ///     μP s_c ê = −v(s_c),   A = (1 − s_c)(μP ê + (0, φ a/c_φ))                      (T14)
  ///
  /// (Carter's solution where φ = 0; s_c the smallest root of |v(s)| = μP s); its slip zone
  /// carries μ p_n in the direction of the upstream traction minus dx·w/L1 (FASTSIM's
  /// step). An element takes the mean of (T14) over its part in the adhesion zone and the
  /// slip zone's traction in the share of its load the strip's ellipse puts on the rest,
  /// capped at μ p_n. Forces on body 1, as the exact path's.
  /// @throws fastnorm::invalid_argument as SteadyRollingSolver::solve
  void solve(const Grid<Scalar>& grid, const Solution<Scalar>& normal, Scalar friction, const Creepage<Scalar>& creepage,
             RollingDirection direction, TangentialSolution<Scalar>& answer) {
    detail::check_tangential_input(grid, normal, friction, creepage, "StripTheory::solve");
    detail::reset_answer(answer, grid.size());
    find_strips(grid, normal);
    if (strips_.empty()) return detail::mark_no_contact(answer);
    calibrate(grid);
    for (const Strip& strip : strips_) solve_strip(grid, normal, friction, creepage, direction, strip, answer);
    answer.sweeps = 1;
    answer.status = Status::converged;
    answer.message = "strip theory: one pass";
  }

  /// The same, returning the answer.
  TangentialSolution<Scalar> solve(const Grid<Scalar>& grid, const Solution<Scalar>& normal, Scalar friction,
                                   const Creepage<Scalar>& creepage,
                                   RollingDirection direction = RollingDirection::positive_x) {
    TangentialSolution<Scalar> answer;
    solve(grid, normal, friction, creepage, direction, answer);
    return answer;
  }

  /// The constants of each connected region of the last solve's contact area, in the order
  /// of their first strip (row by row from the grid's first).
  const std::vector<StripCompliance<Scalar>>& compliances() const { return compliances_; }

 private:
  struct Strip {
    Eigen::Index row = 0, begin = 0, end = 0;  ///< columns [begin, end)
    Eigen::Index region = 0;                   ///< union-find link, then the region's number
  };
  struct Extent {
    Eigen::Index count = 0, first_i = 0, last_i = 0, first_j = 0, last_j = 0;
    Scalar squared_half_lengths = 0;  ///< Σ a_s² over its strips
  };

  /// The runs of elements carrying pressure along each row, and their connected regions
  /// (runs of neighbouring rows that share a column), by union-find.
  void find_strips(const Grid<Scalar>& grid, const Solution<Scalar>& normal) {
    strips_.clear();
    Eigen::Index previous_row_begin = 0, previous_row_end = 0;
    for (Eigen::Index j = 0; j < grid.my(); ++j) {
      const Eigen::Index row_begin = static_cast<Eigen::Index>(strips_.size());
      for (Eigen::Index i = 0; i < grid.mx();) {
        if (!detail::carries_pressure(normal, grid.index(i, j))) {
          ++i;
          continue;
        }
        const Eigen::Index index = static_cast<Eigen::Index>(strips_.size());
        Strip strip{j, i, i + 1, index};
        while (strip.end < grid.mx() && detail::carries_pressure(normal, grid.index(strip.end, j))) ++strip.end;
        i = strip.end;
        strips_.push_back(strip);
        for (Eigen::Index above = previous_row_begin; above < previous_row_end; ++above) {
          const Strip& other = strips_[static_cast<std::size_t>(above)];
          if (other.begin < strip.end && strip.begin < other.end) unite(above, index);
        }
      }
      previous_row_begin = row_begin;
      previous_row_end = static_cast<Eigen::Index>(strips_.size());
    }
  }

  Eigen::Index root(Eigen::Index s) const {
    while (strips_[static_cast<std::size_t>(s)].region != s) s = strips_[static_cast<std::size_t>(s)].region;
    return s;
  }
  /// Joins the regions of strips a and b at the smaller root.
  void unite(Eigen::Index a, Eigen::Index b) {
    const Eigen::Index root_a = root(a), root_b = root(b);
    if (root_a != root_b) strips_[static_cast<std::size_t>(std::max(root_a, root_b))].region = std::min(root_a, root_b);
  }

  /// Numbers the regions, and gives each the constants of its equivalent ellipse (T15).
  void calibrate(const Grid<Scalar>& grid) {
    roots_.resize(strips_.size());
    for (std::size_t s = 0; s < strips_.size(); ++s) roots_[s] = root(static_cast<Eigen::Index>(s));
    // A region holds at least one strip: room for as many regions as strips, so that a patch
    // whose contact first splits into more regions does not allocate in a time step.
    extents_.reserve(strips_.size());
    compliances_.reserve(strips_.size());
    extents_.clear();
    for (std::size_t s = 0; s < strips_.size(); ++s) {
      Strip& strip = strips_[s];
      const auto top = static_cast<std::size_t>(roots_[s]);
      if (top == s) {  // the first strip of a region: roots_ holds its number from here on
        roots_[s] = static_cast<Eigen::Index>(extents_.size());
        extents_.push_back({0, strip.begin, strip.end - 1, strip.row, strip.row, 0});
      }
      strip.region = roots_[top];
      Extent& extent = extents_[static_cast<std::size_t>(strip.region)];
      const Eigen::Index count = strip.end - strip.begin;
      const Scalar half_length = static_cast<Scalar>(count) * grid.dx() / 2;
      extent.count += count;
      extent.first_i = std::min(extent.first_i, strip.begin), extent.last_i = std::max(extent.last_i, strip.end - 1);
      extent.last_j = strip.row;
      extent.squared_half_lengths += half_length * half_length;
    }
    const Scalar shear_modulus = material_.combined_shear_modulus(), nu = material_.combined_poisson_ratio();
    compliances_.clear();
    for (const Extent& extent : extents_) {
      const auto ellipse = detail::ellipse_of_extent(static_cast<Scalar>(extent.count) * grid.element_area(),
                                                     static_cast<Scalar>(extent.last_i - extent.first_i + 1) * grid.dx(),
                                                     static_cast<Scalar>(extent.last_j - extent.first_j + 1) * grid.dy());
      const auto coefficients = kalker_coefficients(ellipse.a / ellipse.b, nu);
      const Scalar c = std::sqrt(ellipse.a * ellipse.b);
      compliances_.push_back({pi<Scalar> * pi<Scalar> / (2 * shear_modulus * coefficients.c11),
                              pi<Scalar> * pi<Scalar> / (2 * shear_modulus * coefficients.c22),
                              pi<Scalar> / 2 * extent.squared_half_lengths * grid.dy() /
                                  (shear_modulus * c * c * c * coefficients.c23),
                              detail::flexibility_of(ellipse, shear_modulus, coefficients).longitudinal});
    }
  }

  /// One strip by (T13)–(T14), its elements from the leading edge.
  void solve_strip(const Grid<Scalar>& grid, const Solution<Scalar>& normal, Scalar friction,
                   const Creepage<Scalar>& creepage, RollingDirection direction, const Strip& strip,
                   TangentialSolution<Scalar>& answer) const {
    const StripCompliance<Scalar>& compliance = compliances_[static_cast<std::size_t>(strip.region)];
    const bool positive = direction == RollingDirection::positive_x;
    const Scalar sense = positive ? Scalar(1) : Scalar(-1), dx = grid.dx(), y = grid.y(strip.row);
    const Eigen::Index count = strip.end - strip.begin;
    const Scalar n = static_cast<Scalar>(count), half_length = n * dx / 2;
    const Scalar centre = (grid.x(strip.begin) + grid.x(strip.end - 1)) / 2;
    Scalar load = 0;
    for (Eigen::Index i = strip.begin; i < strip.end; ++i) load += normal.pressure(grid.index(i, strip.row));
    const Scalar bound = friction * 4 * load / (pi<Scalar> * n);  // μP
    const Scalar rigid_x = creepage.longitudinal - creepage.spin * (y - creepage.spin_centre_y);
    // v(s) = (vx, v0 + v1 s) (T13) and the centre s_c of the adhesion zone (T14).
    const Scalar vx = rigid_x / compliance.longitudinal;
    const Scalar v0 = (creepage.lateral + creepage.spin * (centre - creepage.spin_centre_x)) / compliance.lateral;
    const Scalar v1 = creepage.spin * sense * half_length / compliance.spin;
    const Scalar centre_s = detail::smallest_root_below_one(bound * bound - v1 * v1, -2 * v0 * v1, -(vx * vx + v0 * v0));
    const Scalar radius = 1 - centre_s, inverse_radius = radius > 0 ? 1 / radius : Scalar(0), per_length = n / 2;
    Scalar ex = 1, ey = 0;  // ê; where s_c = 0 it cancels from (T14)
    const Scalar ux = -vx, uy = -(v0 + v1 * centre_s), u = std::sqrt(ux * ux + uy * uy);
    if (u > 0) ex = ux / u, ey = uy / u;
    const Scalar ax = radius * bound * ex, ay = radius * (bound * ey + v1);
    // The integrals of both ellipses up to the element's upstream edge, carried along.
    Scalar large_edge = detail::ellipse_integral(Scalar(1)), small_edge = large_edge;
    Scalar upstream_x = 0, upstream_y = 0;
    for (Eigen::Index step = 0; step < count; ++step) {
      const Eigen::Index i = positive ? strip.end - 1 - step : strip.begin + step, k = grid.index(i, strip.row);
      const Scalar high = 1 - 2 * static_cast<Scalar>(step) / n, low = 1 - 2 * static_cast<Scalar>(step + 1) / n;
      const Scalar cap = friction * normal.pressure(k), x = grid.x(i);
      const Scalar wy = creepage.lateral + creepage.spin * (x - creepage.spin_centre_x);
      // The element's part in the adhesion zone [2s_c − 1, 1] takes its mean of (T14), the
      // rest μ p_n turned by FASTSIM's step, shared as the strip's ellipse shares the
      // element's load: continuous as the zone's end crosses the element.
      const Scalar zone_end = 2 * centre_s - 1;
      const Scalar adhesion_share =
          radius > 0 ? std::clamp((high - zone_end) * per_length, Scalar(0), Scalar(1)) : Scalar(0);
      Scalar px = 0, py = 0, slip_share = 1;
      if (adhesion_share > 0) {
        const Scalar end = std::max(low, zone_end);
        const Scalar large_end = detail::ellipse_integral(end);
        const Scalar small_end = detail::ellipse_integral(std::max(Scalar(-1), (end - centre_s) * inverse_radius));
        if (adhesion_share < 1) {
          const Scalar large_low = detail::ellipse_integral(low);
          slip_share = (large_end - large_low) / (large_edge - large_low);
        }
        const Scalar large = bound * (large_edge - large_end) * per_length;
        const Scalar small = radius * (small_edge - small_end) * per_length;
        large_edge = large_end, small_edge = small_end;
        px = large * ex - ax * small;
        py = large * ey - ay * small;
      }
      Scalar magnitude = cap;  // |p|, known where the element slides entirely
      if (adhesion_share < 1) {
        const Scalar tx = upstream_x - dx * rigid_x / compliance.turning, ty = upstream_y - dx * wy / compliance.turning;
        const Scalar size = std::sqrt(tx * tx + ty * ty), scale = size > 0 ? slip_share * cap / size : Scalar(0);
        px += scale * tx, py += scale * ty;
        if (size == 0) magnitude = 0;
      }
      bool adheres = adhesion_share >= Scalar(0.5);
      if (adhesion_share > 0) {
        const Scalar size_squared = px * px + py * py;
        magnitude = std::sqrt(size_squared);
        if (magnitude > cap) {  // where the pressure is below the strip's ellipse
          px *= cap / magnitude, py *= cap / magnitude;
          magnitude = cap;
          adheres = false;
        }
      }
      upstream_x = px, upstream_y = py;
      answer.traction_x(k) = px;
      answer.traction_y(k) = py;
      answer.state(k) = adheres ? TractionState::adhesion : TractionState::slip;
      Scalar traction_times_slip = 0;
      if (!adheres) {
        // The slip's size from the strip's strain outside its adhesion zone (the Hilbert
        // transform of (T14) there), against the traction.
        const Scalar middle = (high + low) / 2, t = (middle - centre_s) * inverse_radius;
        const Scalar outside = radius > 0 ? t + std::sqrt(std::max(Scalar(0), t * t - 1)) : Scalar(0);
        const Scalar sx = compliance.longitudinal * (vx + bound * ex * middle - ax * outside);
        const Scalar sy = compliance.lateral * (v0 + bound * ey * middle - ay * outside) + compliance.spin * v1 * middle;
        const Scalar slip = std::sqrt(sx * sx + sy * sy), along = magnitude > 0 ? slip / magnitude : Scalar(0);
        answer.slip_x(k) = -along * px, answer.slip_y(k) = -along * py;
        traction_times_slip = magnitude * slip;
      }
      detail::add_element(answer, grid.element_area(), x, y, k, traction_times_slip);
    }
  }

  Material<Scalar> material_;
  std::vector<Strip> strips_;
  std::vector<Extent> extents_;
  std::vector<Eigen::Index> roots_;  ///< per strip: its region's root, then for a root its number
  std::vector<StripCompliance<Scalar>> compliances_;
};

}  // namespace fastnorm
