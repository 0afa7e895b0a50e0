#pragma once
/// @file profile_value.hpp
/// What a 2-D profile function returns at a point.

namespace fastnorm::wheelrail {

/// A profile height and its slope at one lateral position.
template <typename Scalar = double>
struct ProfileValue {
  Scalar value = 0;  ///< height (m), in the profile's own sign convention
  Scalar slope = 0;  ///< d(value)/dy (dimensionless)
};

}  // namespace fastnorm::wheelrail
