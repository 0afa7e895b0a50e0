#pragma once
/// @file wheelset_contact_result.hpp
/// What the wheelset contact model of the time loop returns (docs/wheel-rail.md §9):
/// per patch its frame, grid, pressures, forces and stiffness, per wheel and wheelset the
/// sums, and the step status.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "fastnorm/solution.hpp"
#include "fastnorm/tangential_problem.hpp"
#include "fastnorm/wheelrail/patch.hpp"

namespace fastnorm::wheelrail {

/// A wheel's place in the results, as in WheelsetContactResult::wheels and the bindings:
/// 0 the left wheel, 1 the right.
inline std::size_t wheel_index(Side side) { return side == Side::right ? 1 : 0; }

/// How a patch relates to the patches of the same wheel at the previous call.
enum class PatchHistory {
  continued,  ///< the continuation of one previous patch (warm start from its contact set)
  appeared,   ///< no previous patch near it (cold start)
  merged,     ///< two or more previous patches became this one (started from their sets)
  split,      ///< one previous patch became this and another (started from its set)
};

inline const char* to_string(PatchHistory history) {
  switch (history) {
    case PatchHistory::continued: return "continued";
    case PatchHistory::appeared: return "appeared";
    case PatchHistory::merged: return "merged";
    case PatchHistory::split: return "split";
  }
  return "unknown";
}

/// One contact patch at the pose of the call. Track frame: x forward, y right, z down (m).
struct PatchContact {
  ContactPatch patch{{}, Grid<double>(1, 1, 1, 1), {}};  ///< frame, grid and undeformed distance h (approach 0)
  Solution<double> solution;    ///< pressures on patch.grid (Pa), contact set, status
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< the contact reference point (weighted centre on the rail)
  double profile_y = 0;         ///< the wheel profile coordinate y_w of the reference point, weighted alike (m)
  Eigen::Vector3d pressure_centre = Eigen::Vector3d::Zero();  ///< centroid of the pressure in the tangent plane
  double normal_force = 0;      ///< Fn (N)
  /// The contact force on the wheel (N): −Fn·n (n into the rail, PatchFrame::normal) plus
  /// creep_force.
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  /// Its moment about the wheelset centre (N·m): (pressure_centre − C) × (−Fn·n), plus
  /// (P_ref − C) × creep_force − Mn·n with the creep.
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  /// With velocities (docs/wheel-rail.md §10; else zero): the creepages of the rail against
  /// the wheel at the reference point P_ref, which is the spin centre.
  Creepage<double> creepage;
  /// With velocities: the tractions on the rail in the patch frame (x, s), their forces
  /// Fx = force_x, Fs = force_y and spin moment Mn = spin_moment about P_ref, the adhesion
  /// and slip areas (FASTSIM); without, empty and not_solved.
  TangentialSolution<double> traction;
  /// The creep force on the wheel, −(Fx·e_x + Fs·t_s) (N, track frame).
  Eigen::Vector3d creep_force = Eigen::Vector3d::Zero();
  /// With velocities and options.creep.sensitivities: d(Fx, Fs, Mn)/d(ξ, η, φ) of `traction`
  /// (rows N, N, N·m; columns per unit creepage, φ in rad/m; fastsim.hpp, CreepJacobian);
  /// NaN otherwise.
  Eigen::Matrix3d creep_jacobian = Eigen::Matrix3d::Constant(std::nan(""));
  double contact_angle = 0;     ///< of the normal from the vertical, + leaning to the track centre (rad)
  double approach = 0;          ///< the rigid interpenetration −min h (m)
  Eigen::Index contact_elements = 0;
  double max_pressure = 0;      ///< Pa
  /// dFn/dδ (N/m): the normal stiffness of the discrete model at the final contact set
  /// (δ the approach along n); NaN when options.stiffness is off.
  double stiffness = std::nan("");
  PatchHistory history = PatchHistory::appeared;

  bool ok() const { return solution.ok(); }
};

/// Whether a step (an evaluate) gave every patch a usable answer, and if not, the first
/// patch that failed and why. Default-constructed: not_solved (nothing evaluated yet).
struct StepStatus {
  enum class Code {
    not_solved,    ///< no evaluate has filled it
    ok,            ///< every patch solved with a usable answer (Solution::ok)
    patch_failed,  ///< a patch solve did not give a usable answer: `side`, `patch`, `solver_status`
  };
  Code code = Code::not_solved;
  Side side = Side::left;     ///< the wheel of the failed patch
  int patch = -1;             ///< its index in that wheel's patches (tread first); -1 if none failed
  Status solver_status = Status::not_solved;  ///< the failed patch's Solution::status
  /// Empty when ok; else e.g. "right wheel, patch 1 of 2: numerical issue: …".
  std::string message;

  bool ok() const { return code == Code::ok; }

  /// Ok for `wheel`, the message's storage kept (so that a time loop's step allocates
  /// nothing for it).
  void set_ok(Side wheel) {
    code = Code::ok, side = wheel, patch = -1, solver_status = Status::not_solved;
    message.clear();
  }
  /// Patch `index` of `count` of `wheel` failed with `status` and the solver's `detail`:
  /// the message written into the storage it has.
  void set_patch_failed(Side wheel, int index, std::size_t count, Status status, const std::string& detail) {
    code = Code::patch_failed, side = wheel, patch = index, solver_status = status;
    message.clear();
    message.append(to_string(wheel)).append(" wheel, patch ").append(std::to_string(index)).append(" of ");
    message.append(std::to_string(count)).append(": ").append(fastnorm::to_string(status));
    if (!detail.empty()) message.append(": ").append(detail);
  }
};

inline const char* to_string(StepStatus::Code code) {
  switch (code) {
    case StepStatus::Code::not_solved: return "not solved";
    case StepStatus::Code::ok: return "ok";
    case StepStatus::Code::patch_failed: return "patch failed";
  }
  return "unknown";
}

/// Wall-clock time of the three stages of one wheel's evaluation (s).
struct StageTimes {
  double search = 0;    ///< contact search, patch frames and grids
  double distance = 0;  ///< undeformed distance h on the grids
  double solve = 0;     ///< normal solves and stiffness
  double tangential = 0;  ///< creepages and creep forces (0 without velocities)
};

/// One wheel at the pose of the call.
struct WheelContact {
  Side side = Side::right;
  std::vector<PatchContact> patches;  ///< by increasing y_w (tread first, flange last)
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   ///< Σ patch forces (N)
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();  ///< Σ patch moments about the wheelset centre (N·m)
  double normal_force = 0;            ///< Σ Fn (N)
  int vanished = 0;                   ///< previous patches with no successor (contact lost there)
  /// A patch's reference point lies on the steepest flank of the flange or beyond it
  /// (Wheelset::at_flange_climb): the wheel is at flange climb.
  bool flange_climb = false;
  StageTimes times;
  /// The work its patch solves spent: the sum of their Solution::iterations (active-set
  /// iterations; CG's for CG), what WheelsetContact::set_iteration_budget counts.
  int iterations = 0;
  StepStatus status;  ///< this wheel's: ok, or its first failed patch

  bool ok() const { return status.ok(); }
};

/// Both wheels at one pose.
struct WheelsetContactResult {
  WheelsetPose pose;
  std::array<WheelContact, 2> wheels;                ///< left, right
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   ///< on the wheelset (N)
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();  ///< about its centre (N·m)
  StepStatus status;  ///< ok, or the first failed patch (left wheel first)
  int iterations = 0;  ///< the work of the step: both wheels' `iterations`

  const WheelContact& wheel(Side side) const { return wheels[wheel_index(side)]; }
  /// Every patch solved with a usable answer.
  bool ok() const { return status.ok(); }
  /// A wheel at flange climb.
  bool flange_climb() const { return wheels[0].flange_climb || wheels[1].flange_climb; }
};

}  // namespace fastnorm::wheelrail
