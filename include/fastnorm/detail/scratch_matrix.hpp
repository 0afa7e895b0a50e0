#pragma once
/// @file detail/scratch_matrix.hpp
/// Workspace matrices that keep their storage: an Eigen matrix gives its memory back
/// whenever its size changes, and the systems of the active-set loop change size every
/// iteration; this storage only grows, so a loop that reuses it stops allocating once it
/// has met its largest system (docs/performance.md §3).

#include <Eigen/Core>
#include <algorithm>
#include <utility>
#include <vector>

namespace fastnorm {
namespace detail {

template <typename Scalar>
class ScratchMatrix {
 public:
  using Index = Eigen::Index;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  ScratchMatrix() = default;
  ScratchMatrix(const ScratchMatrix& other) { *this = other; }
  /// Copies the view of the last resize (what a reader sees) into this storage, grown only
  /// if it is smaller; the values beyond the view are not copied.
  ScratchMatrix& operator=(const ScratchMatrix& other) {
    if (this != &other) {
      resize(other.rows_, other.cols_);
      std::copy_n(other.values_.data(), static_cast<std::size_t>(rows_ * cols_), values_.data());
    }
    return *this;
  }
  /// A moved-from matrix is empty (a 0 × 0 view), so that copying it copies nothing: the
  /// defaults would leave its view's size over storage it no longer holds.
  ScratchMatrix(ScratchMatrix&& other) noexcept
      : rows_(std::exchange(other.rows_, 0)), cols_(std::exchange(other.cols_, 0)), values_(std::move(other.values_)) {}
  ScratchMatrix& operator=(ScratchMatrix&& other) noexcept {
    if (this != &other) {
      rows_ = std::exchange(other.rows_, 0);
      cols_ = std::exchange(other.cols_, 0);
      values_ = std::move(other.values_);
      other.values_.clear();
    }
    return *this;
  }
  ~ScratchMatrix() = default;

  /// A copy of `other`'s lower triangle (its diagonal and below) into this storage, with
  /// its view's size; the values above the diagonal are left undefined. What a symmetric
  /// system or a Cholesky factor that is read by its lower triangle only needs copied: half
  /// the values of a square view.
  void assign_lower(const ScratchMatrix& other) {
    if (this == &other) return;
    resize(other.rows_, other.cols_);
    for (Index column = 0; column < cols_; ++column) {
      const Index first = std::min(column, rows_), at = column * rows_ + first;
      std::copy_n(other.values_.data() + at, static_cast<std::size_t>(rows_ - first), values_.data() + at);
    }
  }
  /// A rows × cols view of the storage, grown if needed; contents undefined.
  Eigen::Map<Matrix> resize(Index rows, Index cols) {
    rows_ = rows;
    cols_ = cols;
    if (values_.size() < static_cast<std::size_t>(rows * cols)) values_.resize(static_cast<std::size_t>(rows * cols));
    return view();
  }
  /// The view of the last resize.
  Eigen::Map<Matrix> view() { return Eigen::Map<Matrix>(values_.data(), rows_, cols_); }
  Eigen::Map<const Matrix> view() const { return Eigen::Map<const Matrix>(values_.data(), rows_, cols_); }
  /// Storage for `values` values at least (it never shrinks).
  void reserve(std::size_t values) {
    if (values_.size() < values) values_.resize(values);
  }
  /// Values the storage holds without growing.
  std::size_t capacity() const { return values_.size(); }
  Index rows() const { return rows_; }

 private:
  Index rows_ = 0, cols_ = 0;
  std::vector<Scalar> values_;
};

}  // namespace detail
}  // namespace fastnorm
