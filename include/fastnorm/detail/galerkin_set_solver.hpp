#pragma once
/// @file detail/galerkin_set_solver.hpp
/// Step 2 of the reduced strip-basis solvers on one set (docs/method.md §1–3): the Galerkin
/// system (Aᵀ C_II A) α = Aᵀ rhs assembled from the influence and segment tables, solved by
/// Cholesky, p_I = A α; and the join check's displacements from the basis coefficients.

#include <Eigen/Core>
#include <Eigen/QR>
#include <algorithm>
#include <vector>

#include "fastnorm/detail/in_place_cholesky.hpp"
#include "fastnorm/detail/scratch_matrix.hpp"
#include "fastnorm/detail/segment_tables.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/influence.hpp"
#include "fastnorm/strips.hpp"

namespace fastnorm {
namespace detail {

/// What a Galerkin set solver keeps: the assemblies of
/// Aᵀ C_II A with their Cholesky factors for the sets of the current solve and of the
/// previous one, and the workspace of one set. All
/// of it keeps its storage (assemblies no longer needed wait in `spare`), so the loop stops
/// allocating once it has met its largest set (docs/performance.md §3).
template <typename Scalar>
struct GalerkinMemory {
  using Index = Eigen::Index;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  struct Assembly {
    std::vector<Segment> segments;   // sorted by strip, then first element
    std::vector<Index> order;        // segment indices in the order of their unknowns
    std::vector<Index> offsets;      // first unknown of each segment
    ScratchMatrix<Scalar> matrix;    // Aᵀ C_II A, its lower triangle (store_block)
    InPlaceCholesky<Scalar> cholesky;
    int factor_updates = 0;          // rank-one updates its factor's rows carry (factorise)
    Index unknowns() const { return matrix.rows(); }
  };
  std::vector<Assembly> path;       // the sets of this solve
  std::vector<Assembly> last_path;  // the sets of the previous solve of a sequence
  std::vector<Assembly> spare;      // storage to reuse
  // Workspace of one set.
  std::vector<Segment> segments, target_runs;
  std::vector<Index> old_index, new_index;
  std::vector<std::size_t> direct;
  struct SurvivorRun {  // unknowns of consecutive surviving segments, contiguous in both sets
    Index next_offset, previous_offset, size;
  };
  std::vector<SurvivorRun> survivor_runs;
  std::vector<Index> survivor_unknowns;  // kept unknowns past the leading ones: rows of the previous factor
  ScratchMatrix<Scalar> dropped_columns, coupling, times_basis, block_entries, reduced_rhs, coefficients;
  std::size_t system_capacity = 0;  // values of the largest matrix or factor recycled

  GalerkinMemory() = default;
  GalerkinMemory(const GalerkinMemory& other) { *this = other; }
  /// A copy holds what the next solve reads of the memory, the assemblies of the last solve
  /// (`path`; next_problem() recycles `last_path` first, unread), copied into this
  /// memory's own assemblies and spares; its spares and its one set's workspace stay its
  /// own storage (a time loop's trial steps copy workspaces often: WheelsetContact::restore).
  GalerkinMemory& operator=(const GalerkinMemory& other) {
    if (this != &other) {
      recycle(last_path);
      copy_assemblies(other.path, path);
      system_capacity = std::max(system_capacity, other.system_capacity);
    }
    return *this;
  }
  GalerkinMemory(GalerkinMemory&&) noexcept = default;
  GalerkinMemory& operator=(GalerkinMemory&&) noexcept = default;
  ~GalerkinMemory() = default;

  /// Storage for sets of up to `segment_count` segments and solves of up to `set_count`
  /// sets, so that the usual sets of a grid do not grow it a little at a time (nothing once
  /// reserved). The Galerkin matrices and factors still grow to the largest system met.
  void reserve(std::size_t segment_count, std::size_t set_count) {
    for (auto* list : {&segments, &target_runs}) list->reserve(segment_count);
    for (auto* list : {&old_index, &new_index}) list->reserve(segment_count);
    survivor_unknowns.reserve(segment_count);
    direct.reserve(segment_count);
    survivor_runs.reserve(segment_count);
    for (auto* assemblies : {&path, &last_path}) assemblies->reserve(set_count);
    spare.reserve(2 * set_count);  // both paths' assemblies come back to it (forget)
  }

  /// An assembly to fill: the spare one with the most storage, so that storage grows only
  /// when more systems of the largest size are needed at once than ever before; a new one
  /// has lists for as many segments as the set's, and matrices as large as the largest
  /// recycled (`system_capacity`).
  Assembly take_spare() {
    if (spare.empty()) {
      Assembly fresh;
      for (auto* list : {&fresh.order, &fresh.offsets}) list->reserve(segments.capacity());
      fresh.segments.reserve(segments.capacity());
      fresh.matrix.reserve(system_capacity);
      fresh.cholesky.reserve(system_capacity);
      return fresh;
    }
    const auto largest = std::max_element(spare.begin(), spare.end(), [](const Assembly& a, const Assembly& b) {
      return a.matrix.capacity() < b.matrix.capacity();
    });
    Assembly assembly = std::move(*largest);
    *largest = std::move(spare.back());
    spare.pop_back();
    return assembly;
  }
  void recycle(std::vector<Assembly>& assemblies) {
    for (Assembly& assembly : assemblies) {
      system_capacity = std::max({system_capacity, assembly.matrix.capacity(), assembly.cholesky.capacity()});
      spare.push_back(std::move(assembly));
    }
    assemblies.clear();
  }
  /// `to` made a copy of `from`, in assemblies it holds or takes from the spares.
  void copy_assemblies(const std::vector<Assembly>& from, std::vector<Assembly>& to) {
    while (to.size() > from.size()) {
      spare.push_back(std::move(to.back()));
      to.pop_back();
    }
    while (to.size() < from.size()) to.push_back(take_spare());
    for (std::size_t k = 0; k < from.size(); ++k) {
      // Lists with the source's room: a copy of a longer set later still fits.
      to[k].segments.reserve(from[k].segments.capacity());
      to[k].order.reserve(from[k].order.capacity());
      to[k].offsets.reserve(from[k].offsets.capacity());
      // Every member of an Assembly (one added to it is added here); of the system and its
      // factor the lower triangles, all that store_block writes and the solves read.
      to[k].segments = from[k].segments;
      to[k].order = from[k].order;
      to[k].offsets = from[k].offsets;
      to[k].matrix.assign_lower(from[k].matrix);
      to[k].cholesky.assign_lower(from[k].cholesky);
      to[k].factor_updates = from[k].factor_updates;
    }
  }
  /// No set to look up any more (another solver's, or a cold start): every assembly
  /// becomes storage to reuse.
  void forget() {
    recycle(path);
    recycle(last_path);
  }
  /// Before a solve: the previous solve's sets become the ones to look up.
  void next_problem() {
    recycle(last_path);
    std::swap(last_path, path);
  }
};

/// Step 2 of the reduced method on one set: segments, basis blocks, Galerkin matrix
/// assembled by pairs of segments from the Toeplitz table, solve, expansion. Blocks between
/// segments that did not change since the previous set are copied, not recomputed, and the
/// factor's rows of the previous set's leading unchanged segments are kept; a set already
/// assembled in the previous solve of a sequence reuses that assembly and its factorisation
/// (docs/method.md §3, docs/performance.md §3).
template <typename Basis, typename Scalar>
class GalerkinSetSolver {
 public:
  using Index = Eigen::Index;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Memory = GalerkinMemory<Scalar>;
  using Assembly = typename Memory::Assembly;
  static constexpr bool exact_on_set = false;  // the set's problem in the basis

  GalerkinSetSolver(const InfluenceTable<Scalar>& influence, const Basis& basis,
                    SegmentTables<Scalar>& tables, Memory& memory)
      : influence_(influence), basis_(basis), tables_(tables), memory_(memory) {}

  /// The block of `basis` for a segment of `count` elements: the basis's, or the identity
  /// for a segment of no more elements than it has functions (is_identity).
  static Matrix segment_block(const Basis& basis, Index count) {
    return count <= basis.unknowns() ? Matrix(Matrix::Identity(count, count)) : basis.template block<Scalar>(count);
  }

  /// The set solver of solve_active_set: right-hand sides over `active` in, pressures out.
  bool solve(const std::vector<Index>& active, Eigen::Ref<Matrix> columns) {
    segment_strips(influence_.grid(), active, memory_.segments);
    if (!memory_.path.empty() && memory_.path.back().segments == memory_.segments) {
      return solve_with(memory_.path.back(), columns);  // the set just solved, again (a stiffness)
    }
    auto& last_path = memory_.last_path;
    const auto known = std::find_if(last_path.begin(), last_path.end(), [&](const Assembly& assembly) {
      return assembly.segments == memory_.segments;
    });
    Assembly next;
    if (known != last_path.end()) {
      next = std::move(*known);
      last_path.erase(known);
    } else {
      next = memory_.take_spare();
      next.segments.assign(memory_.segments.begin(), memory_.segments.end());
      // Blocks and factor rows come from the set solved just before (or last, in the previous solve).
      const Assembly* previous = !memory_.path.empty() ? &memory_.path.back()
                                 : !last_path.empty()  ? &last_path.back()
                                                       : nullptr;
      const Index leading = order_unknowns(next, previous);
      assemble(next, previous);
      factorise(next, previous, leading);
    }
    memory_.path.push_back(std::move(next));
    return solve_with(memory_.path.back(), columns);
  }

  /// Solves with an assembled set: right-hand sides over the set in `columns`, pressures out.
  bool solve_with(const Assembly& assembly, Eigen::Ref<Matrix> columns) {
    // Right-hand sides Aᵀ rhs, segment by segment; solved in place into the coefficients α.
    auto coefficients = memory_.reduced_rhs.resize(assembly.unknowns(), columns.cols());
    for (std::size_t s = 0; s < assembly.segments.size(); ++s) {
      const Segment& segment = assembly.segments[s];
      const auto rows = columns.middleRows(segment.set_position, segment.count);
      auto target = coefficients.middleRows(assembly.offsets[s], unknowns_of(segment.count));
      if (is_identity(segment.count)) target = rows; else target.noalias() = block_of(segment.count).transpose() * rows;
    }
    if (assembly.cholesky.factored()) {
      assembly.cholesky.solve_in_place(coefficients);
    } else {
      // A without full column rank makes Aᵀ C A singular: take the minimum-norm solution
      // (rare; this path allocates).
      const Matrix full = assembly.matrix.view().template selfadjointView<Eigen::Lower>();
      const Eigen::CompleteOrthogonalDecomposition<Matrix> decomposition(full);
      const Matrix minimum_norm = decomposition.solve(Matrix(coefficients));
      if (!minimum_norm.allFinite()) return false;
      coefficients = minimum_norm;
    }

    // Pressures p_I = A α.
    for (std::size_t s = 0; s < assembly.segments.size(); ++s) {
      const Segment& segment = assembly.segments[s];
      const auto alpha = coefficients.middleRows(assembly.offsets[s], unknowns_of(segment.count));
      auto target = columns.middleRows(segment.set_position, segment.count);
      if (is_identity(segment.count)) target = alpha; else target.noalias() = block_of(segment.count) * alpha;
    }
    return true;
  }

  /// The join check of solve_active_set: u_t = Σ_s C_ts p_s at the elements `targets` for
  /// pressures `pressure` on the set just solved (`active`), which lie in the span of the
  /// basis. Per source segment, α = A⁺ p and each sorted run of targets in a strip takes q
  /// slices of the displacement table (Eq. (M3)); without a table, n_s slices of the
  /// influence table.
  void displacement(const std::vector<Index>& targets, const std::vector<Index>& /*active: its segments are known*/,
                    const Eigen::Ref<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>& pressure,
                    Eigen::Ref<Eigen::Matrix<Scalar, Eigen::Dynamic, 1>> result) {
    FASTNORM_ASSERT(!memory_.path.empty());
    const Assembly& assembly = memory_.path.back();
    FASTNORM_ASSERT(assembly.segments.empty() ||
                    pressure.size() == assembly.segments.back().set_position + assembly.segments.back().count);
    const Index mx = influence_.grid().mx();
    segment_strips(influence_.grid(), targets, memory_.target_runs);
    result.setZero();
    for (const Segment& source : assembly.segments) {
      const auto source_pressure = pressure.segment(source.set_position, source.count);
      const auto table = is_identity(source.count) ? DisplacementTable<Scalar>()
                                                   : tables_.displacement(source.count, new_block(), mx);
      if (table) {
        auto alpha = memory_.coefficients.resize(basis_.unknowns(), 1);  // q ≤ n_s here
        alpha.noalias() = projection_of(source.count) * source_pressure;
        for (const Segment& run : memory_.target_runs) {
          const Index row = run.first - source.first + mx - source.count, dj = std::abs(run.strip - source.strip);
          table.add_to(alpha, row, dj, result.segment(run.set_position, run.count));
        }
      } else {
        for (const Segment& run : memory_.target_runs) {
          auto displacement = result.segment(run.set_position, run.count);
          for (Index m = 0; m < source.count; ++m) {
            displacement +=
                source_pressure(m) * influence_.run(run.first - source.first - m, run.strip - source.strip, run.count);
          }
        }
      }
    }
  }

 private:
  /// A segment with no more elements than the basis has functions keeps one unknown per
  /// element (identity block), as the paper does at leading and trailing edges.
  bool is_identity(Index count) const { return count <= basis_.unknowns(); }
  Index unknowns_of(Index count) const { return is_identity(count) ? count : basis_.unknowns(); }

  /// The block of a segment of `count` elements, the basis's or the identity (is_identity):
  /// it depends on the count only, so it is kept per count with the segment tables, which
  /// every workspace and grid size of the solver share.
  const Matrix& block_of(Index count) { return tables_.block(count, new_block()); }

  /// The pseudo-inverse A⁺ of the basis block of `count` elements (kept as block_of):
  /// α = A⁺ p for p = A α.
  const Matrix& projection_of(Index count) { return tables_.projection(count, new_block()); }

  /// What makes a segment's block when the tables have none yet.
  auto new_block() const {
    return [this](Index count) { return segment_block(basis_, count); };
  }

  /// Position of `segment` in the assembly `previous`, or −1.
  static Index previous_index(const Assembly* previous, const Segment& segment) {
    if (previous == nullptr) return -1;
    const auto& old = previous->segments;
    const auto at = std::lower_bound(old.begin(), old.end(), segment, [](const Segment& a, const Segment& b) {
      return a.strip < b.strip || (a.strip == b.strip && a.first < b.first);
    });
    return at != old.end() && *at == segment ? static_cast<Index>(at - old.begin()) : -1;
  }

  /// Orders the unknowns of `next` (its `order`, `offsets` and matrix size): first the
  /// leading segments of `previous`'s order that `next` still holds, whose rows of the
  /// factor are kept, then its other segments that `previous` holds, in `previous`'s order,
  /// then its new ones. A segment that changes thus moves to the end, and since the
  /// active-set loop moves the same few strip ends back and forth, the kept part is most
  /// of the system. Returns the number of leading kept unknowns, those before the first
  /// one `previous` held and `next` dropped (0 if `previous` has no factor).
  Index order_unknowns(Assembly& next, const Assembly* previous) {
    auto& old_index = memory_.old_index;  // per segment of next: its index in previous, or −1
    auto& new_index = memory_.new_index;  // per segment of previous: its index in next, or −1
    old_index.clear();
    for (const Segment& segment : next.segments) old_index.push_back(previous_index(previous, segment));
    next.order.clear();
    Index kept = 0;
    if (previous != nullptr) {
      new_index.assign(previous->segments.size(), -1);
      for (std::size_t s = 0; s < old_index.size(); ++s) {
        if (old_index[s] >= 0) new_index[static_cast<std::size_t>(old_index[s])] = static_cast<Index>(s);
      }
      bool leading = previous->cholesky.factored();
      for (const Index p : previous->order) {
        const Index s = new_index[static_cast<std::size_t>(p)];
        leading = leading && s >= 0;
        if (s < 0) continue;
        next.order.push_back(s);
        if (leading) kept += unknowns_of(next.segments[static_cast<std::size_t>(s)].count);
      }
    }
    for (std::size_t s = 0; s < old_index.size(); ++s) {
      if (old_index[s] < 0) next.order.push_back(static_cast<Index>(s));
    }
    next.offsets.resize(next.segments.size());
    Index unknowns = 0;
    for (const Index s : next.order) {
      next.offsets[static_cast<std::size_t>(s)] = unknowns;
      unknowns += unknowns_of(next.segments[static_cast<std::size_t>(s)].count);
    }
    next.matrix.resize(unknowns, unknowns);
    return kept;
  }

  /// The Cholesky factor of `next` (docs/method.md §3, "Reuse of the factor" and "Dropped
  /// unknowns by rank updates"). The unknowns that `previous` holds too come first, in its
  /// order. The leading `leading` of them (up to the first unknown that `next` dropped) have
  /// `previous`'s rows of the factor as they are. Where updating_pays, the rows of the other
  /// kept unknowns are `previous`'s restricted to the kept unknowns, updated by the dropped
  /// unknowns' columns restricted to the kept rows (restricted to them, L Lᵀ is the kept
  /// block minus those columns' outer products: InPlaceCholesky::update_rank adds them
  /// back); otherwise they are computed with the new unknowns' rows (factorise_from).
  /// Updates carry round-off from factor to factor along a sequence, so a factor that would
  /// carry more than `update_limit` of them is computed afresh.
  void factorise(Assembly& next, const Assembly* previous, Index leading) {
    const Index n = next.unknowns();
    next.cholesky.resize(n);
    auto factor = next.cholesky.matrix();
    const auto matrix = next.matrix.view();
    // The kept unknowns past the leading ones, as rows of previous's factor (increasing).
    auto& rows = memory_.survivor_unknowns;
    rows.clear();
    Index dropped = 0;
    if (previous != nullptr && previous->cholesky.factored()) {
      for (const Index s : next.order) {
        const auto segment = static_cast<std::size_t>(s);
        const Index old = memory_.old_index[segment];
        if (old < 0) break;  // the new segments come last
        if (next.offsets[segment] < leading) continue;
        const Index from = previous->offsets[static_cast<std::size_t>(old)];
        for (Index u = 0; u < unknowns_of(next.segments[segment].count); ++u) rows.push_back(from + u);
      }
      dropped = previous->unknowns() - leading - static_cast<Index>(rows.size());
    }
    const int carried = leading > 0 || !rows.empty() ? previous->factor_updates : 0;
    const bool afresh = !rows.empty() && carried + dropped > update_limit;  // ends the chain
    const bool update = !rows.empty() && !afresh && updating_pays(n, leading, rows, previous->unknowns());
    Index kept = afresh ? 0 : leading;
    if (kept > 0) {
      factor.topLeftCorner(kept, kept).template triangularView<Eigen::Lower>() =
          previous->cholesky.factor().topLeftCorner(kept, kept);
    }
    if (update) {
      const auto old = previous->cholesky.factor();
      const auto count = static_cast<Index>(rows.size());
      for (Index c = 0; c < leading; ++c) {
        for (Index r = 0; r < count; ++r) factor(leading + r, c) = old(rows[static_cast<std::size_t>(r)], c);
      }
      for (Index c = 0; c < count; ++c) {
        const Index column = rows[static_cast<std::size_t>(c)];
        for (Index r = c; r < count; ++r) factor(leading + r, leading + c) = old(rows[static_cast<std::size_t>(r)], column);
      }
      // V: per dropped unknown with kept rows below it, its column restricted to them.
      auto dropped_columns = memory_.dropped_columns.resize(count, dropped);
      Index columns = 0, first_below = count;
      for_dropped(leading, rows, previous->unknowns(), [&](Index d, Index first) {
        auto column = dropped_columns.col(columns++);
        column.head(first).setZero();
        for (Index r = first; r < count; ++r) column(r) = old(rows[static_cast<std::size_t>(r)], d);
        first_below = std::min(first_below, first);
      });
      if (columns > 0) {
        next.cholesky.update_rank(leading + first_below, leading + count,
                                  dropped_columns.block(first_below, 0, count - first_below, columns));
      }
      kept = leading + count;
    }
    next.factor_updates = kept > 0 ? carried + (update ? static_cast<int>(dropped) : 0) : 0;
    const Index rest = n - kept;
    factor.bottomLeftCorner(rest, kept) = matrix.bottomLeftCorner(rest, kept);
    factor.bottomRightCorner(rest, rest).template triangularView<Eigen::Lower>() = matrix.bottomRightCorner(rest, rest);
    next.cholesky.factorise_from(kept);
  }

  /// visit(d, first) for each unknown d ≥ `leading` of a previous factor of `unknowns`
  /// unknowns that `rows` (the kept ones past the leading, increasing) does not hold and
  /// that has kept rows below it, the first of them rows[first].
  template <typename Visit>
  static void for_dropped(Index leading, const std::vector<Index>& rows, Index unknowns, const Visit& visit) {
    const auto count = static_cast<Index>(rows.size());
    Index first = 0;  // the first kept row after d
    for (Index d = leading; d < unknowns; ++d) {
      while (first < count && rows[static_cast<std::size_t>(first)] < d) ++first;
      if (first == count) return;  // no kept row below: it changes nothing
      if (rows[static_cast<std::size_t>(first)] != d) visit(d, first);
    }
  }

  /// Whether updating the kept rows (factorise) costs less than computing every row after
  /// the leading ones from the matrix. Flops: a rank-one update of m rows about 2m², the
  /// rows computed after k kept ones of n (factorise_from) (n − k)k² + (n − k)²k + (n − k)³/3,
  /// an update's flop weighted `update_weight` against those of Eigen's blocked products
  /// (weights of 1 and 8 timed within the noise of 3, docs/performance.md §8).
  static bool updating_pays(Index n, Index leading, const std::vector<Index>& rows, Index previous_unknowns) {
    const auto count = static_cast<Index>(rows.size());
    double updates = 0;
    for_dropped(leading, rows, previous_unknowns, [&](Index, Index first) {
      const auto m = static_cast<double>(count - first);
      updates += 2 * m * m;
    });
    const auto computed = [n](Index kept) {
      const auto rest = static_cast<double>(n - kept), k = static_cast<double>(kept);
      return rest * k * k + rest * rest * k + rest * rest * rest / 3;
    };
    return update_weight * updates + computed(leading + count) < computed(leading);
  }

  /// Most rank-one updates a factor's rows may carry (factorise): chains of about 2 000 were
  /// measured at round-off (docs/method.md §3, "Dropped unknowns by rank updates").
  static constexpr int update_limit = 1000;
  /// The cost of an update's flop in flops of Eigen's products (updating_pays).
  static constexpr double update_weight = 3;

  /// Block (t, s) of an assembly, A_tᵀ C_ts A_s (t's unknowns down, s's across), as the
  /// assembly stores it: only the lower triangle is kept (all the factorisation reads), so
  /// the block lies at (t, s) when t's unknowns come after s's and as its transpose at
  /// (s, t) otherwise.
  template <typename Value>
  static void store_block(Assembly& assembly, std::size_t t, std::size_t s, const Value& value) {
    auto matrix = assembly.matrix.view();
    const Index row = assembly.offsets[t], column = assembly.offsets[s];
    if (row >= column) {
      matrix.block(row, column, value.rows(), value.cols()) = value;
    } else {
      matrix.block(column, row, value.cols(), value.rows()) = value.transpose();
    }
  }
  /// The blocks between two segments that `previous` holds too, copied from it. Such
  /// segments keep their relative order (order_unknowns), so they form runs whose unknowns
  /// are contiguous in both systems, and the lower triangle between two runs is one
  /// submatrix of both: a few copies instead of one per pair of segments.
  void copy_survivors(Assembly& next, const Assembly& previous) {
    auto& runs = memory_.survivor_runs;
    runs.clear();
    for (const Index s : next.order) {
      const Index old = memory_.old_index[static_cast<std::size_t>(s)];
      if (old < 0) continue;
      const Index at = next.offsets[static_cast<std::size_t>(s)], was = previous.offsets[static_cast<std::size_t>(old)];
      const Index size = unknowns_of(next.segments[static_cast<std::size_t>(s)].count);
      if (!runs.empty() && at == runs.back().next_offset + runs.back().size &&
          was == runs.back().previous_offset + runs.back().size) {
        runs.back().size += size;
      } else {
        runs.push_back({at, was, size});
      }
    }
    auto matrix = next.matrix.view();
    const auto old = previous.matrix.view();
    for (std::size_t a = 0; a < runs.size(); ++a) {
      const auto& row = runs[a];
      matrix.block(row.next_offset, row.next_offset, row.size, row.size).template triangularView<Eigen::Lower>() =
          old.block(row.previous_offset, row.previous_offset, row.size, row.size);
      for (std::size_t b = 0; b < a; ++b) {
        const auto& column = runs[b];
        FASTNORM_ASSERT(row.previous_offset > column.previous_offset);  // the same order in both
        matrix.block(row.next_offset, column.next_offset, row.size, column.size) =
            old.block(row.previous_offset, column.previous_offset, row.size, column.size);
      }
    }
  }

  /// Block (t, s) from the displacement table W of the longer of the two segments
  /// (Eq. (M3)): A_tᵀ C_ts A_s = Σ_m A_short(m, ·)ᵀ W_long(Δ + m, dj, ·) over the shorter
  /// segment's elements, min(n_t, n_s)·q_t·q_s operations (docs/method.md §3). False when
  /// the longer segment has no table (it is no longer than the basis, or past the budget).
  bool block_from_displacement(Assembly& next, std::size_t t, std::size_t s) {
    const Segment &target = next.segments[t], &source = next.segments[s];
    const bool source_longer = source.count >= target.count;
    const Segment &longer = source_longer ? source : target, &shorter = source_longer ? target : source;
    if (is_identity(longer.count)) return false;
    const Index mx = influence_.grid().mx();
    const auto table = tables_.displacement(longer.count, new_block(), mx);
    if (!table) return false;
    const Index q_long = table.functions(), q_short = unknowns_of(shorter.count);
    // entries(a, b): a over the shorter segment's unknowns, b over the longer's.
    auto entries = memory_.block_entries.resize(q_short, q_long);
    const Index row = shorter.first - longer.first + mx - longer.count, dj = std::abs(shorter.strip - longer.strip);
    const Scalar* w = table.at(row, dj);
    if (is_identity(shorter.count)) {  // one unknown per element: the entries are W's own
      for (Index m = 0; m < shorter.count; ++m, w += q_long) {
        for (Index b = 0; b < q_long; ++b) entries(m, b) = w[b];
      }
    } else {
      const Matrix& basis = block_of(shorter.count);
      for (Index b = 0; b < q_long; ++b) {
        for (Index a = 0; a < q_short; ++a) {
          const Scalar* function = basis.col(a).data();
          Scalar sum = 0;
          for (Index m = 0; m < shorter.count; ++m) sum += function[m] * w[m * q_long + b];
          entries(a, b) = sum;
        }
      }
    }
    if (source_longer) {
      store_block(next, t, s, entries);
    } else {
      store_block(next, t, s, entries.transpose());
    }
    return true;
  }

  /// Aᵀ C_II A, its lower triangle (store_block): block (t, s) for t ≥ s = A_tᵀ C_ts A_s.
  /// The blocks between two segments both in `previous` are copied from it
  /// (copy_survivors); the others are read from the displacement table of the longer
  /// segment (block_from_displacement), or, when it has none (past the memory budget), from
  /// the correlation table of the two lengths (Eq. (M2)); a pair of two segments no longer
  /// than the basis is C_ts itself. Pairs without any table take the direct product: per
  /// source segment s, the Toeplitz blocks C_ts of those targets stacked into one tall
  /// matrix times A_s. `order_unknowns` has filled `old_index`.
  void assemble(Assembly& next, const Assembly* previous) {
    if (previous != nullptr) copy_survivors(next, *previous);
    const auto& old_index = memory_.old_index;
    auto& direct = memory_.direct;
    for (std::size_t s = 0; s < next.segments.size(); ++s) {
      const Segment& source = next.segments[s];
      const Index q_s = unknowns_of(source.count);
      direct.clear();
      Index rows = 0;
      for (std::size_t t = s; t < next.segments.size(); ++t) {
        if (old_index[s] >= 0 && old_index[t] >= 0) continue;  // both unchanged: copied
        const Segment& target = next.segments[t];
        const Index q_t = unknowns_of(target.count);
        if (is_identity(target.count) && is_identity(source.count)) {
          // One unknown per element on both: the block is C_ts itself, a few entries.
          auto block = memory_.block_entries.resize(target.count, source.count);
          influence_.fill_toeplitz(target.first - source.first, target.strip - source.strip, block);
          store_block(next, t, s, block);
          continue;
        }
        if (block_from_displacement(next, t, s)) continue;
        if (const Matrix* correlation = tables_.correlation(target.count, source.count, new_block())) {
          // Σ_d c(Δ + d, dj) K(d), d = −(n_s − 1) … n_t − 1: K's column a + q_t·b is entry (a, b).
          // One dot product per entry rather than Kᵀ times the run: for runs of tens of
          // entries Eigen's matrix–vector product spends more on its set-up than on the sums
          // (measured: polynomial-edge:4:1 solve 0.85×, docs/performance.md §8).
          auto entries = memory_.block_entries.resize(q_t * q_s, 1);
          const auto run = influence_.run(target.first - source.first - (source.count - 1),
                                          target.strip - source.strip, target.count + source.count - 1);
          for (Index e = 0; e < q_t * q_s; ++e) entries(e) = correlation->col(e).dot(run);
          store_block(next, t, s, Eigen::Map<const Matrix>(entries.data(), q_t, q_s));
        } else {
          direct.push_back(t);
          rows += target.count;
        }
      }
      if (direct.empty()) continue;
      // C_ts(m, n) = C(i_t + m − i_s − n, j_t − j_s): one run of the table each column.
      auto coupling = memory_.coupling.resize(rows, source.count);
      Index row = 0;
      for (std::size_t t : direct) {
        const Segment& target = next.segments[t];
        influence_.fill_toeplitz(target.first - source.first, target.strip - source.strip,
                                 coupling.middleRows(row, target.count));
        row += target.count;
      }
      const bool source_identity = is_identity(source.count);
      auto times_basis = memory_.times_basis.resize(rows, q_s);
      if (!source_identity) {
        // In tiles of rows: every target's rows at once were packed on the heap (stack_tile).
        const Index tile = stack_tile<Scalar>(source.count);
        for (Index first = 0; first < rows; first += tile) {
          const Index count = std::min(tile, rows - first);
          times_basis.middleRows(first, count).noalias() = coupling.middleRows(first, count) * block_of(source.count);
        }
      }
      const auto half = source_identity ? coupling : times_basis;
      row = 0;
      for (std::size_t t : direct) {
        const Segment& target = next.segments[t];
        if (is_identity(target.count)) {
          store_block(next, t, s, half.middleRows(row, target.count));
        } else {
          auto block = memory_.block_entries.resize(unknowns_of(target.count), q_s);
          block.noalias() = block_of(target.count).transpose() * half.middleRows(row, target.count);
          store_block(next, t, s, block);
        }
        row += target.count;
      }
    }
  }

  const InfluenceTable<Scalar>& influence_;
  const Basis& basis_;
  SegmentTables<Scalar>& tables_;
  Memory& memory_;
};

}  // namespace detail
}  // namespace fastnorm
