#pragma once
/// @file segment_correlation.hpp
/// Correlations of the basis blocks of two segment lengths, the tables that turn a block
/// of the Galerkin matrix into one short dot product per entry (docs/method.md Eq. (M2)):
///
///     (A_tᵀ C_ts A_s)_ab = Σ_d c(Δ + d, dj) K_ab(d),   K_ab(d) = Σ_{m − n = d} A_t(m, a) A_s(n, b)
///
/// with Δ = i_t − i_s and dj = j_t − j_s. K depends on the two element counts and the basis
/// only — not on h, the grid spacing or the material — so a solver builds each table once
/// and every later block of those two counts costs q_t·q_s·(n_t + n_s − 1) operations
/// instead of the n_t·n_s·(q_s + 1) of the direct Toeplitz product.

#include <Eigen/Core>
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <memory>
#include <mutex>
#include <vector>

#include "fastnorm/error.hpp"

namespace fastnorm {
namespace detail {

/// The tables K of Eq. (M2) for every pair of segment lengths up to `longest`, built on
/// first use and kept within a memory budget. Safe to share between threads (a solver's
/// const solve may run on several): a table, once published, never changes.
template <typename Scalar>
class SegmentCorrelations {
 public:
  using Index = Eigen::Index;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  /// @param longest the longest segment (grid.mx())
  /// @param budget_bytes most memory the tables may take; pairs past it get no table
  SegmentCorrelations(Index longest, std::size_t budget_bytes)
      : longest_(longest),
        budget_bytes_(budget_bytes),
        published_(static_cast<std::size_t>((longest + 1) * (longest + 1))) {
    FASTNORM_ASSERT(longest >= 1);
  }

  /// K for a target of `target_count` and a source of `source_count` elements:
  /// (n_t + n_s − 1) × (q_t·q_s), row d + n_s − 1, column a + q_t·b. Built from
  /// `block_of(count)`, the n × q basis block the solver uses for a segment of that count.
  /// nullptr when the budget has no room for it (the caller then multiplies directly).
  template <typename BlockOf>
  const Matrix* find(Index target_count, Index source_count, const BlockOf& block_of) {
    FASTNORM_ASSERT(target_count >= 1 && source_count >= 1 && target_count <= longest_ &&
                    source_count <= longest_);
    auto& slot = published_[static_cast<std::size_t>(target_count * (longest_ + 1) + source_count)];
    if (const Matrix* table = slot.load(std::memory_order_acquire)) return table;

    const Matrix target_block = block_of(target_count), source_block = block_of(source_count);
    const std::size_t bytes = sizeof(Scalar) * static_cast<std::size_t>(target_count + source_count - 1) *
                              static_cast<std::size_t>(target_block.cols() * source_block.cols());
    if (used_bytes_.fetch_add(bytes) + bytes > budget_bytes_) {
      used_bytes_.fetch_sub(bytes);
      return nullptr;
    }
    auto table = std::make_unique<Matrix>(correlate(target_block, source_block));
    const std::lock_guard<std::mutex> lock(owner_mutex_);
    if (const Matrix* other = slot.load(std::memory_order_acquire)) {  // another thread was first
      used_bytes_.fetch_sub(bytes);
      return other;
    }
    owned_.push_back(std::move(table));
    slot.store(owned_.back().get(), std::memory_order_release);
    return owned_.back().get();
  }

  /// Memory the tables take now (bytes).
  std::size_t used_bytes() const { return used_bytes_.load(); }

 private:
  /// K_ab(d) for d = −(n_s − 1) … n_t − 1: each entry a dot product of the overlapping
  /// parts of column a of the target block and column b of the source block.
  static Matrix correlate(const Matrix& target, const Matrix& source) {
    const Index n_t = target.rows(), n_s = source.rows(), q_t = target.cols();
    Matrix table(n_t + n_s - 1, q_t * source.cols());
    for (Index d = -(n_s - 1); d < n_t; ++d) {
      const Index first = std::max<Index>(0, d), length = std::min(n_t, n_s + d) - first;  // m range
      for (Index b = 0; b < source.cols(); ++b) {
        for (Index a = 0; a < q_t; ++a) {
          table(d + n_s - 1, a + q_t * b) =
              target.col(a).segment(first, length).dot(source.col(b).segment(first - d, length));
        }
      }
    }
    return table;
  }

  Index longest_;
  std::size_t budget_bytes_;
  std::vector<std::atomic<const Matrix*>> published_;  // per (n_t, n_s); null until built
  std::atomic<std::size_t> used_bytes_{0};
  std::mutex owner_mutex_;
  std::vector<std::unique_ptr<Matrix>> owned_;
};

}  // namespace detail
}  // namespace fastnorm
