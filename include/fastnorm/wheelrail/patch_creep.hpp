#pragma once
/// @file patch_creep.hpp
/// The creep forces of one patch of the time loop's model (docs/wheel-rail.md §10): its
/// creepages at its reference point from the wheelset's velocity by rigid kinematics, its
/// tractions on its pressure by FASTSIM or strip theory, and their force and moment on the
/// wheel, added to the patch's.

#include <Eigen/Core>
#include <cmath>

#include "fastnorm/constants.hpp"
#include "fastnorm/fastsim.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/strip_theory.hpp"
#include "fastnorm/wheelrail/creepage.hpp"
#include "fastnorm/wheelrail/wheelset.hpp"
#include "fastnorm/wheelrail/wheelset_contact_options.hpp"
#include "fastnorm/wheelrail/wheelset_contact_result.hpp"

namespace fastnorm::wheelrail {

/// The creep forces' workspaces of a wheelset contact model (strip theory's, and its
/// central differences'); what it adds to a patch depends on the patch and the arguments
/// only.
class PatchCreep {
 public:
  explicit PatchCreep(const Material<double>& material) : strips_(material) {}

  /// The creepages of `out` at its reference point and its creep forces by the method of
  /// options.creep (whose friction must be set) on its pressure, added to its force and
  /// moment on the wheel; without pressure, its creepages only.
  void add(const Wheelset& wheelset, const WheelsetContactOptions& options, const WheelsetPose& pose,
           const WheelsetVelocity& velocity, PatchContact& out) {
    const auto& patch = out.patch;
    const PatchKinematics kinematics = patch_kinematics(wheelset, pose, velocity, patch.frame);
    const auto& normal = out.solution;
    if (!normal.ok() || !(normal.normal_force > 0)) {  // no pressure to carry tractions
      clear(out, patch.grid.size());
      out.creepage = kinematics.creepage;
      return;
    }
    out.creepage = kinematics.creepage;
    const double friction = *options.creep.friction;
    if (options.creep.method == CreepMethod::fastsim) {
      const auto flexibility = kalker_flexibility(equivalent_ellipse(patch.grid, normal), options.material);
      solve_fastsim(patch.grid, normal, friction, kinematics.creepage, flexibility, kinematics.direction, out.traction,
                    options.creep.sensitivities ? &out.creep_jacobian : nullptr);
    } else {
      strips_.solve(patch.grid, normal, friction, kinematics.creepage, kinematics.direction, out.traction);
      if (options.creep.sensitivities) strip_theory_jacobian(patch, normal, friction, kinematics, out.creep_jacobian);
    }
    const auto& traction = out.traction;
    out.creep_force = -(traction.force_x * Eigen::Vector3d::UnitX() + traction.force_y * patch.frame.lateral_axis());
    out.force += out.creep_force;
    out.moment += detail::cross(patch.frame.reference - wheelset.centre(pose), out.creep_force) -
                  traction.spin_moment * patch.frame.normal();
  }

  /// No creep: the patch's creepages, tractions and creep force cleared, its tractions
  /// `elements` long (0 without velocities: a model evaluated without them holds none).
  static void clear(PatchContact& out, Eigen::Index elements) {
    out.creepage = {};
    fastnorm::detail::reset_answer(out.traction, elements);
    out.creep_force.setZero();
    out.creep_jacobian.setConstant(std::nan(""));
  }

 private:
  /// d(Fx, Fy, Mz)/d(ξ, η, φ) of strip theory by central differences, steps 10⁻⁷ in ξ and η
  /// and 10⁻⁷/c in φ (c the patch's size √(area/π)): strip theory is smooth in the
  /// creepages but for the element where an adhesion zone ends, whose jumps are 10⁻⁵ of the
  /// forces' scale per step and average out.
  void strip_theory_jacobian(const ContactPatch& patch, const Solution<>& normal, double friction,
                             const PatchKinematics& kinematics, CreepJacobian<double>& jacobian) {
    const double size = std::sqrt(static_cast<double>(normal.in_contact.count()) * patch.grid.element_area() / pi<double>);
    for (int column = 0; column < 3; ++column) {
      const double step = column == 2 ? 1e-7 / size : 1e-7;
      Eigen::Vector3d sides[2];
      for (int side = 0; side < 2; ++side) {
        Creepage<> shifted = kinematics.creepage;
        double& value = column == 0 ? shifted.longitudinal : column == 1 ? shifted.lateral : shifted.spin;
        value += side == 0 ? step : -step;
        strips_.solve(patch.grid, normal, friction, shifted, kinematics.direction, difference_traction_);
        sides[side] = {difference_traction_.force_x, difference_traction_.force_y, difference_traction_.spin_moment};
      }
      jacobian.col(column) = (sides[0] - sides[1]) / (2 * step);
    }
  }

  StripTheory<> strips_;                      // CreepMethod::strip_theory's workspace
  TangentialSolution<> difference_traction_;  // strip theory's central differences
};

}  // namespace fastnorm::wheelrail
