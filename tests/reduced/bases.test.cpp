#include <catch2/catch.hpp>
#include <cmath>
#include <fastnorm/bases.hpp>

using Catch::Matchers::Contains;

// The worked example of the paper's appendix (Fig. A1; docs/design.md §4): strip 1 has
// 3 elements at x = −2a, 0, 2a (L1 = 3a), strip 2 has 5 at −4a … 4a (L2 = 5a).
TEST_CASE("Elliptic basis reproduces the paper's worked example", "[bases]") {
  const fastnorm::EllipticBasis basis;
  Eigen::MatrixXd strip1(3, 2), strip2(5, 2);
  strip1 << 1, std::sqrt(5.0 / 9), 1, 1, 1, std::sqrt(5.0 / 9);
  // The printed paper shows √(5/9) at ±2a of strip 2; the correct value is √(1 − 4/25) = √21/5.
  strip2 << 1, 3.0 / 5, 1, std::sqrt(21.0) / 5, 1, 1, 1, std::sqrt(21.0) / 5, 1, 3.0 / 5;
  CHECK((basis.block<double>(3) - strip1).cwiseAbs().maxCoeff() <= 1e-15);
  CHECK((basis.block<double>(5) - strip2).cwiseAbs().maxCoeff() <= 1e-15);
  CHECK(basis.unknowns() == 2);
}

TEST_CASE("Polynomial basis spans the paper's powers of x exactly", "[bases]") {
  // The paper's grade-2 matrix B has rows [1, x, x²] at the element positions relative
  // to the segment centre (reconstructed from its definition: the appendix itself could
  // not be consulted). Legendre P0, P1, P2 of ξ = x/L give B = A T with
  // T = [[1, 0, L²/3], [0, L, 0], [0, 0, 2L²/3]], since x² = L²(2 P2 + P0)/3.
  const double a = 0.25e-3;
  const fastnorm::PolynomialBasis basis(2);
  for (int count : {3, 5}) {
    const double half_length = count * a;  // L = n·dx/2 with dx = 2a
    Eigen::MatrixXd paper(count, 3);
    for (int m = 0; m < count; ++m) {
      const double x = (2 * m - (count - 1)) * a;
      paper.row(m) << 1, x, x * x;
    }
    Eigen::Matrix3d transform;
    transform << 1, 0, half_length * half_length / 3, 0, half_length, 0, 0, 0, 2 * half_length * half_length / 3;
    const Eigen::MatrixXd legendre = basis.block<double>(count);
    INFO("segment of " << count << " elements");
    CHECK((legendre * transform - paper).cwiseAbs().maxCoeff() <= 1e-15 * paper.cwiseAbs().maxCoeff());
  }
  // Strip 1 in the paper's own numbers.
  Eigen::MatrixXd strip1(3, 3);
  strip1 << 1, -2 * a, 4 * a * a, 1, 0, 0, 1, 2 * a, 4 * a * a;
  Eigen::Matrix3d t1;
  t1 << 1, 0, 3 * a * a, 0, 3 * a, 0, 0, 0, 6 * a * a;
  CHECK((basis.block<double>(3) * t1 - strip1).cwiseAbs().maxCoeff() <= 1e-20);
}

TEST_CASE("Legendre columns are the Legendre polynomials", "[bases]") {
  const fastnorm::PolynomialBasis basis(4);
  const Eigen::MatrixXd values = basis.block<double>(7);
  const Eigen::VectorXd xi = fastnorm::segment_coordinates<double>(7);
  for (int m = 0; m < 7; ++m) {
    const double x = xi(m);
    CHECK(values(m, 2) == Approx((3 * x * x - 1) / 2).margin(1e-15));
    CHECK(values(m, 3) == Approx((5 * x * x * x - 3 * x) / 2).margin(1e-15));
    CHECK(values(m, 4) == Approx((35 * std::pow(x, 4) - 30 * x * x + 3) / 8).margin(1e-15));
  }
  CHECK(basis.name() == "polynomial:4");
  CHECK_THROWS_WITH(fastnorm::PolynomialBasis(-1), Contains("grade"));
  CHECK_THROWS_WITH(fastnorm::PolynomialBasis(31), Contains("grade"));
}

TEST_CASE("Edge-enriched basis frees the end elements", "[bases]") {
  const fastnorm::EllipticEdgeBasis basis(fastnorm::EllipticBasis(), 1);
  CHECK(basis.unknowns() == 4);
  CHECK(basis.name() == "elliptic-edge:1");
  const Eigen::MatrixXd values = basis.block<double>(6);
  const Eigen::MatrixXd inner = fastnorm::EllipticBasis().block<double>(6);
  // Columns: leading edge, trailing edge, then the inner basis on rows 1..4 only.
  CHECK(values.row(0) == Eigen::RowVector4d(1, 0, 0, 0));
  CHECK(values.row(5) == Eigen::RowVector4d(0, 1, 0, 0));
  CHECK((values.block(1, 2, 4, 2) - inner.block(1, 0, 4, 2)).cwiseAbs().maxCoeff() == 0);
  CHECK(values.block(1, 0, 4, 2).cwiseAbs().maxCoeff() == 0);

  const fastnorm::PolynomialEdgeBasis wide(fastnorm::PolynomialBasis(4), 2);
  CHECK(wide.unknowns() == 9);
  CHECK(wide.name() == "polynomial-edge:4:2");
  const Eigen::MatrixXd wide_values = wide.block<double>(12);
  CHECK(wide_values.block(0, 0, 2, 2).isIdentity());
  CHECK(wide_values.block(10, 2, 2, 2).isIdentity());
  CHECK_THROWS_WITH(fastnorm::EllipticEdgeBasis(fastnorm::EllipticBasis(), 0), Contains("edge_elements"));
}
