#pragma once
/// @file equilibrium.hpp
/// Static equilibrium of a loaded wheelset on the track (docs/wheel-rail.md §5, from
/// ../shared/docs/wheelset-geometry.md §5): Newton–Raphson on the vertical position z and
/// roll φ with the normal forces of a chosen solver, and the single-wheel mode of
/// CONTACT's benchmark (vertical force prescribed on one wheel, roll 0).

#include <Eigen/Dense>
#include <cmath>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "fastnorm/any_solver.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/wheelrail/contact_search.hpp"
#include "fastnorm/wheelrail/patch.hpp"

namespace fastnorm::wheelrail {

/// Settings of an equilibrium search.
struct EquilibriumOptions {
  std::string solver = "norm";     ///< any AnySolver name
  PatchGridOptions grid;           ///< patch grids (fixed after the first contact search)
  SearchOptions search;            ///< contact search and patch merging
  double young_modulus = 2.1e11;   ///< both bodies (Pa)
  double poisson_ratio = 0.3;      ///< both bodies
  double force_tolerance = 1e-6;   ///< |vertical residual| ≤ tol·load and |roll moment| ≤ tol·load·d
  int max_iterations = 40;         ///< Newton steps in all (each solves every patch once)
  /// Start from this z (and roll, with two wheels) instead of the rigid contact lowered by
  /// a Hertz estimate: e.g. an equilibrium found by a reduced solver, or the previous time
  /// step's, so that full NORM needs fewer solves. y and yaw come from the call.
  std::optional<WheelsetPose> start;
};

enum class EquilibriumStatus {
  converged,      ///< residuals below tolerance
  lost_contact,   ///< a wheel that must carry load has no contact with its rail
  not_converged,  ///< the step limit was reached
  solver_failed,  ///< a patch solve did not give a usable answer
};

inline const char* to_string(EquilibriumStatus status) {
  switch (status) {
    case EquilibriumStatus::converged: return "converged";
    case EquilibriumStatus::lost_contact: return "lost contact";
    case EquilibriumStatus::not_converged: return "not converged";
    case EquilibriumStatus::solver_failed: return "solver failed";
  }
  return "unknown";
}

/// One solved patch.
struct PatchResult {
  ContactPatch patch;
  Solution<double> solution;
};

/// The loaded wheelset at rest.
struct Equilibrium {
  EquilibriumStatus status = EquilibriumStatus::converged;
  std::string message;
  WheelsetPose pose;                  ///< z and roll found (y, yaw as given)
  std::vector<PatchResult> patches;   ///< every patch of the loaded wheel(s), at `pose`
  double vertical_force = 0;          ///< Σ N cos δ (N), what the rails carry
  double lateral_force = 0;           ///< Σ N sin δ (N): the lateral force needed to hold y
  double vertical_residual = 0;       ///< vertical_force − load (N)
  double roll_residual = 0;           ///< −Σ N·L about the wheelset centre (N·m); 0 in single-wheel mode
  int iterations = 0;                 ///< Newton steps (solves of every patch)

  bool ok() const { return status == EquilibriumStatus::converged; }
};

namespace detail {

// Equilibrium search for the wheels in `sides` carrying `load`; roll is an unknown only
// when both wheels are loaded. Each outer pass finds the patches at the current pose (exact
// h); within a pass a rigid motion (dz, dφ) changes the approach of patch k by
// c_k·dz + L_k·dφ (wheelset-geometry.md §5), so Newton runs on solves of h_k − approach_k.
// A pass ends when the residual at its own pose is within tolerance, or the pose moves.
inline Equilibrium find_equilibrium(const Track& track, const Wheelset& wheelset, const std::vector<Side>& sides,
                                    WheelsetPose pose, double load, const EquilibriumOptions& options) {
  const bool with_roll = sides.size() == 2;
  const Material<double> material(options.young_modulus, options.poisson_ratio);
  const double lever_scale = wheelset.layout().taping_line_half_distance;
  Equilibrium result;
  double dx = 0, ds = 0;
  int pass = 0;
  while (result.iterations < options.max_iterations) {
    ++pass;
    // Patches at this pose.
    std::vector<ContactPatch> patches;
    std::vector<ContactRegion> regions;
    for (Side side : sides) {
      auto found = contact_regions(track, wheelset, side, pose, options.search);
      if (found.empty()) {
        result.status = EquilibriumStatus::lost_contact;
        result.message = std::string("the ") + to_string(side) + " wheel does not touch its rail";
        result.pose = pose;
        return result;
      }
      regions.insert(regions.end(), found.begin(), found.end());
    }
    std::vector<PatchFrame> frames;
    std::vector<PatchExtent> extents;
    for (const auto& region : regions) {
      frames.push_back(patch_frame(track, region));
      extents.push_back(patch_extent(frames.back(), region));
    }
    // Element sizes from the regions of the first two passes (the first starts from a
    // guessed approach), then fixed so that the discretisation no longer changes.
    if (pass <= 2) std::tie(dx, ds) = element_sizes(extents, options.grid);
    std::vector<AnySolver<double>> solvers;
    for (std::size_t k = 0; k < regions.size(); ++k) {
      auto grid = patch_grid(extents[k], dx, ds);
      patches.push_back({frames[k], grid, undeformed_distance(track, wheelset, pose, frames[k], grid)});
      solvers.emplace_back(options.solver, grid, material);
    }
    const std::size_t count = patches.size();
    Eigen::VectorXd cosine(count), lever(count), overlap(count);  // overlap: −min h, the rigid approach
    for (std::size_t k = 0; k < count; ++k) {
      const auto& frame = patches[k].frame;
      overlap(static_cast<Eigen::Index>(k)) = -patches[k].undeformed_distance.minCoeff();
      const Eigen::Vector3d arm = frame.reference - wheelset.centre(pose);
      cosine(k) = std::cos(frame.inclination);
      lever(k) = arm.y() * std::cos(frame.inclination) + arm.z() * std::sin(frame.inclination);
    }
    // Newton within this pass.
    Eigen::Vector2d motion = Eigen::Vector2d::Zero();  // (dz, dφ)
    Eigen::VectorXd previous_approach = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(count), std::nan(""));
    Eigen::VectorXd previous_force(count);
    std::vector<Solution<double>> solutions(count);
    bool first = true;
    while (result.iterations < options.max_iterations) {
      ++result.iterations;
      Eigen::VectorXd approach = cosine * motion(0) + lever * motion(1), force(count), stiffness(count);
      for (std::size_t k = 0; k < count; ++k) {
        const auto e = static_cast<Eigen::Index>(k);
        solutions[k] = solvers[k].solve(patches[k].undeformed_distance.array() - approach(e), Loading<double>::approach());
        if (!solutions[k].ok()) {
          result.status = EquilibriumStatus::solver_failed;
          result.message = "patch " + std::to_string(k + 1) + ": " + solutions[k].message;
          result.pose = pose;
          return result;
        }
        force(e) = solutions[k].normal_force;
        // dN/d(approach): secant on the last two solves, else a Hertz-like 1.5·N/pen.
        const double penetration = approach(e) + overlap(e);
        const double change = approach(e) - previous_approach(e);
        if (std::isfinite(change) && std::abs(change) > 1e-13 && force(e) > 0 && previous_force(e) > 0) {
          stiffness(e) = (force(e) - previous_force(e)) / change;
        } else {
          stiffness(e) = penetration > 0 ? 1.5 * force(e) / penetration : 0;
        }
      }
      previous_approach = approach;
      previous_force = force;
      const Eigen::Vector2d residual(force.dot(cosine) - load, with_roll ? -force.dot(lever) : 0.0);
      const bool balanced = std::abs(residual(0)) <= options.force_tolerance * load &&
                            std::abs(residual(1)) <= options.force_tolerance * load * lever_scale;
      if (balanced && !first) {  // the pose moved: find the patches again
        pose.z += motion(0);
        pose.roll += motion(1);
        break;
      }
      if (balanced) {  // balanced at the pass's own pose (no motion): exact h, done
        for (std::size_t k = 0; k < count; ++k) {
          result.patches.push_back({patches[k], solutions[k]});
          result.lateral_force += force(static_cast<Eigen::Index>(k)) * std::sin(patches[k].frame.inclination);
        }
        result.vertical_residual = residual(0);
        result.roll_residual = residual(1);
        result.vertical_force = force.dot(cosine);
        result.pose = pose;
        return result;
      }
      first = false;
      Eigen::Matrix2d jacobian = Eigen::Matrix2d::Identity();
      jacobian(0, 0) = (stiffness.array() * cosine.array().square()).sum();
      if (with_roll) {
        const double coupled = (stiffness.array() * cosine.array() * lever.array()).sum();
        jacobian << jacobian(0, 0), coupled, -coupled, -(stiffness.array() * lever.array().square()).sum();
      }
      // Every loaded wheel must carry force, or the step is undetermined.
      for (Side side : sides) {
        double carried = 0;
        for (std::size_t k = 0; k < count; ++k) {
          if (patches[k].frame.side == side) carried += force(static_cast<Eigen::Index>(k));
        }
        if (carried <= 0 && with_roll) {
          result.status = EquilibriumStatus::lost_contact;
          result.message = std::string("the ") + to_string(side) + " wheel carries no load";
          result.pose = pose;
          return result;
        }
      }
      if (jacobian(0, 0) <= 0) {  // nothing in contact yet: press on by the deepest overlap
        motion(0) += std::abs(overlap(0)) + 1e-6;
        continue;
      }
      motion -= jacobian.partialPivLu().solve(residual);
    }
  }
  result.status = EquilibriumStatus::not_converged;
  result.message = "no equilibrium within " + std::to_string(options.max_iterations) + " steps";
  result.pose = pose;
  return result;
}

inline void check_equilibrium_input(double y, double yaw, double load, const char* load_name) {
  FASTNORM_CHECK(std::isfinite(y) && std::abs(y) < 0.03,
                 fastnorm::detail::describe("equilibrium: y must lie within ±0.03 m", y));
  FASTNORM_CHECK(std::isfinite(yaw) && std::abs(yaw) < 0.1,
                 fastnorm::detail::describe("equilibrium: yaw must lie within ±0.1 rad", yaw));
  FASTNORM_CHECK(std::isfinite(load) && load > 0,
                 fastnorm::detail::describe(std::string("equilibrium: ") + load_name + " must be positive (N)", load));
}

// A first guess of the elastic approach: 0.09 mm at 100 kN per wheel, scaled as Hertz (N^(2/3)).
inline double approach_guess(double wheel_load) { return 0.09e-3 * std::cbrt(std::pow(wheel_load / 1e5, 2)); }

}  // namespace detail

/// The wheelset at rest under `load` (N, on the wheelset centre, downward) at lateral shift
/// y (m) and yaw (rad): z and roll such that the rails carry the load with no roll moment.
/// Starts from the rigid two-wheel contact (rigid_contact_pose) lowered by a Hertz estimate.
/// @throws fastnorm::invalid_argument for bad y, yaw, load or options
inline Equilibrium solve_equilibrium(const Track& track, const Wheelset& wheelset, double y, double yaw, double load,
                                     const EquilibriumOptions& options = {}) {
  detail::check_equilibrium_input(y, yaw, load, "load");
  WheelsetPose start{y, 0, 0, yaw};
  if (options.start) {
    start.z = options.start->z;
    start.roll = options.start->roll;
  } else {
    start = rigid_contact_pose(track, wheelset, y, yaw, options.search);
    start.z += detail::approach_guess(load / 2);
  }
  return detail::find_equilibrium(track, wheelset, {Side::left, Side::right}, start, load, options);
}

/// CONTACT's single-wheel mode: vertical force `vertical_force` (N) on the wheel of `side`,
/// roll fixed (0 by default), z found; the other wheel is ignored.
/// @throws fastnorm::invalid_argument for bad y, yaw, force or options
inline Equilibrium solve_single_wheel(const Track& track, const Wheelset& wheelset, Side side, double y, double yaw,
                                      double vertical_force, const EquilibriumOptions& options = {}, double roll = 0) {
  detail::check_equilibrium_input(y, yaw, vertical_force, "vertical_force");
  FASTNORM_CHECK(std::isfinite(roll) && std::abs(roll) < 0.05,
                 fastnorm::detail::describe("solve_single_wheel: roll must lie within ±0.05 rad", roll));
  WheelsetPose start{y, 0, roll, yaw};
  start.z = options.start ? options.start->z
                          : smallest_gap(track, wheelset, side, start, options.search).gap +
                                detail::approach_guess(vertical_force);
  return detail::find_equilibrium(track, wheelset, {side}, start, vertical_force, options);
}

}  // namespace fastnorm::wheelrail
