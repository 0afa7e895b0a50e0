#pragma once
/// @file detail/segment_tables.hpp
/// The tables that make a reduced solver fast, built once per solver because they do not
/// depend on h (docs/method.md §3):
///
/// - correlations of the basis blocks of two segment lengths (Eq. (M2)), which turn a block
///   of the Galerkin matrix into one short product per entry,
///
///       (A_tᵀ C_ts A_s)_ab = Σ_d c(Δ + d, dj) K_ab(d),   K_ab(d) = Σ_{m − n = d} A_t(m, a) A_s(n, b),
///
///   Δ = i_t − i_s, dj = j_t − j_s; K depends on the two element counts and the basis only;
/// - displacements of the basis functions of a segment length (Eq. (M3)), which turn the
///   displacement a segment causes at an element into q products instead of n_s,
///
///       u(i_t, j_t) = Σ_b α_b W_b(i_t − i_s, dj),   W_b(d, dj) = Σ_m c(d − m, dj) A_s(m, b);
///
///   W depends on the count, the basis and the influence table. The q values W_b of one
///   (d, dj) are stored side by side, so that the slice a run of candidates reads is one
///   contiguous stretch of memory (the join check reads these tables scattered, mostly from
///   outside the cache: one stretch costs fewer misses than q of them).
///
/// Each table is built on first use and kept within one memory budget; past it the solver
/// falls back to the direct products, which give the same numbers more slowly.

#include <Eigen/Core>
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <memory>
#include <mutex>
#include <vector>

#include "fastnorm/error.hpp"
#include "fastnorm/influence.hpp"

namespace fastnorm {
namespace detail {

/// W of Eq. (M3) for one segment length, as SegmentTables::displacement gives it: a view of
/// the table, or none (past the memory budget).
template <typename Scalar>
class DisplacementTable {
 public:
  using Index = Eigen::Index;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  DisplacementTable() = default;
  /// `values`: q × (rows·my), column dj·rows + r holding W_0 … W_{q−1} at row r.
  DisplacementTable(const Matrix* values, Index rows) : values_(values), rows_(rows) {}

  explicit operator bool() const { return values_ != nullptr; }

  /// u(k) += Σ_b α_b W_b(d, dj) at the rows r = d + mx − n = row + k, k < u.size()
  /// (d = i_t − i_s), b in order (so the sums are those of adding the functions one after
  /// the other). Written out: the join check's runs are a few elements long, and building
  /// Eigen's block expressions of a slice of this layout for each run and function cost
  /// more than the arithmetic (measured: a warm elliptic solve 40 % slower).
  template <typename Coefficients, typename Displacement>
  void add_to(const Coefficients& alpha, Index row, Index dj, Displacement&& u) const {
    const Index q = values_->rows();
    const Scalar* w = values_->data() + (dj * rows_ + row) * q;
    for (Index k = 0; k < u.size(); ++k, w += q) {
      Scalar sum = u(k);
      for (Index b = 0; b < q; ++b) sum += alpha(b) * w[b];
      u(k) = sum;
    }
  }

 private:
  const Matrix* values_ = nullptr;
  Index rows_ = 0;
};

/// The tables of Eqs. (M2) and (M3) for segments up to `longest` elements. Safe to share
/// between threads (a solver's const solve may run on several): a table, once published,
/// never changes.
template <typename Scalar>
class SegmentTables {
 public:
  using Index = Eigen::Index;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  /// @param longest the longest segment (grid.mx())
  /// @param budget_bytes most memory all tables together may take
  SegmentTables(Index longest, std::size_t budget_bytes)
      : longest_(longest),
        budget_bytes_(budget_bytes),
        published_(static_cast<std::size_t>((longest + 1) * (longest + 2))),
        refused_(published_.size()) {
    FASTNORM_ASSERT(longest >= 1);
  }

  /// K for a target of `target_count` and a source of `source_count` elements:
  /// (n_t + n_s − 1) × (q_t·q_s), row d + n_s − 1, column a + q_t·b. Built from
  /// `block_of(count)`, the n × q basis block the solver uses for a segment of that count.
  /// nullptr when the budget has no room for it.
  template <typename BlockOf>
  const Matrix* correlation(Index target_count, Index source_count, const BlockOf& block_of) {
    FASTNORM_ASSERT(target_count >= 1 && source_count >= 1 && target_count <= longest_ &&
                    source_count <= longest_);
    const auto slot = static_cast<std::size_t>(target_count * (longest_ + 1) + source_count);
    if (const Matrix* table = published(slot)) return table;
    if (refused_[slot].load(std::memory_order_relaxed)) return nullptr;
    const Matrix target = block_of(target_count), source = block_of(source_count);
    return publish(slot, (target_count + source_count - 1) * target.cols() * source.cols(),
                   [&]() { return correlate(target, source); });
  }

  /// W for a source of `count` elements on `influence`'s grid (mx = longest), at rows
  /// r = d + mx − n for d = i_t − i_s = −(mx − n) … mx − 1 and |dj| = 0 … my − 1; none when
  /// the budget has no room for it.
  template <typename BlockOf>
  DisplacementTable<Scalar> displacement(Index count, const BlockOf& block_of, const InfluenceTable<Scalar>& influence) {
    FASTNORM_ASSERT(count >= 1 && count <= longest_ && influence.grid().mx() == longest_);
    const auto slot = static_cast<std::size_t>((longest_ + 1) * (longest_ + 1) + count);
    const Index rows = 2 * longest_ - count;
    if (const Matrix* table = published(slot)) return {table, rows};
    if (refused_[slot].load(std::memory_order_relaxed)) return {};
    const Matrix block = block_of(count);
    return {publish(slot, rows * block.cols() * influence.grid().my(), [&]() { return displace(block, influence); }),
            rows};
  }

  /// Memory the tables take now (bytes).
  std::size_t used_bytes() const { return used_bytes_.load(); }

 private:
  const Matrix* published(std::size_t slot) const { return published_[slot].load(std::memory_order_acquire); }

  /// Builds the table of `slot` (`entries` values) by `build()` and publishes it if it fits
  /// the budget; else marks the slot refused (so it is not tried again) and returns nullptr.
  template <typename Build>
  const Matrix* publish(std::size_t slot, Index entries, const Build& build) {
    const std::size_t bytes = sizeof(Scalar) * static_cast<std::size_t>(entries);
    if (used_bytes_.fetch_add(bytes) + bytes > budget_bytes_) {
      used_bytes_.fetch_sub(bytes);
      refused_[slot].store(true, std::memory_order_relaxed);
      return nullptr;
    }
    auto table = std::make_unique<Matrix>(build());
    FASTNORM_ASSERT(static_cast<Index>(table->size()) == entries);
    const std::lock_guard<std::mutex> lock(owner_mutex_);
    if (const Matrix* other = published(slot)) {  // another thread was first
      used_bytes_.fetch_sub(bytes);
      return other;
    }
    owned_.push_back(std::move(table));
    published_[slot].store(owned_.back().get(), std::memory_order_release);
    return owned_.back().get();
  }

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

  /// W_b(d, dj) = Σ_m c(d − m, dj) A(m, b): with row r = d + mx − n, c(d − m) is entry
  /// r + n − 1 − m of the influence table's run, so W_b(·, dj) is a sum of n shifted runs,
  /// stored as row b of the columns of dj (DisplacementTable).
  static Matrix displace(const Matrix& block, const InfluenceTable<Scalar>& influence) {
    const Index n = block.rows(), mx = influence.grid().mx(), my = influence.grid().my();
    const Index rows = 2 * mx - n;
    Matrix table(block.cols(), rows * my);
    Eigen::Matrix<Scalar, Eigen::Dynamic, 1> function(rows);
    for (Index b = 0; b < block.cols(); ++b) {
      for (Index dj = 0; dj < my; ++dj) {
        function.setZero();
        for (Index m = 0; m < n; ++m) function += block(m, b) * influence.run(n - 1 - m - (mx - 1), dj, rows);
        table.row(b).segment(dj * rows, rows) = function.transpose();
      }
    }
    return table;
  }

  Index longest_;
  std::size_t budget_bytes_;
  // Per slot: correlations at n_t·(longest + 1) + n_s, displacements after them at
  // (longest + 1)² + n. Null until built; refused once the budget had no room.
  std::vector<std::atomic<const Matrix*>> published_;
  std::vector<std::atomic<bool>> refused_;
  std::atomic<std::size_t> used_bytes_{0};
  std::mutex owner_mutex_;
  std::vector<std::unique_ptr<Matrix>> owned_;
};

}  // namespace detail
}  // namespace fastnorm
