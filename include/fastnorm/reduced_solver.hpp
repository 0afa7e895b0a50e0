#pragma once
/// @file reduced_solver.hpp
/// Reduced strip-basis solvers (Giner-Navarro, Gómez-Bosch, Alonso, Baeza, Wear 2023;
/// docs/design.md §4, docs/method.md): NORM's active-set loop with the solve on each set
/// replaced by the Galerkin system (Aᵀ C_II A) α = Aᵀ rhs, p_I = A α, where A holds a small
/// basis per segment of each strip.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/QR>
#include <algorithm>
#include <optional>
#include <vector>

#include "fastnorm/active_set.hpp"
#include "fastnorm/bases.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/influence.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/solution.hpp"
#include "fastnorm/strips.hpp"

namespace fastnorm {

namespace detail {

/// Step 2 of the reduced method on one set: segments, basis blocks, Galerkin matrix
/// assembled by pairs of segments from the Toeplitz table, solve, expansion. Keeps the
/// previous set's assembly so that blocks between unchanged segments are copied, not
/// recomputed (docs/method.md §3). One object per solve.
template <typename Basis, typename Scalar>
class GalerkinSetSolver {
 public:
  using Index = Eigen::Index;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  GalerkinSetSolver(const InfluenceTable<Scalar>& influence, const Basis& basis)
      : influence_(influence), basis_(basis) {}

  std::optional<Matrix> solve(const std::vector<Index>& active, const Matrix& rhs) {
    Assembly next;
    next.segments = segment_strips(influence_.grid(), active);
    Index unknowns = 0;
    for (const Segment& segment : next.segments) {
      next.offsets.push_back(unknowns);
      unknowns += unknowns_of(segment.count);
    }
    next.matrix.resize(unknowns, unknowns);
    assemble(next);

    // Right-hand sides Aᵀ rhs, segment by segment.
    Matrix reduced_rhs(unknowns, rhs.cols());
    for (std::size_t s = 0; s < next.segments.size(); ++s) {
      const Segment& segment = next.segments[s];
      const auto rows = rhs.middleRows(segment.set_position, segment.count);
      auto target = reduced_rhs.middleRows(next.offsets[s], unknowns_of(segment.count));
      if (is_identity(segment.count)) target = rows; else target.noalias() = basis_of(segment.count).transpose() * rows;
    }

    Matrix coefficients;
    Eigen::LLT<Matrix, Eigen::Lower> cholesky(next.matrix);
    if (cholesky.info() == Eigen::Success) {
      coefficients = cholesky.solve(reduced_rhs);
    } else {
      // A without full column rank makes Aᵀ C A singular: take the minimum-norm solution.
      const Matrix full = next.matrix.template selfadjointView<Eigen::Lower>();
      const Eigen::CompleteOrthogonalDecomposition<Matrix> decomposition(full);
      coefficients = decomposition.solve(reduced_rhs);
      if (!coefficients.allFinite()) return std::nullopt;
    }

    // Pressures p_I = A α.
    Matrix pressure(static_cast<Index>(active.size()), rhs.cols());
    for (std::size_t s = 0; s < next.segments.size(); ++s) {
      const Segment& segment = next.segments[s];
      const auto alpha = coefficients.middleRows(next.offsets[s], unknowns_of(segment.count));
      auto target = pressure.middleRows(segment.set_position, segment.count);
      if (is_identity(segment.count)) target = alpha; else target.noalias() = basis_of(segment.count) * alpha;
    }
    previous_ = std::move(next);
    return pressure;
  }

 private:
  struct Assembly {
    std::vector<Segment> segments;
    std::vector<Index> offsets;  // first unknown of each segment
    Matrix matrix;               // Aᵀ C_II A, lower triangle filled
  };

  /// A segment with no more elements than the basis has functions keeps one unknown per
  /// element (identity block), as the paper does at leading and trailing edges.
  bool is_identity(Index count) const { return count <= basis_.unknowns(); }
  Index unknowns_of(Index count) const { return is_identity(count) ? count : basis_.unknowns(); }

  /// The basis block of a segment depends only on its element count: cached per count.
  const Matrix& basis_of(Index count) {
    if (static_cast<Index>(blocks_.size()) <= count) blocks_.resize(static_cast<std::size_t>(count) + 1);
    auto& block = blocks_[static_cast<std::size_t>(count)];
    if (block.size() == 0) block = basis_.template block<Scalar>(count);
    return block;
  }

  /// Position of `segment` in the previous assembly, or −1.
  Index previous_index(const Segment& segment) const {
    const auto& old = previous_.segments;
    const auto at = std::lower_bound(old.begin(), old.end(), segment, [](const Segment& a, const Segment& b) {
      return a.strip < b.strip || (a.strip == b.strip && a.first < b.first);
    });
    return at != old.end() && *at == segment ? static_cast<Index>(at - old.begin()) : -1;
  }

  /// Lower triangle of Aᵀ C_II A, block (t, s) for t ≥ s = A_tᵀ C_ts A_s. Per source
  /// segment s, the Toeplitz blocks C_ts of all targets t ≥ s that changed are stacked into
  /// one tall matrix and multiplied by A_s in one product (docs/method.md §3).
  void assemble(Assembly& next) {
    std::vector<Index> old_index;
    for (const Segment& segment : next.segments) old_index.push_back(previous_index(segment));
    std::vector<std::size_t> targets;
    for (std::size_t s = 0; s < next.segments.size(); ++s) {
      const Segment& source = next.segments[s];
      const Index q_s = unknowns_of(source.count);
      targets.clear();
      Index rows = 0;
      for (std::size_t t = s; t < next.segments.size(); ++t) {
        const Index q_t = unknowns_of(next.segments[t].count);
        if (old_index[s] >= 0 && old_index[t] >= 0) {  // both unchanged: copy
          next.matrix.block(next.offsets[t], next.offsets[s], q_t, q_s) =
              previous_.matrix.block(previous_.offsets[static_cast<std::size_t>(old_index[t])],
                                     previous_.offsets[static_cast<std::size_t>(old_index[s])], q_t, q_s);
        } else {
          targets.push_back(t);
          rows += next.segments[t].count;
        }
      }
      if (targets.empty()) continue;
      // C_ts(m, n) = C(|i_t + m − i_s − n|, |j_t − j_s|): one column of the table each.
      coupling_.resize(rows, source.count);
      Index row = 0;
      for (std::size_t t : targets) {
        const Segment& target = next.segments[t];
        influence_.fill_toeplitz(target.first - source.first, target.strip - source.strip,
                                 coupling_.middleRows(row, target.count));
        row += target.count;
      }
      const bool source_identity = is_identity(source.count);
      if (!source_identity) times_basis_.noalias() = coupling_ * basis_of(source.count);
      const Matrix& half = source_identity ? coupling_ : times_basis_;
      row = 0;
      for (std::size_t t : targets) {
        const Segment& target = next.segments[t];
        auto block = next.matrix.block(next.offsets[t], next.offsets[s], unknowns_of(target.count), q_s);
        if (is_identity(target.count)) {
          block = half.middleRows(row, target.count);
        } else {
          block.noalias() = basis_of(target.count).transpose() * half.middleRows(row, target.count);
        }
        row += target.count;
      }
    }
  }

  const InfluenceTable<Scalar>& influence_;
  const Basis& basis_;
  std::vector<Matrix> blocks_;
  Assembly previous_;
  Matrix coupling_, times_basis_;  // workspace of assemble()
};

}  // namespace detail

/// A reduced strip-basis solver: NORM's active-set loop with a Galerkin solve in `Basis`
/// (EllipticBasis, PolynomialBasis, EdgeEnriched<…>, or any type with the interface of
/// bases.hpp) on each set.
///
/// **Example**
/// @code
/// fastnorm::ReducedSolver<fastnorm::PolynomialBasis> solver(grid, steel, fastnorm::PolynomialBasis(4));
/// auto solution = solver.solve(h, fastnorm::Loading<>::approach());
/// @endcode
template <typename Basis, typename Scalar = double>
class ReducedSolver {
 public:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Options = ActiveSetOptions<Scalar>;

  /// @throws fastnorm::invalid_argument for invalid options
  ReducedSolver(const Grid<Scalar>& grid, const Material<Scalar>& material, Basis basis = Basis(),
                Options options = {})
      : influence_(grid, material), basis_(basis), options_(options) {
    options_.validate();
  }

  const Grid<Scalar>& grid() const { return influence_.grid(); }
  const InfluenceTable<Scalar>& influence() const { return influence_; }
  const Basis& basis() const { return basis_; }
  const Options& options() const { return options_; }

  /// As NormSolver::solve, with the pressure along each segment in the basis.
  /// @throws fastnorm::invalid_argument for wrong sizes or non-finite h
  Solution<Scalar> solve(const Eigen::Ref<const Vector>& undeformed_distance,
                         const Loading<Scalar>& loading) const {
    detail::GalerkinSetSolver<Basis, Scalar> set_solver(influence_, basis_);
    return detail::solve_active_set(influence_, undeformed_distance, loading, options_, set_solver);
  }

 private:
  InfluenceTable<Scalar> influence_;
  Basis basis_;
  Options options_;
};

}  // namespace fastnorm
