#pragma once
/// @file detail/in_place_cholesky.hpp
/// A symmetric positive definite system factorised by Eigen's LLT in place, in storage
/// that keeps its capacity (scratch_matrix.hpp): the active-set loop's systems change
/// size every iteration and this one stops allocating once it has met the largest.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "fastnorm/detail/scratch_matrix.hpp"

namespace fastnorm {
namespace detail {

/// Rows (and columns) of a tile of a product or solve whose inner size is `depth`, so that
/// Eigen's packed copies of its operands (up to depth × tile values each) stay below its
/// stack limit (EIGEN_STACK_ALLOCATION_LIMIT, 128 KB): past it they come from the heap, and
/// the time loop allocates (docs/performance.md §8). depth · tile ≤ 64 KB up to a depth of
/// 1 024 (measured: no allocation in the factor update up to 2 000).
template <typename Scalar>
Eigen::Index stack_tile(Eigen::Index depth) {
  return std::clamp<Eigen::Index>(static_cast<Eigen::Index>(65536 / sizeof(Scalar)) / std::max<Eigen::Index>(depth, 1),
                                  8, 64);
}

/// Usage: `resize(n)`, fill the lower triangle of `matrix()`, `factorise()` (which
/// overwrites it with the factor L), then `solve_in_place(rhs)` as often as needed.
template <typename Scalar>
class InPlaceCholesky {
 public:
  using Index = Eigen::Index;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  /// Size n × n; contents undefined until filled.
  void resize(Index n) {
    factored_ = false;
    storage_.resize(n, n);
  }

  /// Storage for `values` values (an n × n factor needs n·n) without growing; it never
  /// shrinks.
  void reserve(std::size_t values) { storage_.reserve(values); }
  /// Values the storage holds without growing.
  std::size_t capacity() const { return storage_.capacity(); }

  /// The matrix to factorise (lower triangle), and after factorise() its factor L.
  Eigen::Map<Matrix> matrix() { return storage_.view(); }

  /// Factorises the lower triangle of matrix() in place; false if it is not positive definite.
  bool factorise() { return factorise_from(0); }

  /// As factorise(), when the leading `kept` × `kept` block of matrix() already holds the
  /// factor L11 of the matrix's leading block (copied from the factorisation of a system
  /// with the same leading unknowns) and the rows below it hold the matrix: the last steps
  /// of a blocked Cholesky, L21 = A21 L11⁻ᵀ and L22 L22ᵀ = A22 − L21 L21ᵀ (docs/method.md §3).
  /// Costs about (n − kept)·kept² + (n − kept)³/3 flops instead of n³/3.
  bool factorise_from(Index kept) {
    Eigen::Map<Matrix> values = storage_.view();
    const Index rest = values.rows() - kept;
    if (kept > 0 && rest > 0) update_trailing(values, kept);
    Eigen::Ref<Matrix> trailing = values.bottomRightCorner(rest, rest);
    if (rest <= unblocked_limit) {
      // Eigen's own unblocked kernel (what Eigen::LLT runs below 32 unknowns): from 32 to
      // about 160 unknowns Eigen::LLT takes its blocked path, whose products cost more to
      // set up than they save at these sizes (measured: 1.2–1.8× the time of the unblocked
      // kernel), and it also computes a norm of the matrix that nothing here reads.
      factored_ = Eigen::internal::llt_inplace<Scalar, Eigen::Lower>::unblocked(trailing) == -1;
    } else {
      const Eigen::LLT<Eigen::Ref<Matrix>, Eigen::Lower> llt(trailing);  // in place: values now hold L
      factored_ = llt.info() == Eigen::Success;
    }
    return factored_;
  }
  /// The factor L of the leading `size` × `size` block of matrix() replaced, from row
  /// `first` on, by the factor of L Lᵀ + V Vᵀ, where the columns of V (rows [first, size),
  /// overwritten) are zero above `first`: rows and columns before `first` do not change.
  /// Written by hand because Eigen's LLT::rankUpdate takes a whole factor, one vector at a
  /// time, and allocates a temporary vector at every call (Eigen/src/Cholesky/LLT.h), which
  /// the time loop must not. The rank-one update of Golub and Van Loan (§6.5.4), for each
  /// column v of V in turn: r = √(L_ii² + v_i²), c = r/L_ii, s = v_i/L_ii, L_ji ← (L_ji +
  /// s v_j)/c, v_j ← c v_j − s L_ji for j > i. Column i of the k-th update needs only
  /// column i after the first k − 1 updates, so all of them are applied to a column before
  /// the next: one pass over the factor instead of one per column of V.
  template <typename Vectors>
  void update_rank(Index first, Index size, Vectors&& vectors) {
    Eigen::Map<Matrix> values = storage_.view();
    for (Index i = first; i < size; ++i) {
      const Index below = size - i - 1;
      auto column = values.col(i).segment(i + 1, below);
      for (Index k = 0; k < vectors.cols(); ++k) {
        const Scalar diagonal = values(i, i), vi = vectors(i - first, k);
        if (vi == Scalar(0)) continue;  // this update leaves the column as it is
        const Scalar root = std::sqrt(diagonal * diagonal + vi * vi);
        const Scalar c = root / diagonal, s = vi / diagonal, inverse_c = diagonal / root;
        values(i, i) = root;
        auto rest = vectors.col(k).segment(i + 1 - first, below);
        column = inverse_c * (column + s * rest);
        rest = c * rest - s * column;
      }
    }
  }
  bool factored() const { return factored_; }
  /// A copy of `other`: its lower triangle, the matrix or the factor (the upper one is never
  /// read), and whether it is factorised.
  void assign_lower(const InPlaceCholesky& other) {
    storage_.assign_lower(other.storage_);
    factored_ = other.factored_;
  }
  /// The factor L (lower triangle) after a successful factorise.
  Eigen::Map<const Matrix> factor() const { return storage_.view(); }

  /// rhs ← A⁻¹ rhs by the two triangular solves with L (after a successful factorise).
  /// Column by column: Eigen's solve of a block of columns packs the factor into a
  /// temporary that comes from the heap once it passes 128 KB; a single column does not.
  template <typename Rhs>
  void solve_in_place(Rhs&& rhs) const {
    const auto factor = storage_.view().template triangularView<Eigen::Lower>();
    for (Index c = 0; c < rhs.cols(); ++c) {
      auto column = rhs.col(c);
      factor.solveInPlace(column);
      factor.adjoint().solveInPlace(column);
    }
  }

 private:
  /// L21 = A21 L11⁻ᵀ and the lower triangle of A22 − L21 L21ᵀ in place, in tiles of at most
  /// stack_tile(kept) rows and columns: untiled, Eigen packed the polynomial bases' ≈ 100
  /// kept unknowns on the heap. A system whose tiles are the whole blocks makes Eigen's two
  /// calls, as untiled.
  static void update_trailing(Eigen::Map<Matrix>& values, Index kept) {
    const Index rest = values.rows() - kept;
    const Index tile = stack_tile<Scalar>(kept);
    const auto factor = values.topLeftCorner(kept, kept);
    auto coupling = values.bottomLeftCorner(rest, kept);
    // X L11ᵀ = A21 column block by column block: X_c = (A21_c − X_{<c} L_{c,<c}ᵀ) L_cc⁻ᵀ.
    for (Index c = 0; c < kept; c += tile) {
      const Index width = std::min(tile, kept - c);
      const auto diagonal = factor.block(c, c, width, width).template triangularView<Eigen::Lower>().transpose();
      for (Index r = 0; r < rest; r += tile) {
        auto block = coupling.block(r, c, std::min(tile, rest - r), width);
        if (c > 0) block.noalias() -= coupling.block(r, 0, block.rows(), c) * factor.block(c, 0, width, c).transpose();
        diagonal.template solveInPlace<Eigen::OnTheRight>(block);
      }
    }
    auto trailing = values.bottomRightCorner(rest, rest);
    for (Index r = 0; r < rest; r += tile) {
      const Index rows = std::min(tile, rest - r);
      const auto row_factor = coupling.middleRows(r, rows);
      trailing.block(r, r, rows, rows).template selfadjointView<Eigen::Lower>().rankUpdate(row_factor, Scalar(-1));
      for (Index c = 0; c < r; c += tile) {
        const Index width = std::min(tile, r - c);
        trailing.block(r, c, rows, width).noalias() -= row_factor * coupling.middleRows(c, width).transpose();
      }
    }
  }

  /// Up to this many unknowns the trailing block is factorised unblocked (factorise_from);
  /// measured against Eigen::LLT, which is faster past about 190.
  static constexpr Index unblocked_limit = 160;

  bool factored_ = false;
  ScratchMatrix<Scalar> storage_;
};

}  // namespace detail
}  // namespace fastnorm
