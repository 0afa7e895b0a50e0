#pragma once
/// @file constants.hpp
/// Constants of fastnorm, in any scalar type: one spelling of π for the library, its tools
/// and its bindings (M_PI is not standard C++), and the iterative solvers' default tolerance.

#include <algorithm>
#include <limits>

namespace fastnorm {

/// π to the precision of `Scalar` (long double literal, rounded once).
template <typename Scalar = double>
inline constexpr Scalar pi = Scalar(3.141592653589793238462643383279502884L);

/// The default stopping tolerance of the iterative solvers (CG, steady rolling): 1e-9, or
/// 32 ε of `Scalar` where that is larger (3.8e-6 for float, whose products and sweeps
/// cannot reach 1e-9).
template <typename Scalar = double>
inline constexpr Scalar default_tolerance = std::max(Scalar(1e-9), 32 * std::numeric_limits<Scalar>::epsilon());

}  // namespace fastnorm
