#pragma once
/// @file tangential_influence.hpp
/// Influence coefficients of the elastic half-space for constant tangential traction on
/// the rectangles of a regular grid (Cerruti's point-load solution integrated in closed
/// form), stored as two-level Toeplitz tables like the normal ones (docs/tangential.md §1).

#include <Eigen/Core>
#include <cmath>
#include <cstdlib>
#include <type_traits>

#include "fastnorm/constants.hpp"
#include "fastnorm/detail/memory_check.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/influence.hpp"
#include "fastnorm/material.hpp"

namespace fastnorm {

/// The tangential displacement differences (m) of the two bodies at a surface point due to
/// a unit traction (1 Pa) on a rectangle: `xx` is u_x for a traction along x, `yy` u_y for
/// one along y, and `xy` both u_x for one along y and u_y for one along x.
template <typename Scalar>
struct TangentialCoefficients {
  Scalar xx = 0, xy = 0, yy = 0;
};

namespace detail {

/// X·asinh(Y/|X|) (0 at X = 0): the primitive F with ∂²F/∂X∂Y = Y²/r³ (docs/tangential.md
/// Eq. (T3)); Y·asinh(X/|Y|) is the one of X²/r³, and their sum Love's I of 1/r.
template <typename Work>
Work lateral_primitive(Work X, Work Y) {
  return X != 0 ? X * std::asinh(Y / std::abs(X)) : Work(0);
}

}  // namespace detail

/// Tangential displacement differences (m) at offset (x, y) (m) from the centre of a
/// rectangle of half-sizes a × b (m) carrying a unit tangential traction (1 Pa), for two
/// bodies of combined shear modulus G and Poisson ratio ν (Material::combined_shear_modulus,
/// combined_poisson_ratio):
///
///     xx = [I − ν J_yy] / (π G),   yy = [I − ν J_xx] / (π G),   xy = ν J_xy / (π G)
///
/// with I, J_xx, J_yy, J_xy the integrals of 1/r, x²/r³, y²/r³ and xy/r³ over the
/// rectangle as seen from the point (docs/tangential.md Eqs. (T1)–(T4)). The coupling of
/// normal and tangential displacements is not included (docs/tangential.md §1).
template <typename Scalar>
TangentialCoefficients<Scalar> cerruti_coefficients(Scalar x, Scalar y, Scalar a, Scalar b, Scalar shear_modulus,
                                                    Scalar poisson_ratio) {
  using Work = detail::KernelWork<Scalar>;
  const Work xw = static_cast<Work>(x), yw = static_cast<Work>(y), aw = static_cast<Work>(a), bw = static_cast<Work>(b);
  const Work nu = static_cast<Work>(poisson_ratio), scale = pi<Work> * static_cast<Work>(shear_modulus);
  // Integrals over X = field − source ∈ [x − a, x + a], Y ∈ [y − b, y + b].
  const auto lateral = [](Work X, Work Y) { return detail::lateral_primitive(X, Y); };                // Y²/r³
  const auto longitudinal = [](Work X, Work Y) { return detail::lateral_primitive(Y, X); };           // X²/r³
  const auto product = [](Work X, Work Y) { return -std::sqrt(X * X + Y * Y); };                      // XY/r³
  const Work j_yy = detail::over_rectangle(xw, yw, aw, bw, lateral);
  const Work j_xx = detail::over_rectangle(xw, yw, aw, bw, longitudinal);
  const Work j_xy = detail::over_rectangle(xw, yw, aw, bw, product);
  const Work i = j_xx + j_yy;
  return {static_cast<Scalar>((i - nu * j_yy) / scale), static_cast<Scalar>(nu * j_xy / scale),
          static_cast<Scalar>((i - nu * j_xx) / scale)};
}

/// The tangential influence coefficients of a grid: u_x and u_y at the centre of element k
/// (m) due to unit tractions (1 Pa) along x or y on element l.
///
/// As the normal table (influence.hpp), each depends only on the offset (i_k − i_l,
/// j_k − j_l) and is stored for the (2mx − 1) × my offsets (di, |dj|): `xx` and `yy` are
/// even in both offsets, `xy` odd in both, so its sign follows dj's (docs/tangential.md
/// §2). A traction p on element l moves element k by u_k = C(k − l) p with the 2 × 2
/// matrix [[xx, xy], [xy, yy]].
///
/// **Example**
/// @code
/// fastnorm::Grid<> grid(40, 40, 2e-4, 2e-4);
/// fastnorm::TangentialInfluenceTable<> table(grid, fastnorm::Material<>::steel());
/// auto self = table.at_offset(0, 0);      // self.xx, self.xy (= 0), self.yy
/// @endcode
template <typename Scalar = double>
class TangentialInfluenceTable {
  static_assert(std::is_floating_point_v<Scalar>, "fastnorm::TangentialInfluenceTable needs a floating-point Scalar");

 public:
  using Index = Eigen::Index;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  TangentialInfluenceTable(const Grid<Scalar>& grid, const Material<Scalar>& material)
      : grid_(grid),
        shear_modulus_(material.combined_shear_modulus()),
        poisson_ratio_(material.combined_poisson_ratio()) {
    detail::check_memory(3 * (2 * static_cast<double>(grid.mx()) - 1) * static_cast<double>(grid.my()), sizeof(Scalar),
                         "TangentialInfluenceTable: grid mx x my");
    const Index rows = 2 * grid.mx() - 1;
    xx_.resize(rows, grid.my());
    xy_.resize(rows, grid.my());
    yy_.resize(rows, grid.my());
    const Scalar a = grid.dx() / 2, b = grid.dy() / 2;
    const Index centre = grid.mx() - 1;
    for (Index dj = 0; dj < grid.my(); ++dj) {
      for (Index di = 0; di < grid.mx(); ++di) {
        const auto c = cerruti_coefficients<Scalar>(static_cast<Scalar>(di) * grid.dx(),
                                                    static_cast<Scalar>(dj) * grid.dy(), a, b, shear_modulus_,
                                                    poisson_ratio_);
        xx_(centre + di, dj) = xx_(centre - di, dj) = c.xx;  // even in x
        yy_(centre + di, dj) = yy_(centre - di, dj) = c.yy;
        xy_(centre + di, dj) = c.xy;
        xy_(centre - di, dj) = -c.xy;  // odd in x
      }
    }
  }

  const Grid<Scalar>& grid() const { return grid_; }
  /// Kalker's combined shear modulus G (Pa) and Poisson ratio ν used for the tables.
  Scalar shear_modulus() const { return shear_modulus_; }
  Scalar poisson_ratio() const { return poisson_ratio_; }

  /// The coefficients for an offset of (di, dj) elements (|di| < mx, |dj| < my), either sign.
  TangentialCoefficients<Scalar> at_offset(Index di, Index dj) const {
    const Index row = grid_.mx() - 1 + di, column = std::abs(dj);
    const Scalar xy = dj < 0 ? -xy_(row, column) : xy_(row, column);  // odd in y
    return {xx_(row, column), xy, yy_(row, column)};
  }

  /// The coefficients for any offset: the table's within |di| < mx, |dj| < my, else the
  /// closed form of docs/tangential.md §2 (the steady-rolling operator reads one element
  /// past the grid).
  TangentialCoefficients<Scalar> coefficients(Index di, Index dj) const {
    if (std::abs(di) < grid_.mx() && std::abs(dj) < grid_.my()) return at_offset(di, dj);
    return cerruti_coefficients<Scalar>(static_cast<Scalar>(di) * grid_.dx(), static_cast<Scalar>(dj) * grid_.dy(),
                                        grid_.dx() / 2, grid_.dy() / 2, shear_modulus_, poisson_ratio_);
  }

  /// The stored tables: xx()(mx − 1 + di, dj) = xx(di·dx, dj·dy) for |di| < mx, 0 ≤ dj < my;
  /// likewise yy() and xy() (xy for dj < 0 is −xy()(·, −dj)).
  const Matrix& xx() const { return xx_; }
  const Matrix& xy() const { return xy_; }
  const Matrix& yy() const { return yy_; }

 private:
  Grid<Scalar> grid_;
  Scalar shear_modulus_, poisson_ratio_;
  Matrix xx_, xy_, yy_;
};

}  // namespace fastnorm
