#pragma once
/// @file constants.hpp
/// Mathematical constants of fastnorm, in any scalar type: one spelling of π for the
/// library, its tools and its bindings (M_PI is not standard C++).

namespace fastnorm {

/// π to the precision of `Scalar` (long double literal, rounded once).
template <typename Scalar = double>
inline constexpr Scalar pi = Scalar(3.141592653589793238462643383279502884L);

}  // namespace fastnorm
