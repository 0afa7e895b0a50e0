#pragma once
/// @file material.hpp
/// Elastic constants of the two bodies and their combined modulus E* (docs/design.md §2).

#include <cmath>
#include <string>
#include <type_traits>

#include "fastnorm/error.hpp"

namespace fastnorm {

/// Young's modulus (Pa) and Poisson's ratio of the two bodies in contact.
///
/// Class invariant: both moduli positive, finite and normal, and so is E*; both ratios in
/// (−1, 0.5].
template <typename Scalar = double>
class Material {
  static_assert(std::is_floating_point_v<Scalar>,
                "fastnorm::Material needs a floating-point Scalar");

 public:
  /// Both bodies of the same material.
  /// @param young_modulus E (Pa, > 0)
  /// @param poisson_ratio ν in (−1, 0.5]
  /// @throws fastnorm::invalid_argument naming the offending argument
  Material(Scalar young_modulus, Scalar poisson_ratio)
      : Material(young_modulus, poisson_ratio, young_modulus, poisson_ratio) {}

  /// Two different bodies.
  /// @throws fastnorm::invalid_argument naming the offending argument
  Material(Scalar young_modulus_1, Scalar poisson_ratio_1, Scalar young_modulus_2,
           Scalar poisson_ratio_2)
      : young_modulus_{young_modulus_1, young_modulus_2},
        poisson_ratio_{poisson_ratio_1, poisson_ratio_2} {
    for (int body = 0; body < 2; ++body) {
      const std::string suffix = "_" + std::to_string(body + 1);
      FASTNORM_CHECK(std::isnormal(young_modulus_[body]) && young_modulus_[body] > 0,
                     detail::describe("material: young_modulus" + suffix +
                                          " must be positive, finite and normal (Pa)",
                                      young_modulus_[body]));
      FASTNORM_CHECK(poisson_ratio_[body] > Scalar(-1) && poisson_ratio_[body] <= Scalar(0.5),
                     detail::describe("material: poisson_ratio" + suffix +
                                          " must lie in (-1, 0.5]",
                                      poisson_ratio_[body]));
    }
    // 1/E* is a sum of two compliances, each up to 1/min E: it must stay finite.
    FASTNORM_CHECK(std::isnormal(combined_modulus()),
                   detail::describe("material: the combined modulus E* must be a normal number (Pa)",
                                    combined_modulus()));
  }

  /// Steel on steel, E = 210 GPa and ν = 0.3 for both bodies: the default of every model
  /// and binding of fastnorm.
  static Material steel() { return Material(Scalar(2.1e11), Scalar(0.3)); }

  /// Young's modulus of body 1 or 2 (Pa).
  Scalar young_modulus(int body = 1) const { return young_modulus_[body - 1]; }
  /// Poisson's ratio of body 1 or 2.
  Scalar poisson_ratio(int body = 1) const { return poisson_ratio_[body - 1]; }

  /// Combined modulus E* (Pa): 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2 (docs/design.md §2).
  Scalar combined_modulus() const {
    Scalar compliance = 0;
    for (int body = 0; body < 2; ++body) {
      compliance += (1 - poisson_ratio_[body] * poisson_ratio_[body]) / young_modulus_[body];
    }
    return 1 / compliance;
  }

  /// Shear modulus G = E/(2(1 + ν)) of body 1 or 2 (Pa).
  Scalar shear_modulus(int body = 1) const {
    return young_modulus_[body - 1] / (2 * (1 + poisson_ratio_[body - 1]));
  }
  /// Kalker's combined shear modulus G (Pa): 1/G = (1/G1 + 1/G2)/2, the modulus of the
  /// tangential influence coefficients (docs/tangential.md §1).
  Scalar combined_shear_modulus() const { return 2 / (1 / shear_modulus(1) + 1 / shear_modulus(2)); }
  /// Kalker's combined Poisson ratio ν: ν/G = (ν1/G1 + ν2/G2)/2. With G it gives back E*:
  /// (1 − ν)/G = 1/E*.
  Scalar combined_poisson_ratio() const {
    return combined_shear_modulus() * (poisson_ratio_[0] / shear_modulus(1) + poisson_ratio_[1] / shear_modulus(2)) / 2;
  }
  /// Kalker's difference parameter K = (G/4)·[(1 − 2ν1)/G1 − (1 − 2ν2)/G2]: how strongly
  /// normal pressure moves the surfaces tangentially against each other (and tangential
  /// traction normally). 0 for bodies of one material (quasi-identical); fastnorm, as
  /// CONTACT by default, solves the normal and tangential problems uncoupled
  /// (docs/tangential.md §1).
  Scalar difference_parameter() const {
    return combined_shear_modulus() / 4 *
           ((1 - 2 * poisson_ratio_[0]) / shear_modulus(1) - (1 - 2 * poisson_ratio_[1]) / shear_modulus(2));
  }

 private:
  Scalar young_modulus_[2];
  Scalar poisson_ratio_[2];
};

}  // namespace fastnorm
