#include <catch2/catch.hpp>
#include <cmath>
#include <fastnorm/hertz.hpp>

using Catch::Matchers::Contains;

TEST_CASE("Hertz sphere matches the textbook closed form", "[hertz]") {
  const double radius = 0.3, e_star = 1.153846153846e11, force = 5e4, pi = 3.14159265358979323846;
  const auto contact = fastnorm::hertz_from_force(radius, radius, e_star, force);
  const double a = std::cbrt(3 * force * radius / (4 * e_star));
  CHECK(contact.semi_axis_x == Approx(a).epsilon(1e-13));
  CHECK(contact.semi_axis_y == Approx(a).epsilon(1e-13));
  CHECK(contact.max_pressure == Approx(3 * force / (2 * pi * a * a)).epsilon(1e-13));
  CHECK(contact.approach == Approx(a * a / radius).epsilon(1e-13));
  // The CONTACT peer case states a = 4.602582041 mm, p0 = 1126959512 Pa, δ = 7.061253816e-5 m.
  CHECK(contact.semi_axis_x == Approx(4.602582041e-3).epsilon(1e-9));
  CHECK(contact.max_pressure == Approx(1126959512).epsilon(1e-9));
  CHECK(contact.approach == Approx(7.061253816e-5).epsilon(1e-9));
}

TEST_CASE("Hertz ellipse: force and approach are inverse, axes follow the radii", "[hertz]") {
  const double e_star = 1.153846153846e11;
  const auto by_force = fastnorm::hertz_from_force(0.46, 0.3, e_star, 1e5);
  const auto by_approach = fastnorm::hertz_from_approach(0.46, 0.3, e_star, by_force.approach);
  CHECK(by_approach.normal_force == Approx(1e5).epsilon(1e-10));
  CHECK(by_approach.semi_axis_x == Approx(by_force.semi_axis_x).epsilon(1e-10));
  // The larger radius is along x, so the contact is longer in x.
  CHECK(by_force.semi_axis_x > by_force.semi_axis_y);
  // Johnson's approximation b/a ≈ (R_y/R_x)^(2/3) holds within a few per cent.
  CHECK(by_force.semi_axis_y / by_force.semi_axis_x == Approx(std::pow(0.3 / 0.46, 2.0 / 3)).epsilon(0.03));
  // F = (2/3) π a b p0 for the elliptical pressure.
  CHECK(2.0 / 3 * 3.14159265358979323846 * by_force.semi_axis_x * by_force.semi_axis_y * by_force.max_pressure ==
        Approx(1e5).epsilon(1e-12));
  const auto swapped = fastnorm::hertz_from_force(0.3, 0.46, e_star, 1e5);
  CHECK(swapped.semi_axis_x == Approx(by_force.semi_axis_y).epsilon(1e-14));
  CHECK(swapped.semi_axis_y == Approx(by_force.semi_axis_x).epsilon(1e-14));
  CHECK(swapped.approach == Approx(by_force.approach).epsilon(1e-14));
}

TEST_CASE("Hertz rejects bad input naming the argument", "[hertz]") {
  CHECK_THROWS_WITH(fastnorm::hertz_from_force(0.0, 0.3, 1e11, 1e5), Contains("radius_x"));
  CHECK_THROWS_WITH(fastnorm::hertz_from_force(0.3, -1.0, 1e11, 1e5), Contains("radius_y"));
  CHECK_THROWS_WITH(fastnorm::hertz_from_force(0.3, 0.3, 0.0, 1e5), Contains("combined_modulus"));
  CHECK_THROWS_WITH(fastnorm::hertz_from_force(0.3, 0.3, 1e11, 0.0), Contains("normal_force"));
  CHECK_THROWS_WITH(fastnorm::hertz_from_approach(0.3, 0.3, 1e11, -1e-5), Contains("approach"));
}

TEST_CASE("The complete elliptic integrals need no library function libc++ lacks", "[hertz]") {
  // Closed forms: K(0) = E(0) = π/2; at k = 1/√2, K = Γ(1/4)²/(4√π), E = K/2 + π/(4K)
  // (Legendre's relation at the lemniscatic modulus).
  const double pi = 3.14159265358979323846;
  const auto [k0, e0] = fastnorm::detail::complete_elliptic_integrals(0.0);
  CHECK(k0 == Approx(pi / 2).epsilon(1e-15));
  CHECK(e0 == Approx(pi / 2).epsilon(1e-15));
  const double lemniscatic = std::pow(std::tgamma(0.25), 2) / (4 * std::sqrt(pi));
  const auto [k1, e1] = fastnorm::detail::complete_elliptic_integrals(std::sqrt(0.5));
  CHECK(k1 == Approx(lemniscatic).epsilon(1e-14));
  CHECK(e1 == Approx(lemniscatic / 2 + pi / (4 * lemniscatic)).epsilon(1e-14));
  // Near k = 1: K ≈ ln(4/k'), E → 1.
  const double near_one = 1 - 1e-12, complement = std::sqrt((1 - near_one) * (1 + near_one));  // k' as stored
  const auto [k2, e2] = fastnorm::detail::complete_elliptic_integrals(near_one);
  CHECK(k2 == Approx(std::log(4 / complement)).epsilon(1e-9));
  CHECK(e2 == Approx(1).epsilon(1e-9));
  // Legendre's relation E K' + E' K − K K' = π/2 over the range.
  for (double k = 0.05; k < 1; k += 0.1) {
    const auto [big_k, big_e] = fastnorm::detail::complete_elliptic_integrals(k);
    const auto [big_k2, big_e2] = fastnorm::detail::complete_elliptic_integrals(std::sqrt(1 - k * k));
    CHECK(big_e * big_k2 + big_e2 * big_k - big_k * big_k2 == Approx(pi / 2).epsilon(1e-14));
  }
  const auto [kf, ef] = fastnorm::detail::complete_elliptic_integrals(std::sqrt(0.5f));
  CHECK(kf == Approx(lemniscatic).epsilon(1e-6));
  CHECK(ef == Approx(lemniscatic / 2 + pi / (4 * lemniscatic)).epsilon(1e-6));
}
