#pragma once
/// @file detail/segment_tables.hpp
/// The tables that make a reduced solver fast, built once per solver because they do not
/// depend on h (docs/method.md §3):
///
/// - displacements of the basis functions of a segment length (Eq. (M3)), which turn the
///   displacement a segment causes at an element into q products instead of n_s,
///
///       u(i_t, j_t) = Σ_b α_b W_b(i_t − i_s, dj),   W_b(d, dj) = Σ_m c(d − m, dj) A_s(m, b),
///
///   and a block of the Galerkin matrix into min(n_t, n_s)·q_t·q_s products, read from the
///   W of its longer segment: (A_tᵀ C_ts A_s)_ab = Σ_m A_t(m, a) W_b(Δ + m, dj) for the
///   longer s, Δ = i_t − i_s, dj = j_t − j_s. W depends on the count, the basis and the
///   influence table. The q values W_b of one (d, dj) are stored side by side, so that the
///   slice a run of candidates reads is one contiguous stretch of memory (the join check
///   reads these tables scattered, mostly from outside the cache: one stretch costs fewer
///   misses than q of them);
/// - correlations of the basis blocks of two segment lengths (Eq. (M2)), for the blocks
///   of a length whose W the budget refused,
///
///       (A_tᵀ C_ts A_s)_ab = Σ_d c(Δ + d, dj) K_ab(d),   K_ab(d) = Σ_{m − n = d} A_t(m, a) A_s(n, b);
///
///   K depends on the two element counts and the basis only.
///
/// Each table is built on first use and kept within one memory budget; past it the solver
/// falls back to the direct products, which give the same numbers more slowly.
///
/// K does not depend on the grid, and W only through the offsets it covers: on a grid of
/// the same element sizes and E* with no more elements either way, W is a part of the
/// larger grid's table (its entries are sums of the same influence coefficients). So one
/// set of tables, made for the largest grid, serves the solvers of every smaller one
/// (ReducedSolver::for_grid): a model that meets many grid sizes builds each table once.

#include <Eigen/Core>
#include <Eigen/QR>
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "fastnorm/error.hpp"
#include "fastnorm/grid.hpp"
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
  /// `values`: q × (rows·my), column dj·rows + r holding W_0 … W_{q−1} at row r of the
  /// tables' grid, which is row r − `row_offset` of the solver's (mx smaller by the offset).
  DisplacementTable(const Matrix* values, Index rows, Index row_offset)
      : values_(values), rows_(rows), row_offset_(row_offset) {}

  explicit operator bool() const { return values_ != nullptr; }

  /// q, the number of functions.
  Index functions() const { return values_->rows(); }

  /// W_0 … W_{q−1} at the row r = d + mx − n = `row` (as add_to reads it) and |dj|; the q
  /// values of row r + 1 follow them.
  const Scalar* at(Index row, Index dj) const {
    return values_->data() + (dj * rows_ + row + row_offset_) * values_->rows();
  }

  /// u(k) += Σ_b α_b W_b(d, dj) at the rows r = d + mx − n = row + k, k < u.size()
  /// (d = i_t − i_s, mx the solver's grid's), b in order (so the sums are those of adding
  /// the functions one after the other). Written out: the join check's runs are a few
  /// elements long, and building Eigen's block expressions of a slice of this layout for
  /// each run and function cost more than the arithmetic (measured: a warm elliptic solve
  /// 40 % slower).
  template <typename Coefficients, typename Displacement>
  void add_to(const Coefficients& alpha, Index row, Index dj, Displacement&& u) const {
    const Index q = functions();
    const Scalar* w = at(row, dj);
    for (Index k = 0; k < u.size(); ++k, w += q) {
      Scalar sum = u(k);
      for (Index b = 0; b < q; ++b) sum += alpha(b) * w[b];
      u(k) = sum;
    }
  }

 private:
  const Matrix* values_ = nullptr;
  Index rows_ = 0, row_offset_ = 0;
};

/// The tables of Eqs. (M2) and (M3) for the grids that `extent`'s grid covers (covers()).
/// Safe to share between threads and solvers (a solver's const solve may run on several):
/// a table, once published, never changes.
template <typename Scalar>
class SegmentTables {
 public:
  using Index = Eigen::Index;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  /// @param extent the influence table of the largest grid served; segments up to its mx
  /// @param budget_bytes most memory all tables together may take
  SegmentTables(std::shared_ptr<const InfluenceTable<Scalar>> extent, std::size_t budget_bytes)
      : extent_(std::move(extent)),
        longest_(extent_->grid().mx()),
        budget_bytes_(budget_bytes),
        published_(static_cast<std::size_t>((longest_ + 1) * (longest_ + 4))),
        refused_(published_.size()) {}

  /// Whether these tables serve a solver of `influence`: the same element sizes and E*, and
  /// no more elements either way than the extent's grid.
  bool covers(const InfluenceTable<Scalar>& influence) const {
    return covers(influence.grid(), influence.combined_modulus());
  }
  /// The same for a solver on `grid` with E* `combined_modulus` (Pa).
  bool covers(const Grid<Scalar>& grid, Scalar combined_modulus) const {
    return extent_->covers(grid) && combined_modulus == extent_->combined_modulus();
  }
  /// The influence table of the largest grid served, whose coefficients the solvers of the
  /// grids it covers read (InfluenceTable's sharing constructor).
  const InfluenceTable<Scalar>& extent() const { return *extent_; }

  /// The block a solver uses for a segment of `count` elements, `block_of(count)` (n × q),
  /// built once; every table is built from these. Blocks and their pseudo-inverses are
  /// outside the budget: n·q values each, and every solve needs them.
  template <typename BlockOf>
  const Matrix& block(Index count, const BlockOf& block_of) {
    FASTNORM_ASSERT(count >= 1 && count <= longest_);
    const auto slot = static_cast<std::size_t>((longest_ + 1) * (longest_ + 2) + count);
    if (const Matrix* built = published(slot)) return *built;
    auto made = std::make_unique<Matrix>(block_of(count));
    return *adopt(slot, made);
  }

  /// The pseudo-inverse A⁺ (q × n) of block(count): α = A⁺ p for p = A α; built once.
  template <typename BlockOf>
  const Matrix& projection(Index count, const BlockOf& block_of) {
    FASTNORM_ASSERT(count >= 1 && count <= longest_);
    const auto slot = static_cast<std::size_t>((longest_ + 1) * (longest_ + 3) + count);
    if (const Matrix* built = published(slot)) return *built;
    auto inverse = std::make_unique<Matrix>(
        Eigen::CompleteOrthogonalDecomposition<Matrix>(block(count, block_of)).pseudoInverse());
    return *adopt(slot, inverse);
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
    const Matrix &target = block(target_count, block_of), &source = block(source_count, block_of);
    return publish(slot, (target_count + source_count - 1) * target.cols() * source.cols(),
                   [&]() { return correlate(target, source); });
  }

  /// W for a source of `count` elements, as a solver on a covered grid of `mx` elements
  /// along x reads it (rows d + mx − n); stored on the extent's grid (mx = longest) at rows
  /// r = d + longest − n for d = i_t − i_s = −(longest − n) … longest − 1 and |dj| = 0 …
  /// my − 1. None when the budget has no room for it.
  template <typename BlockOf>
  DisplacementTable<Scalar> displacement(Index count, const BlockOf& block_of, Index mx) {
    FASTNORM_ASSERT(count >= 1 && count <= mx && mx <= longest_);
    const auto slot = static_cast<std::size_t>((longest_ + 1) * (longest_ + 1) + count);
    const Index rows = 2 * longest_ - count;
    if (const Matrix* table = published(slot)) return {table, rows, longest_ - mx};
    if (refused_[slot].load(std::memory_order_relaxed)) return {};
    const Matrix& source = block(count, block_of);
    const Matrix* table =
        publish(slot, rows * source.cols() * extent_->grid().my(), [&]() { return displace(source, *extent_); });
    if (table == nullptr) return {};
    return {table, rows, longest_ - mx};
  }

  /// Builds every table a solver of a covered grid reads, now, if together they fit the
  /// budget: W and the pseudo-inverse for each count from `first_displaced` (smaller
  /// segments have none). With every W at hand a solver reads no K: a block comes from the
  /// W of its longer segment, and two segments no longer than the basis take a few
  /// entries of the influence table (GalerkinSetSolver::assemble). Returns whether it
  /// did; if not, it builds nothing but the blocks, and each table is built when first
  /// needed (docs/wheel-rail.md §9).
  template <typename BlockOf>
  bool build_all(const BlockOf& block_of, Index first_displaced) {
    Index entries = 0;
    for (Index n = first_displaced; n <= longest_; ++n) {
      entries += (2 * longest_ - n) * block(n, block_of).cols() * extent_->grid().my();
    }
    const std::size_t bytes = sizeof(Scalar) * static_cast<std::size_t>(entries);
    if (used_bytes_.load() + bytes > budget_bytes_) return false;
    for (Index n = first_displaced; n <= longest_; ++n) {
      projection(n, block_of);
      displacement(n, block_of, longest_);
    }
    return true;
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
    const Matrix* kept = adopt(slot, table);
    if (table) used_bytes_.fetch_sub(bytes);  // another thread's was kept
    return kept;
  }

  /// Publishes `matrix` (taking it) as the entry of `slot` and returns it, unless another
  /// thread was first: then that one, and `matrix` is left as it was.
  const Matrix* adopt(std::size_t slot, std::unique_ptr<Matrix>& matrix) {
    const std::lock_guard<std::mutex> lock(owner_mutex_);
    if (const Matrix* other = published(slot)) return other;
    owned_.push_back(std::move(matrix));
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

  std::shared_ptr<const InfluenceTable<Scalar>> extent_;
  Index longest_;
  std::size_t budget_bytes_;
  // Per slot: correlations at n_t·(longest + 1) + n_s, displacements after them at
  // (longest + 1)² + n, then basis blocks at (longest + 1)(longest + 2) + n and projections
  // at (longest + 1)(longest + 3) + n. Null until built; refused once the budget had no room.
  std::vector<std::atomic<const Matrix*>> published_;
  std::vector<std::atomic<bool>> refused_;
  std::atomic<std::size_t> used_bytes_{0};
  std::mutex owner_mutex_;
  std::vector<std::unique_ptr<Matrix>> owned_;
};

}  // namespace detail
}  // namespace fastnorm
