#pragma once
/// @file bases.hpp
/// Bases for the pressure along a segment (docs/design.md §4, docs/method.md §2). A basis
/// is a small type with
///   - `Eigen::Index unknowns() const`: its number of functions q;
///   - `Matrix block<Scalar>(Index count) const`: the count × q values of its functions at
///     the element centres of a segment of `count` elements (ξ of strips.hpp);
///   - `std::string name() const`.
/// A reduced solver takes any such type; a segment with count ≤ q keeps one unknown per
/// element instead (the solver's rule, not the basis's).

#include <Eigen/Core>
#include <cmath>
#include <string>

#include "fastnorm/error.hpp"
#include "fastnorm/strips.hpp"

namespace fastnorm {

template <typename Scalar>
using BasisBlock = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

/// A basis whose functions are evaluated at the local coordinates ξ: `Derived` provides
/// `BasisBlock<Scalar> evaluate(const Eigen::Matrix<Scalar, Dynamic, 1>& xi) const`.
template <typename Derived>
struct CoordinateBasis {
  template <typename Scalar>
  BasisBlock<Scalar> block(Eigen::Index count) const {
    return static_cast<const Derived&>(*this).evaluate(segment_coordinates<Scalar>(count));
  }
};

/// p(ξ) = α0 + α1·sqrt(1 − ξ²): Hertz's half-ellipse on a constant (2 unknowns).
struct EllipticBasis : CoordinateBasis<EllipticBasis> {
  Eigen::Index unknowns() const { return 2; }
  std::string name() const { return "elliptic"; }

  template <typename Scalar>
  BasisBlock<Scalar> evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& xi) const {
    BasisBlock<Scalar> values(xi.size(), 2);
    values.col(0).setOnes();
    values.col(1) = (1 - xi.array().square()).sqrt().matrix();
    return values;
  }
};

/// p(ξ) = Σ_{n=0..g} β_n P_n(ξ), Legendre polynomials of grade ≤ g (g + 1 unknowns).
///
/// The paper writes p = Σ β_n xⁿ. The polynomials of grade ≤ g are one space whatever
/// basis spans them, and x = x_c + L ξ is an affine map of ξ, so {P_n(ξ)} spans exactly
/// {xⁿ}: the Galerkin solution p = A α is the same. The powers of x make Aᵀ C A a
/// Hilbert-like matrix (columns 1, x, x², … nearly parallel on a segment); Legendre
/// polynomials are orthogonal on (−1, 1) and keep it well conditioned.
struct PolynomialBasis : CoordinateBasis<PolynomialBasis> {
  /// @param grade g, 0 to 30
  /// @throws fastnorm::invalid_argument for a grade outside [0, 30]
  explicit PolynomialBasis(int grade = 4) : grade_(grade) {
    FASTNORM_CHECK(grade >= 0 && grade <= 30,
                   detail::describe("PolynomialBasis: grade must lie in [0, 30]", grade));
  }
  int grade() const { return grade_; }
  Eigen::Index unknowns() const { return grade_ + 1; }
  std::string name() const { return "polynomial:" + std::to_string(grade_); }

  template <typename Scalar>
  BasisBlock<Scalar> evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& xi) const {
    BasisBlock<Scalar> values(xi.size(), grade_ + 1);
    values.col(0).setOnes();
    if (grade_ >= 1) values.col(1) = xi;
    // Bonnet: (n + 1) P_{n+1} = (2n + 1) ξ P_n − n P_{n−1}.
    for (int n = 1; n < grade_; ++n) {
      values.col(n + 1) = ((2 * n + 1) * xi.cwiseProduct(values.col(n)) - n * values.col(n - 1)) / (n + 1);
    }
    return values;
  }

 private:
  int grade_;
};

/// `Inner` on the interior of a segment, plus a free unknown on each of its first and
/// last `edge_elements` elements (docs/method.md §2.3). The inner functions keep the ξ of
/// the whole segment, so the elliptic one still vanishes at the segment's ends; they are
/// zero on the edge elements, whose own unknowns carry them.
template <typename Inner>
class EdgeEnriched {
 public:
  /// @throws fastnorm::invalid_argument for edge_elements < 1
  explicit EdgeEnriched(Inner inner = Inner(), Eigen::Index edge_elements = 1)
      : inner_(inner), edge_elements_(edge_elements) {
    FASTNORM_CHECK(edge_elements >= 1,
                   detail::describe("EdgeEnriched: edge_elements must be >= 1", edge_elements));
  }
  const Inner& inner() const { return inner_; }
  Eigen::Index edge_elements() const { return edge_elements_; }
  Eigen::Index unknowns() const { return 2 * edge_elements_ + inner_.unknowns(); }
  std::string name() const {
    const std::string inner_name = inner_.name();
    const auto colon = inner_name.find(':');
    return colon == std::string::npos
               ? inner_name + "-edge:" + std::to_string(edge_elements_)
               : inner_name.substr(0, colon) + "-edge" + inner_name.substr(colon) + ":" +
                     std::to_string(edge_elements_);
  }

  template <typename Scalar>
  BasisBlock<Scalar> block(Eigen::Index count) const {
    const Eigen::Index k = edge_elements_, interior = count - 2 * k;
    FASTNORM_ASSERT(interior > 0);
    BasisBlock<Scalar> values = BasisBlock<Scalar>::Zero(count, unknowns());
    for (Eigen::Index m = 0; m < k; ++m) {
      values(m, m) = 1;                          // leading edge
      values(count - k + m, k + m) = 1;          // trailing edge
    }
    const Eigen::Matrix<Scalar, Eigen::Dynamic, 1> xi = segment_coordinates<Scalar>(count);
    values.block(k, 2 * k, interior, inner_.unknowns()) = inner_.evaluate(Eigen::Matrix<Scalar, Eigen::Dynamic, 1>(xi.segment(k, interior)));
    return values;
  }

 private:
  Inner inner_;
  Eigen::Index edge_elements_;
};

using EllipticEdgeBasis = EdgeEnriched<EllipticBasis>;
using PolynomialEdgeBasis = EdgeEnriched<PolynomialBasis>;

}  // namespace fastnorm
