#include <catch2/catch.hpp>
#include <fastnorm/material.hpp>

using Catch::Matchers::Contains;

TEST_CASE("Combined modulus of two bodies", "[material]") {
  // Steel on steel: E* = E / (2 (1 − ν²)).
  const fastnorm::Material<> steel(2.1e11, 0.3);
  CHECK(steel.combined_modulus() == Approx(2.1e11 / (2 * 0.91)).epsilon(1e-14));
  // Steel on a rigid-ish body twice as stiff with ν = 0: 1/E* = 0.91/E + 1/(2E).
  const fastnorm::Material<> mixed(2.1e11, 0.3, 4.2e11, 0.0);
  CHECK(mixed.combined_modulus() == Approx(1 / (0.91 / 2.1e11 + 1 / 4.2e11)).epsilon(1e-14));
  CHECK(mixed.young_modulus(2) == 4.2e11);
  CHECK(mixed.poisson_ratio(1) == 0.3);
}

TEST_CASE("Material rejects bad constants naming the argument", "[material]") {
  using M = fastnorm::Material<>;
  CHECK_THROWS_WITH(M(0.0, 0.3), Contains("young_modulus_1"));
  CHECK_THROWS_WITH(M(2e11, 0.3, -1.0, 0.3), Contains("young_modulus_2"));
  CHECK_THROWS_WITH(M(2e11, 0.6), Contains("poisson_ratio_1"));
  CHECK_THROWS_WITH(M(2e11, 0.3, 2e11, -1.0), Contains("poisson_ratio_2"));
  CHECK_THROWS_AS(M(std::nan(""), 0.3), fastnorm::invalid_argument);
  // A subnormal modulus (found by tests/fuzz/solvers), and normal moduli whose E* is not.
  CHECK_THROWS_WITH(M(1.5e-314, 0.3), Contains("young_modulus_1") && Contains("normal"));
  CHECK_THROWS_WITH(M(3e-308, 0.0, 3e-308, 0.0), Contains("combined modulus"));
  CHECK(M(1e-300, 0.3).combined_modulus() == Approx(1e-300 / (2 * 0.91)));
  CHECK_NOTHROW(M(2e11, 0.5));  // incompressible is allowed
}
