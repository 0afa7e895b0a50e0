// Integrals of the half-space point-load kernels over a rectangle, computed numerically in
// long double without the closed forms of influence.hpp and tangential_influence.hpp: the
// independent truth of the influence-coefficient tests (docs/kernel.md §3,
// docs/tangential.md §4).
//
// Each kernel is g(θ)/r with θ the angle of the source point seen from the field point:
// 1/r (g = 1), x²/r³ (cos²θ), y²/r³ (sin²θ), xy/r³ (sin θ cos θ). Near the field point
// (the singular self term included) the rectangle is split at the field point into four
// corner rectangles, each integrated in polar coordinates around its singular corner,
// where the radial integral is the radius itself: ∫ g(θ) R(θ) dθ, smooth in θ; far from
// it, by a tensor Gauss–Legendre rule.
#pragma once

#include <cmath>
#include <vector>

namespace fastnorm {
namespace test {

using Real = long double;
inline constexpr Real pi_long = 3.14159265358979323846264338327950288L;

// Gauss–Legendre rule on [−1, 1] by Newton's method on P_n.
struct GaussLegendre {
  std::vector<Real> nodes, weights;
  explicit GaussLegendre(int n) {
    for (int i = 1; i <= n; ++i) {
      Real x = std::cos(pi_long * (i - 0.25L) / (n + 0.5L)), derivative = 0;
      for (int step = 0; step < 100; ++step) {
        Real p0 = 1, p1 = x;
        for (int k = 2; k <= n; ++k) {
          const Real p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        derivative = n * (x * p1 - p0) / (x * x - 1);
        const Real dx = p1 / derivative;
        x -= dx;
        if (std::abs(dx) < 1e-19L) break;
      }
      nodes.push_back(x);
      weights.push_back(2 / ((1 - x * x) * derivative * derivative));
    }
  }
  // Composite rule of `panels` equal panels on [low, high].
  template <typename F>
  Real integrate(F f, Real low, Real high, int panels) const {
    Real sum = 0;
    const Real width = (high - low) / panels;
    for (int p = 0; p < panels; ++p) {
      const Real mid = low + (p + 0.5L) * width;
      for (std::size_t n = 0; n < nodes.size(); ++n) sum += weights[n] * f(mid + width / 2 * nodes[n]);
    }
    return sum * width / 2;
  }
};

inline const GaussLegendre& gauss_legendre_24() {
  static const GaussLegendre rule(24);
  return rule;
}

enum class PointKernel { inverse_distance, xx, yy, xy };

// g(θ) of the kernel, θ the angle of (x, y) = r (cos θ, sin θ).
inline Real angular_factor(PointKernel kernel, Real theta) {
  switch (kernel) {
    case PointKernel::xx: return std::cos(theta) * std::cos(theta);
    case PointKernel::yy: return std::sin(theta) * std::sin(theta);
    case PointKernel::xy: return std::sin(theta) * std::cos(theta);
    case PointKernel::inverse_distance: break;
  }
  return 1;
}

inline Real kernel_value(PointKernel kernel, Real x, Real y) {
  const Real r = std::sqrt(x * x + y * y);
  switch (kernel) {
    case PointKernel::xx: return x * x / (r * r * r);
    case PointKernel::yy: return y * y / (r * r * r);
    case PointKernel::xy: return x * y / (r * r * r);
    case PointKernel::inverse_distance: break;
  }
  return 1 / r;
}

// ∫₀^X ∫₀^Y kernel dA for X, Y ≥ 0 in polar coordinates around the singular corner:
// ∫₀^θc g X / cos θ dθ + ∫_θc^(π/2) g Y / sin θ dθ, θc = atan2(Y, X).
inline Real corner_integral(PointKernel kernel, Real X, Real Y) {
  if (X == 0 || Y == 0) return 0;
  const Real corner = std::atan2(Y, X);
  const auto along_x = [&](Real theta) { return angular_factor(kernel, theta) * X / std::cos(theta); };
  const auto along_y = [&](Real theta) { return angular_factor(kernel, theta) * Y / std::sin(theta); };
  const auto& rule = gauss_legendre_24();
  return rule.integrate(along_x, 0, corner, 64) + rule.integrate(along_y, corner, pi_long / 2, 64);
}

// ∫∫ kernel dA over [x1, x2] × [y1, y2], the field point at the origin (may lie inside).
inline Real rectangle_integral_near(PointKernel kernel, Real x1, Real x2, Real y1, Real y2) {
  // ∫₀^X ∫₀^Y f(x, y) = sX·sY ∫₀^|X| ∫₀^|Y| f(sX u, sY v): the kernels are even in x and
  // y except xy, odd in both, which gives sX·sY once more.
  const auto signed_corner = [kernel](Real X, Real Y) {
    const Real signs = (X < 0) != (Y < 0) ? -1 : 1;
    return (kernel == PointKernel::xy ? 1 : signs) * corner_integral(kernel, std::abs(X), std::abs(Y));
  };
  return signed_corner(x2, y2) - signed_corner(x1, y2) - signed_corner(x2, y1) + signed_corner(x1, y1);
}

// The same by a direct tensor rule: for field points well outside the rectangle.
inline Real rectangle_integral_far(PointKernel kernel, Real x1, Real x2, Real y1, Real y2) {
  const auto& rule = gauss_legendre_24();
  const auto row = [&](Real x) {
    return rule.integrate([&](Real y) { return kernel_value(kernel, x, y); }, y1, y2, 4);
  };
  return rule.integrate(row, x1, x2, 4);
}

// ∫∫ kernel over the source element of size dx × dy whose centre is (di·dx, dj·dy) away
// from the field point (field minus source), in coordinates centred on the field point.
inline Real element_integral(PointKernel kernel, int di, int dj, Real dx, Real dy, bool near) {
  const Real x = di * dx, y = dj * dy;
  const Real x1 = -x - dx / 2, x2 = -x + dx / 2, y1 = -y - dy / 2, y2 = -y + dy / 2;
  return near ? rectangle_integral_near(kernel, x1, x2, y1, y2) : rectangle_integral_far(kernel, x1, x2, y1, y2);
}

}  // namespace test
}  // namespace fastnorm
