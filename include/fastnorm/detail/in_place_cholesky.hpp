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

  /// The matrix to factorise (lower triangle), and after factorise() its factor L.
  Eigen::Map<Matrix> matrix() { return storage_.view(); }

  /// Factorises the lower triangle of matrix() in place; false if it is not positive definite.
  bool factorise() {
    Eigen::Map<Matrix> values = storage_.view();
    const Eigen::LLT<Eigen::Ref<Matrix>, Eigen::Lower> llt(values);  // in place: values now hold L
    factored_ = llt.info() == Eigen::Success;
    return factored_;
  }
  bool factored() const { return factored_; }

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
