#pragma once
/// @file detail/in_place_cholesky.hpp
/// A symmetric positive definite system factorised by Eigen's LLT in place, in storage
/// that keeps its capacity (scratch_matrix.hpp): the active-set loop's systems change
/// size every iteration and this one stops allocating once it has met the largest.

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "fastnorm/detail/scratch_matrix.hpp"

namespace fastnorm {
namespace detail {

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
    if (kept > 0 && rest > 0) {
      auto coupling = values.bottomLeftCorner(rest, kept);
      values.topLeftCorner(kept, kept).template triangularView<Eigen::Lower>().transpose().template solveInPlace<
          Eigen::OnTheRight>(coupling);
      values.bottomRightCorner(rest, rest).template selfadjointView<Eigen::Lower>().rankUpdate(coupling, Scalar(-1));
    }
    Eigen::Ref<Matrix> trailing = values.bottomRightCorner(rest, rest);
    const Eigen::LLT<Eigen::Ref<Matrix>, Eigen::Lower> llt(trailing);  // in place: values now hold L
    factored_ = llt.info() == Eigen::Success;
    return factored_;
  }
  bool factored() const { return factored_; }
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
  bool factored_ = false;
  ScratchMatrix<Scalar> storage_;
};

}  // namespace detail
}  // namespace fastnorm
