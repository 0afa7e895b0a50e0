#pragma once
/// @file influence.hpp
/// Influence coefficients of the elastic half-space for constant pressure on the
/// rectangles of a regular grid (Love 1929), stored as a two-level Toeplitz table
/// (docs/design.md §2, docs/kernel.md).

#include <Eigen/Core>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <type_traits>
#include <vector>

#include "fastnorm/constants.hpp"
#include "fastnorm/detail/memory_check.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/material.hpp"

namespace fastnorm {

namespace detail {

/// The precision the kernel is evaluated in: at least double. The four-term
/// difference of docs/kernel.md Eq. (K1) cancels about log10(r/dx)+2 digits far away,
/// which float cannot spare; the table is rounded to Scalar after.
template <typename Scalar>
using KernelWork = std::conditional_t<(sizeof(Scalar) < sizeof(double)), double, Scalar>;

/// I(X, Y) = ∫₀^X ∫₀^Y dx dy / sqrt(x² + y²) = X·asinh(Y/|X|) + Y·asinh(X/|Y|),
/// odd in each argument; a term is 0 when its |·| is 0 (docs/kernel.md Eq. (K2)).
template <typename Work>
Work love_primitive(Work X, Work Y) {
  Work value = 0;
  if (X != 0) value += X * std::asinh(Y / std::abs(X));
  if (Y != 0) value += Y * std::asinh(X / std::abs(Y));
  return value;
}

/// The double difference F(x+a, y+b) − F(x−a, y+b) − F(x+a, y−b) + F(x−a, y−b): the integral
/// of ∂²F/∂X∂Y over the rectangle [x−a, x+a] × [y−b, y+b] (docs/kernel.md Eq. (K1)).
template <typename Work, typename Primitive>
Work over_rectangle(Work x, Work y, Work a, Work b, const Primitive& primitive) {
  return primitive(x + a, y + b) - primitive(x - a, y + b) - primitive(x + a, y - b) + primitive(x - a, y - b);
}

}  // namespace detail

/// Normal surface displacement (m) of both bodies together at offset (x, y) (m) from
/// the centre of a rectangle of half-sizes a × b (m) carrying unit pressure (1 Pa):
///
///     C(x, y) = [I(x+a, y+b) − I(x−a, y+b) − I(x+a, y−b) + I(x−a, y−b)] / (π E*)
///
/// @param combined_modulus E* (Pa), see Material::combined_modulus()
/// @note See docs/design.md §2 and docs/kernel.md Eq. (K1).
template <typename Scalar>
Scalar love_coefficient(Scalar x, Scalar y, Scalar a, Scalar b, Scalar combined_modulus) {
  using Work = detail::KernelWork<Scalar>;
  const Work xw = static_cast<Work>(x), yw = static_cast<Work>(y), aw = static_cast<Work>(a), bw = static_cast<Work>(b);
  const Work sum = detail::over_rectangle(xw, yw, aw, bw, [](Work X, Work Y) { return detail::love_primitive(X, Y); });
  return static_cast<Scalar>(sum / (pi<Work> * Work(combined_modulus)));
}

/// The influence coefficients C_kl of a grid: displacement at the centre of element k
/// (m) due to unit pressure (1 Pa) on element l.
///
/// C_kl depends only on the offset (i_k − i_l, j_k − j_l): a two-level Toeplitz matrix with
/// (2mx−1)(2my−1) offsets. The kernel is even in y, so the table stored here keeps the
/// (2mx−1) × my offsets (di, |dj|): each of its columns, the coupling of two strips |dj|
/// apart, is read forwards by every Toeplitz product (docs/kernel.md §2). The N × N
/// matrix is never formed; `dense_block` fills the sub-block a direct solver needs.
///
/// **Example**
/// @code
/// fastnorm::Grid<> grid(40, 40, 2e-4, 2e-4);
/// fastnorm::InfluenceTable<> table(grid, fastnorm::Material<>(2.1e11, 0.3));
/// double self = table(0, 0);        // C_00
/// double neighbour = table(0, 1);   // C_01 = C(dx, 0)
/// @endcode
template <typename Scalar = double>
class InfluenceTable {
  static_assert(std::is_floating_point_v<Scalar>,
                "fastnorm::InfluenceTable needs a floating-point Scalar");

 public:
  using Index = Eigen::Index;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  InfluenceTable(const Grid<Scalar>& grid, const Material<Scalar>& material)
      : grid_(grid), combined_modulus_(material.combined_modulus()) {
    auto coefficients = std::make_shared<Matrix>(checked_rows(grid), grid.my());
    const Scalar a = grid.dx() / 2, b = grid.dy() / 2;
    const Index centre = grid.mx() - 1;
    for (Index dj = 0; dj < grid.my(); ++dj) {
      for (Index di = 0; di < grid.mx(); ++di) {
        (*coefficients)(centre + di, dj) = love_coefficient<Scalar>(static_cast<Scalar>(di) * grid.dx(),
                                                                    static_cast<Scalar>(dj) * grid.dy(), a, b,
                                                                    combined_modulus_);
        (*coefficients)(centre - di, dj) = (*coefficients)(centre + di, dj);  // even in x
      }
    }
    stride_ = coefficients->rows();
    origin_ = coefficients->data() + centre;
    coefficients_ = std::move(coefficients);
  }

  /// The table of `grid`, read from `larger`'s coefficients, which it shares: nothing is
  /// computed or copied. A coefficient depends only on its offset, the element sizes and
  /// E*, so this equals InfluenceTable(grid, material) to the last bit. What a model that
  /// meets many grid sizes uses (ReducedSolver::for_grid), so that a new size builds no
  /// table.
  /// @throws fastnorm::invalid_argument if `larger` does not cover `grid` (covers)
  InfluenceTable(const InfluenceTable& larger, const Grid<Scalar>& grid) : InfluenceTable(larger) {
    FASTNORM_CHECK(larger.covers(grid), "InfluenceTable: the larger table must cover grid (the same element sizes, "
                                        "no more elements either way)");
    grid_ = grid;  // a copy shares the coefficients: only the grid it is read for changes
  }

  /// Whether this table holds every coefficient of `grid`: the same element sizes, and no
  /// more elements either way (the origin does not matter).
  bool covers(const Grid<Scalar>& grid) const {
    return grid.mx() <= grid_.mx() && grid.my() <= grid_.my() && grid.dx() == grid_.dx() && grid.dy() == grid_.dy();
  }

  const Grid<Scalar>& grid() const { return grid_; }
  /// E* used for the table (Pa).
  Scalar combined_modulus() const { return combined_modulus_; }

  /// C for an offset of (di, dj) elements; either sign.
  Scalar at_offset(Index di, Index dj) const { return column(dj)[di]; }

  /// C_kl: displacement at element k due to unit pressure on element l (m/Pa).
  Scalar operator()(Index k, Index l) const {
    return at_offset(grid_.i_of(k) - grid_.i_of(l), grid_.j_of(k) - grid_.j_of(l));
  }

  /// The table: table()(mx − 1 + di, dj) = C(di·dx, dj·dy), |di| < mx, 0 ≤ dj < my (a view
  /// of the stored coefficients, which may be a larger table's).
  Eigen::Map<const Matrix, 0, Eigen::OuterStride<>> table() const {
    return {column(0) - (grid_.mx() - 1), 2 * grid_.mx() - 1, grid_.my(), Eigen::OuterStride<>(stride_)};
  }

  /// C(di, dj) for di = first_di … first_di + length − 1 (|di| < mx): a forward slice of
  /// one table column, no copy.
  auto run(Index first_di, Index dj, Index length) const {
    return Eigen::Map<const Vector>(column(dj) + first_di, length);
  }

  /// Dense symmetric block C_II for the elements `set` (each < grid.size()).
  Matrix dense_block(const std::vector<Index>& set) const { return dense_block(set, set); }

  /// Dense block C_RS: rows the elements `rows`, columns the elements `columns`.
  Matrix dense_block(const std::vector<Index>& rows, const std::vector<Index>& columns) const {
    Matrix block(static_cast<Index>(rows.size()), static_cast<Index>(columns.size()));
    dense_block(rows, columns, block);
    return block;
  }

  /// As dense_block, into `block` (rows.size() × columns.size()) without allocating.
  void dense_block(const std::vector<Index>& rows, const std::vector<Index>& columns,
                   Eigen::Ref<Matrix> block) const {
    FASTNORM_CHECK(block.rows() == static_cast<Index>(rows.size()) && block.cols() == static_cast<Index>(columns.size()),
                   "dense_block: block must be rows.size() x columns.size()");
    for (Index c = 0; c < block.cols(); ++c) {
      const Index ic = grid_.i_of(columns[static_cast<std::size_t>(c)]);
      const Index jc = grid_.j_of(columns[static_cast<std::size_t>(c)]);
      for (Index r = 0; r < block.rows(); ++r) {
        const Index k = rows[static_cast<std::size_t>(r)];
        block(r, c) = at_offset(grid_.i_of(k) - ic, grid_.j_of(k) - jc);
      }
    }
  }

  /// Displacements u_t = Σ_s C_ts p_s (m) at the elements `targets` due to pressures
  /// `source_pressure` (Pa) on the elements `sources`. Cost: targets × sources; fastest
  /// when the sources come in runs of consecutive elements of a strip (a sorted set).
  Vector displacement(const std::vector<Index>& targets, const std::vector<Index>& sources,
                      const Eigen::Ref<const Vector>& source_pressure) const {
    Vector result(static_cast<Index>(targets.size()));
    displacement(targets, sources, source_pressure, result);
    return result;
  }

  /// As displacement, into `result` (targets.size() values) without allocating.
  void displacement(const std::vector<Index>& targets, const std::vector<Index>& sources,
                    const Eigen::Ref<const Vector>& source_pressure, Eigen::Ref<Vector> result) const {
    FASTNORM_CHECK(source_pressure.size() == static_cast<Index>(sources.size()),
                   "displacement: source_pressure must have one value per source element");
    FASTNORM_CHECK(result.size() == static_cast<Index>(targets.size()),
                   "displacement: result must have one value per target element");
    const Index mx = grid_.mx();
    result.setZero();
    for (std::size_t start = 0; start < sources.size();) {
      // A run: sources start..start+length−1 are consecutive elements of strip j.
      std::size_t length = 1;
      const Index i0 = grid_.i_of(sources[start]), j = grid_.j_of(sources[start]);
      while (start + length < sources.size() && sources[start + length] == sources[start] + static_cast<Index>(length) &&
             i0 + static_cast<Index>(length) < mx) {
        ++length;
      }
      const auto run_pressure = source_pressure.segment(static_cast<Index>(start), static_cast<Index>(length));
      // The target's strip is found by a division only when it changes (targets usually sorted).
      Index strip_first = 0, target_j = 0;
      for (Index t = 0; t < result.size(); ++t) {
        const Index k = targets[static_cast<std::size_t>(t)];
        if (k < strip_first || k >= strip_first + mx) {
          target_j = k / mx;
          strip_first = target_j * mx;
        }
        // Σ_n C(i_t − i0 − n, dj) p_n = Σ_n C(i0 + n − i_t, dj) p_n (even in x): forwards.
        result(t) += run(i0 - (k - strip_first), target_j - j, static_cast<Index>(length)).dot(run_pressure);
      }
      start += length;
    }
  }

  /// The Toeplitz block C(row_offset + m − n, dj) for m < block.rows(), n < block.cols():
  /// the coupling of two runs of strips dj apart whose first elements are row_offset
  /// apart in x. Each of its columns is a run of one table column.
  void fill_toeplitz(Index row_offset, Index dj, Eigen::Ref<Matrix> block) const {
    for (Index n = 0; n < block.cols(); ++n) block.col(n) = run(row_offset - n, dj, block.rows());
  }

  /// displacement += pressure · C(·, source): adds the displacement (m) of every element due
  /// to `pressure` (Pa) on the element `source`. Cost: grid.size().
  void add_displacement(Index source, Scalar pressure, Eigen::Ref<Vector> displacement) const {
    const Index mx = grid_.mx(), i = grid_.i_of(source), j = grid_.j_of(source);
    for (Index row = 0; row < grid_.my(); ++row) {
      // C(i_t − i, row − j) for i_t = 0…mx−1: a forward slice of one table column (even in x).
      displacement.segment(row * mx, mx) +=
          pressure * run(-i, row - j, mx);
    }
  }

  /// Displacements at every element due to a pressure on the whole grid: C p (m).
  /// Cost: grid.size() × (non-zero pressures).
  Vector displacement(const Eigen::Ref<const Vector>& pressure) const {
    FASTNORM_CHECK(pressure.size() == grid_.size(),
                   detail::describe("displacement: pressure must have grid.size() values",
                                    pressure.size()));
    std::vector<Index> loaded, all(static_cast<std::size_t>(grid_.size()));
    for (Index k = 0; k < grid_.size(); ++k) {
      all[static_cast<std::size_t>(k)] = k;
      if (pressure(k) != 0) loaded.push_back(k);
    }
    Vector loaded_pressure(static_cast<Index>(loaded.size()));
    for (std::size_t s = 0; s < loaded.size(); ++s) {
      loaded_pressure(static_cast<Index>(s)) = pressure(loaded[s]);
    }
    return displacement(all, loaded, loaded_pressure);
  }

 private:
  /// The table's 2·mx − 1 rows, once its (2·mx − 1)·my values are known to fit in memory.
  static Index checked_rows(const Grid<Scalar>& grid) {
    detail::check_memory((2 * static_cast<double>(grid.mx()) - 1) * static_cast<double>(grid.my()), sizeof(Scalar),
                         "InfluenceTable: grid mx x my");
    return 2 * grid.mx() - 1;
  }

  /// C(di, dj) at [di], |di| < mx: column |dj| of the coefficients from di = 0.
  const Scalar* column(Index dj) const { return origin_ + std::abs(dj) * stride_; }

  Grid<Scalar> grid_;
  Scalar combined_modulus_;
  // Rows: offsets di; columns: |dj|. Possibly a larger grid's (shared, never changed).
  std::shared_ptr<const Matrix> coefficients_;
  // Derived from coefficients_, kept so that a read in the solvers' loops is one load.
  const Scalar* origin_ = nullptr;  // C(0, 0)
  Index stride_ = 0;                // between columns
};

}  // namespace fastnorm
