#pragma once
/// @file grid.hpp
/// The potential contact area: a regular grid of mx × my rectangles (docs/design.md §1).

#include <Eigen/Core>
#include <cmath>
#include <type_traits>

#include "fastnorm/error.hpp"

namespace fastnorm {

/// A regular grid of `mx × my` rectangular elements of size `dx × dy` (m).
///
/// `x` is the rolling direction (index `i`, fastest in memory), `y` the lateral
/// direction (index `j`). Element `k = i + mx·j` has its centre at
/// `(x0 + i·dx, y0 + j·dy)`.
///
/// Class invariant: mx, my ≥ 1; dx, dy > 0 and finite; x0, y0 finite.
///
/// **Example**
/// @code
/// fastnorm::Grid<> grid(60, 60, 1e-4, 1e-4, -3e-3, -3e-3);
/// double x = grid.x_of(grid.index(3, 4));  // -3e-3 + 3e-4
/// @endcode
template <typename Scalar = double>
class Grid {
  static_assert(std::is_floating_point_v<Scalar>, "fastnorm::Grid needs a floating-point Scalar");

 public:
  using Index = Eigen::Index;

  /// @param mx elements in the rolling direction x (≥ 1)
  /// @param my elements in the lateral direction y (≥ 1)
  /// @param dx element length in x (m, > 0)
  /// @param dy element length in y (m, > 0)
  /// @param x0 x of the centre of element (0, 0) (m)
  /// @param y0 y of the centre of element (0, 0) (m)
  /// @throws fastnorm::invalid_argument naming the offending argument
  Grid(Index mx, Index my, Scalar dx, Scalar dy, Scalar x0 = Scalar(0), Scalar y0 = Scalar(0))
      : mx_(mx), my_(my), dx_(dx), dy_(dy), x0_(x0), y0_(y0) {
    FASTNORM_CHECK(mx >= 1, detail::describe("grid: mx must be >= 1", mx));
    FASTNORM_CHECK(my >= 1, detail::describe("grid: my must be >= 1", my));
    FASTNORM_CHECK(std::isfinite(dx) && dx > 0,
                   detail::describe("grid: dx must be positive and finite", dx));
    FASTNORM_CHECK(std::isfinite(dy) && dy > 0,
                   detail::describe("grid: dy must be positive and finite", dy));
    FASTNORM_CHECK(std::isfinite(x0), detail::describe("grid: x0 must be finite", x0));
    FASTNORM_CHECK(std::isfinite(y0), detail::describe("grid: y0 must be finite", y0));
    // Sizes that the arithmetic of a solve can carry: the element area dx·dy neither
    // overflows nor underflows, and the far corner of the grid is finite.
    FASTNORM_CHECK(std::isnormal(dx * dy),
                   detail::describe("grid: the element area dx*dy overflows or underflows (lengths in m?)", dx * dy));
    FASTNORM_CHECK(std::isfinite(x0 + static_cast<Scalar>(mx) * dx) && std::isfinite(y0 + static_cast<Scalar>(my) * dy),
                   "grid: x0 + mx*dx and y0 + my*dy must be finite");
  }

  Index mx() const { return mx_; }
  Index my() const { return my_; }
  Scalar dx() const { return dx_; }
  Scalar dy() const { return dy_; }
  Scalar x0() const { return x0_; }
  Scalar y0() const { return y0_; }

  /// Number of elements, mx·my.
  Index size() const { return mx_ * my_; }
  /// Area of one element, dx·dy (m²).
  Scalar element_area() const { return dx_ * dy_; }

  /// Element number of (i, j).
  Index index(Index i, Index j) const { return i + mx_ * j; }
  /// Rolling-direction index i of element k.
  Index i_of(Index k) const { return k % mx_; }
  /// Lateral index j of element k.
  Index j_of(Index k) const { return k / mx_; }

  /// x of the centre of column i (m).
  Scalar x(Index i) const { return x0_ + static_cast<Scalar>(i) * dx_; }
  /// y of the centre of row j (m).
  Scalar y(Index j) const { return y0_ + static_cast<Scalar>(j) * dy_; }
  /// x of the centre of element k (m).
  Scalar x_of(Index k) const { return x(i_of(k)); }
  /// y of the centre of element k (m).
  Scalar y_of(Index k) const { return y(j_of(k)); }

 private:
  Index mx_;
  Index my_;
  Scalar dx_;
  Scalar dy_;
  Scalar x0_;
  Scalar y0_;
};

}  // namespace fastnorm
