#pragma once
/// @file anderson_mixing.hpp
/// Anderson acceleration of a fixed-point iteration x ← G(x) (Walker & Ni, SIAM J. Numer.
/// Anal. 49 (2011), "type II" with memory m): from the last m differences of the outputs G
/// and of the residuals f = G(x) − x, the next iterate is G(x_k) − ΔG γ with γ the least-squares
/// solution of ΔF γ ≈ f_k. Used by the steady-rolling sweeps once their element states have
/// settled (docs/tangential.md §7). The least-squares problem is solved by its normal
/// equations ΔFᵀΔF γ = ΔFᵀ f_k: the m × m Gram matrix gains one row a step (m dot products
/// of the residual's length, where a QR of ΔF costs 2·m² of them a step), and Eigen's
/// complete orthogonal decomposition of it drops the directions of nearly dependent
/// differences. What the squared condition costs in γ only changes how much a step is
/// accelerated, not the fixed point.

#include <Eigen/Core>
#include <Eigen/QR>
#include <algorithm>

namespace fastnorm::detail {

template <typename Scalar>
class AndersonMixing {
 public:
  using Index = Eigen::Index;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  /// `output_size`: the length of G(x); `residual_size`: of f; `memory`: m ≥ 1.
  AndersonMixing(Index output_size, Index residual_size, Index memory)
      : output_changes_(output_size, memory),
        residual_changes_(residual_size, memory),
        gram_(memory, memory),
        last_output_(output_size),
        last_residual_(residual_size) {}

  /// Forgets the history: the next call of mix only records its pair.
  void reset() { recorded_ = 0, have_last_ = false; }

  /// Records the iteration's output and residual and replaces `output` by the mixed next
  /// iterate (left unchanged on the first call after a reset). The columns of the history are
  /// kept in a ring: the least-squares solution does not depend on their order.
  void mix(Eigen::Ref<Vector> output, const Vector& residual) {
    const Index memory = output_changes_.cols();
    if (have_last_) {
      const Index column = recorded_++ % memory;
      output_changes_.col(column) = output - last_output_;
      residual_changes_.col(column) = residual - last_residual_;
      for (Index other = 0; other < std::min(recorded_, memory); ++other) {
        gram_(other, column) = gram_(column, other) = residual_changes_.col(other).dot(residual_changes_.col(column));
      }
    }
    last_output_ = output;
    last_residual_ = residual;
    have_last_ = true;
    const Index stored = std::min(recorded_, memory);
    if (stored == 0) return;
    const Vector projected = residual_changes_.leftCols(stored).transpose() * residual;
    const Vector weights = gram_.topLeftCorner(stored, stored).completeOrthogonalDecomposition().solve(projected);
    output -= output_changes_.leftCols(stored) * weights;
  }

 private:
  Matrix output_changes_, residual_changes_;  // one column per remembered step
  Matrix gram_;                               // ΔFᵀΔF of the remembered steps
  Vector last_output_, last_residual_;
  Index recorded_ = 0;  // changes recorded since the reset; the ring keeps the last m
  bool have_last_ = false;
};

}  // namespace fastnorm::detail
