#pragma once
/// @file profile_curve.hpp
/// A profile as the wheel–rail geometry uses it: value and slope on a valid interval,
/// whatever its source (closed form or a spline through measured points), plus the two
/// 1-D solvers the geometry needs.

#include <cmath>
#include <functional>
#include <optional>
#include <utility>
#include <variant>

#include "fastnorm/error.hpp"
#include "fastnorm/wheelrail/profile_file.hpp"
#include "fastnorm/wheelrail/profile_value.hpp"
#include "fastnorm/wheelrail/s1002.hpp"
#include "fastnorm/wheelrail/uic60.hpp"

namespace fastnorm::wheelrail {

/// A profile function y ↦ {value, slope} (m) valid on [y_min(), y_max()] (m).
/// Wheels: value = radius increase F above the nominal radius, y = profile coordinate from
/// the taping line, positive to the field side (as S1002). Rails: value = depth z_r below
/// the top (positive down), y = y_r from the rail's axis, positive to the field side of the
/// right rail, uncanted unless the track is given a cant of zero.
///
/// The built-in profiles and splines are held as themselves, so that `evaluate` is a direct
/// call the compiler can inline into the geometry's loops (h along a row evaluates the wheel
/// at every node, docs/wheel-rail.md §4); any other function of y is held as a
/// `std::function` and costs an indirect call per point.
class ProfileCurve {
 public:
  /// Any function of y, e.g. a closed form of one's own.
  using Function = std::function<ProfileValue<double>(double)>;

  /// @throws fastnorm::invalid_argument for an empty function or an interval that is not
  ///         y_min < y_max (both finite)
  ProfileCurve(Function function, double y_min, double y_max) : source_(std::move(function)), y_min_(y_min), y_max_(y_max) {
    FASTNORM_CHECK(static_cast<bool>(std::get<Function>(source_)), "ProfileCurve: function is empty");
    FASTNORM_CHECK(std::isfinite(y_min) && std::isfinite(y_max) && y_min < y_max,
                   "ProfileCurve: y_min < y_max must hold (m), both finite");
  }
  /// The closed-form S1002 wheel on its whole valid interval.
  explicit ProfileCurve(S1002<double> wheel) : source_(wheel), y_min_(S1002<double>::y_min), y_max_(S1002<double>::y_max) {}
  /// The closed-form UIC60 head up to the end of its R13 arcs.
  explicit ProfileCurve(const Uic60<double>& rail) : source_(rail), y_min_(-rail.flank_start()), y_max_(rail.flank_start()) {}
  /// A spline through measured points, on the interval its points span.
  explicit ProfileCurve(SplineProfile spline)
      : source_(std::move(spline)), y_min_(std::get<SplineProfile>(source_).y_min()),
        y_max_(std::get<SplineProfile>(source_).y_max()) {}

  ProfileValue<double> evaluate(double y) const {
    // A chain of direct calls rather than std::visit: each branch can be inlined, and the
    // branch taken is the same at every call of a model.
    if (const auto* wheel = std::get_if<S1002<double>>(&source_)) return wheel->evaluate(y);
    if (const auto* rail = std::get_if<Uic60<double>>(&source_)) return rail->evaluate(y);
    if (const auto* spline = std::get_if<SplineProfile>(&source_)) return spline->evaluate(y);
    return std::get<Function>(source_)(y);
  }

  double y_min() const { return y_min_; }
  double y_max() const { return y_max_; }
  bool contains(double y) const { return y >= y_min_ && y <= y_max_; }

 private:
  std::variant<S1002<double>, Uic60<double>, SplineProfile, Function> source_;
  double y_min_;
  double y_max_;
};

/// The closed-form S1002 wheel.
inline ProfileCurve s1002_wheel() { return ProfileCurve(S1002<double>()); }

/// The closed-form UIC60 head up to the end of its R13 arcs (MBench variant by default).
inline ProfileCurve uic60_rail(const Uic60<double>& rail = Uic60<double>::mbench()) { return ProfileCurve(rail); }

/// A measured or worn profile: the spline through its points.
inline ProfileCurve spline_curve(SplineProfile spline) { return ProfileCurve(std::move(spline)); }

namespace detail {

/// Root of f on [low, high] where f(low) = `at_low` and f(high) differ in sign: Newton
/// steps from `guess`, kept inside the shrinking bracket (bisection when a step leaves it).
/// `f` returns {value, derivative}. Hand-written: a scalar 1-D root is not Eigen's business.
template <typename Function>
double bracketed_root(Function f, double low, double at_low, double high, double guess, double tolerance) {
  if (at_low == 0) return low;
  double x = (guess > low && guess < high) ? guess : (low + high) / 2;
  for (int step = 0; step < 200 && high - low > tolerance; ++step) {
    const auto here = f(x);
    if (here.value == 0) return x;
    if ((here.value < 0) == (at_low < 0)) {
      low = x;
      at_low = here.value;
    } else {
      high = x;
    }
    const double newton = here.slope != 0 ? x - here.value / here.slope : low - 1;
    const double next = (newton > low && newton < high) ? newton : (low + high) / 2;
    if (std::abs(next - x) <= tolerance / 4) return next;
    x = next;
  }
  return x;
}

/// The same, with f(low) evaluated first.
template <typename Function>
double bracketed_root(Function f, double low, double high, double guess, double tolerance) {
  return bracketed_root(f, low, f(low).value, high, guess, tolerance);
}

/// Root of f by Newton's method from `x` when that converges quickly: at most 8 steps, each
/// inside (low, high), until a step moves less than tolerance/4 — or, for the first step,
/// at most `first_step_acceptance` (a guess so good that one step is enough, see
/// undeformed_distance); empty otherwise (then bracketed_root). The fast path of a root
/// near a known one (undeformed_distance along a row of elements).
template <typename Function>
std::optional<double> newton_root(Function f, double x, double low, double high, double tolerance,
                                  double first_step_acceptance = 0) {
  for (int step = 0; step < 8; ++step) {
    const auto here = f(x);
    if (here.slope == 0) return std::nullopt;
    const double next = x - here.value / here.slope;
    if (!(next > low && next < high)) return std::nullopt;
    const double moved = std::abs(next - x);
    if (moved <= tolerance / 4 || (step == 0 && moved <= first_step_acceptance)) return next;
    x = next;
  }
  return std::nullopt;
}

/// Minimum of a unimodal f on [low, high] by golden-section search (to `tolerance` in x).
template <typename Function>
std::pair<double, double> golden_minimum(Function f, double low, double high, double tolerance) {
  const double ratio = (std::sqrt(5.0) - 1) / 2;
  double a = high - ratio * (high - low), b = low + ratio * (high - low);
  double fa = f(a), fb = f(b);
  while (high - low > tolerance) {
    if (fa <= fb) {
      high = b;
      b = a;
      fb = fa;
      a = high - ratio * (high - low);
      fa = f(a);
    } else {
      low = a;
      a = b;
      fa = fb;
      b = low + ratio * (high - low);
      fb = f(b);
    }
  }
  return fa <= fb ? std::pair{a, fa} : std::pair{b, fb};
}

}  // namespace detail
}  // namespace fastnorm::wheelrail
