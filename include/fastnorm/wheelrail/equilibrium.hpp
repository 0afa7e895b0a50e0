#pragma once
/// @file equilibrium.hpp
/// Static equilibrium of a loaded wheelset on the track (docs/wheel-rail.md §5): Newton–Raphson on the vertical position z and
/// roll φ with the normal forces of a chosen solver, and the single-wheel mode of
/// CONTACT's benchmark (vertical force prescribed on one wheel, roll 0).

#include <Eigen/LU>
#include <cmath>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "fastnorm/any_solver.hpp"
#include "fastnorm/solver_spec.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/wheelrail/contact_search.hpp"
#include "fastnorm/wheelrail/patch.hpp"

namespace fastnorm::wheelrail {

/// Settings of an equilibrium search.
struct EquilibriumOptions {
  SolverSpec<double> solver;       ///< the patch solver (NORM with default options by default)
  PatchGridOptions grid;           ///< patch grids (fixed after the first contact search)
  SearchOptions search;            ///< contact search and patch merging
  double young_modulus = 2.1e11;   ///< both bodies (Pa)
  double poisson_ratio = 0.3;      ///< both bodies
  double force_tolerance = 1e-6;   ///< |vertical residual| ≤ tol·load and |roll moment| ≤ tol·load·d
  int max_iterations = 40;         ///< Newton steps in all (each solves every patch once)
  /// A patch's stiffness dN/d(approach) before two solves give a secant: this factor times
  /// N / penetration (Hertz: N ∝ δ^1.5, so 1.5).
  double hertz_stiffness_factor = 1.5;
  /// Smallest change of a patch's approach (m) from which a secant stiffness is taken.
  double secant_min_change = 1e-13;
  /// First guess of a wheel's elastic approach at 100 kN (m), scaled as Hertz (N^(2/3)).
  double approach_at_100kN = 0.09e-3;
  /// Start from this z (and roll, with two wheels) instead of the rigid contact lowered by
  /// a Hertz estimate: e.g. an equilibrium found by a reduced solver, or the previous time
  /// step's, so that full NORM needs fewer solves. y and yaw come from the call.
  std::optional<WheelsetPose> start;

  /// @throws fastnorm::invalid_argument naming the offending field
  void validate() const {
    solver.validate();
    grid.validate();
    search.validate();
    Material<double>(young_modulus, poisson_ratio);  // checks both
    using fastnorm::detail::check_positive;
    check_positive(force_tolerance, "EquilibriumOptions: force_tolerance");
    check_positive(hertz_stiffness_factor, "EquilibriumOptions: hertz_stiffness_factor");
    check_positive(secant_min_change, "EquilibriumOptions: secant_min_change (m)");
    check_positive(approach_at_100kN, "EquilibriumOptions: approach_at_100kN (m)");
    FASTNORM_CHECK(max_iterations >= 1,
                   fastnorm::detail::describe("EquilibriumOptions: max_iterations must be >= 1", max_iterations));
    if (start) check_pose(*start, "EquilibriumOptions: start");
  }
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

/// The equilibrium search (docs/wheel-rail.md §5) for the wheels in `sides` carrying `load`;
/// roll is an unknown only when both wheels are loaded. Each outer pass finds the patches at
/// the current pose (exact h); within a pass a rigid motion (dz, dφ) changes the approach
/// of patch k by c_k·dz + L_k·dφ (docs/wheel-rail.md §5), so Newton runs on solves of
/// h_k − approach_k. A pass ends when the residual at its own pose is within tolerance, or
/// the pose moves. Solvers are kept for every grid size met and each patch keeps its
/// workspace while its grid stays the same, so later steps start warm.
template <typename Solver>
class EquilibriumSearch {
 public:
  EquilibriumSearch(const Track& track, const Wheelset& wheelset, std::vector<Side> sides, double load,
                    const EquilibriumOptions& options)
      : track_(track), wheelset_(wheelset), sides_(std::move(sides)), load_(load), options_(options),
        material_(options.young_modulus, options.poisson_ratio) {}

  Equilibrium run(WheelsetPose pose) {
    for (int pass = 1; result_.iterations < options_.max_iterations; ++pass) {
      if (!find_patches(pose, pass)) return finish(EquilibriumStatus::lost_contact, pose);
      switch (newton(pose)) {
        case Step::balanced: return finish(EquilibriumStatus::converged, pose);
        case Step::lost_contact: return finish(EquilibriumStatus::lost_contact, pose);
        case Step::solver_failed: return finish(EquilibriumStatus::solver_failed, pose);
        case Step::moved: break;
      }
    }
    result_.message = "no equilibrium within " + std::to_string(options_.max_iterations) + " steps";
    return finish(EquilibriumStatus::not_converged, pose);
  }

 private:
  enum class Step { balanced, moved, lost_contact, solver_failed };

  /// The patches at `pose` with their exact h, a solver and a workspace each; false (and a
  /// message) if a loaded wheel does not touch its rail.
  bool find_patches(const WheelsetPose& pose, int pass) {
    std::vector<ContactRegion> regions;
    for (Side side : sides_) {
      auto found = contact_regions(track_, wheelset_, side, pose, options_.search);
      if (found.empty()) {
        result_.message = std::string("the ") + to_string(side) + " wheel does not touch its rail";
        return false;
      }
      regions.insert(regions.end(), found.begin(), found.end());
    }
    std::vector<PatchFrame> frames;
    std::vector<PatchExtent> extents;
    for (const auto& region : regions) {
      frames.push_back(patch_frame(track_, region));
      extents.push_back(patch_extent(frames.back(), region));
    }
    // Element sizes from the regions of the first two passes (the first starts from a
    // guessed approach), then fixed so that the discretisation no longer changes.
    if (pass <= 2) std::tie(dx_, ds_) = element_sizes(extents, options_.grid);
    const std::vector<ContactPatch> previous = std::move(patches_);
    patches_.clear();
    solver_of_.clear();
    workspaces_.resize(regions.size());
    for (std::size_t k = 0; k < regions.size(); ++k) {
      const auto grid = patch_grid(extents[k], dx_, ds_);
      patches_.push_back({frames[k], grid, undeformed_distance(track_, wheelset_, pose, frames[k], grid)});
      solver_of_.push_back(solver_for(grid));
      if (k >= previous.size() || !same_grid(previous[k].grid, grid)) workspaces_[k].forget();
    }
    return true;
  }

  /// Newton steps on (dz, dφ) with the patches of this pass.
  Step newton(WheelsetPose& pose) {
    const auto count = static_cast<Eigen::Index>(patches_.size());
    Eigen::VectorXd cosine(count), lever(count), overlap(count);  // overlap: −min h, the rigid approach
    for (Eigen::Index k = 0; k < count; ++k) {
      const auto& frame = patches_[static_cast<std::size_t>(k)].frame;
      overlap(k) = -patches_[static_cast<std::size_t>(k)].undeformed_distance.minCoeff();
      const Eigen::Vector3d arm = frame.reference - wheelset_.centre(pose);
      cosine(k) = std::cos(frame.inclination);
      lever(k) = arm.y() * std::cos(frame.inclination) + arm.z() * std::sin(frame.inclination);
    }
    Eigen::Vector2d motion = Eigen::Vector2d::Zero();  // (dz, dφ)
    Eigen::VectorXd previous_approach = Eigen::VectorXd::Constant(count, std::nan(""));
    Eigen::VectorXd previous_force(count), force(count), stiffness(count);
    solutions_.resize(patches_.size());
    for (bool first = true; result_.iterations < options_.max_iterations; first = false) {
      ++result_.iterations;
      const Eigen::VectorXd approach = cosine * motion(0) + lever * motion(1);
      if (!solve_patches(approach, overlap, previous_approach, previous_force, force, stiffness)) return Step::solver_failed;
      previous_approach = approach;
      previous_force = force;
      const Eigen::Vector2d residual(force.dot(cosine) - load_, with_roll() ? -force.dot(lever) : 0.0);
      if (balanced(residual)) {
        if (first) {  // balanced at the pass's own pose (no motion): exact h, done
          store(force, cosine, residual);
          return Step::balanced;
        }
        pose.z += motion(0);  // the pose moved: find the patches again
        pose.roll += motion(1);
        return Step::moved;
      }
      if (!every_wheel_carries(force)) return Step::lost_contact;
      const Eigen::Matrix2d jacobian = newton_jacobian(stiffness, cosine, lever);
      if (jacobian(0, 0) <= 0) {  // nothing in contact yet: press on by the deepest overlap
        motion(0) += std::abs(overlap(0)) + 1e-6;
        continue;
      }
      motion -= jacobian.partialPivLu().solve(residual);
    }
    return Step::moved;  // out of steps: run() ends
  }

  /// Solves every patch at its approach; force and stiffness dN/d(approach) of each: secant
  /// on the last two solves, else hertz_stiffness_factor·N/penetration.
  bool solve_patches(const Eigen::VectorXd& approach, const Eigen::VectorXd& overlap,
                     const Eigen::VectorXd& previous_approach, const Eigen::VectorXd& previous_force,
                     Eigen::VectorXd& force, Eigen::VectorXd& stiffness) {
    for (std::size_t k = 0; k < patches_.size(); ++k) {
      const auto e = static_cast<Eigen::Index>(k);
      const Solver& solver = solvers_[solver_of_[k]];
      solutions_[k] = solver.solve(patches_[k].undeformed_distance.array() - approach(e),
                                   Loading<double>::approach(), workspaces_[k]);
      if (!solutions_[k].ok()) {
        result_.message = "patch " + std::to_string(k + 1) + ": " + solutions_[k].message;
        return false;
      }
      force(e) = solutions_[k].normal_force;
      const double penetration = approach(e) + overlap(e);
      const double change = approach(e) - previous_approach(e);
      if (std::isfinite(change) && std::abs(change) > options_.secant_min_change && force(e) > 0 &&
          previous_force(e) > 0) {
        stiffness(e) = (force(e) - previous_force(e)) / change;
      } else {
        stiffness(e) = penetration > 0 ? options_.hertz_stiffness_factor * force(e) / penetration : 0;
      }
    }
    return true;
  }

  Eigen::Matrix2d newton_jacobian(const Eigen::VectorXd& stiffness, const Eigen::VectorXd& cosine,
                                  const Eigen::VectorXd& lever) const {
    Eigen::Matrix2d jacobian = Eigen::Matrix2d::Identity();
    jacobian(0, 0) = (stiffness.array() * cosine.array().square()).sum();
    if (with_roll()) {
      const double coupled = (stiffness.array() * cosine.array() * lever.array()).sum();
      jacobian << jacobian(0, 0), coupled, -coupled, -(stiffness.array() * lever.array().square()).sum();
    }
    return jacobian;
  }

  bool balanced(const Eigen::Vector2d& residual) const {
    return std::abs(residual(0)) <= options_.force_tolerance * load_ &&
           std::abs(residual(1)) <= options_.force_tolerance * load_ * wheelset_.layout().taping_line_half_distance;
  }

  /// With two loaded wheels each must carry force, or the Newton step is undetermined.
  bool every_wheel_carries(const Eigen::VectorXd& force) {
    if (!with_roll()) return true;
    for (Side side : sides_) {
      double carried = 0;
      for (std::size_t k = 0; k < patches_.size(); ++k) {
        if (patches_[k].frame.side == side) carried += force(static_cast<Eigen::Index>(k));
      }
      if (carried <= 0) {
        result_.message = std::string("the ") + to_string(side) + " wheel carries no load";
        return false;
      }
    }
    return true;
  }

  void store(const Eigen::VectorXd& force, const Eigen::VectorXd& cosine, const Eigen::Vector2d& residual) {
    for (std::size_t k = 0; k < patches_.size(); ++k) {
      result_.patches.push_back({patches_[k], solutions_[k]});
      result_.lateral_force += force(static_cast<Eigen::Index>(k)) * std::sin(patches_[k].frame.inclination);
    }
    result_.vertical_residual = residual(0);
    result_.roll_residual = residual(1);
    result_.vertical_force = force.dot(cosine);
  }

  /// The solver of a grid's size (solvers do not depend on the grid's origin).
  std::size_t solver_for(const Grid<double>& grid) {
    for (std::size_t n = 0; n < solvers_.size(); ++n) {
      const auto& known = solvers_[n].grid();
      if (known.mx() == grid.mx() && known.my() == grid.my() && known.dx() == grid.dx() && known.dy() == grid.dy()) {
        return n;
      }
    }
    solvers_.emplace_back(options_.solver, grid, material_);
    return solvers_.size() - 1;
  }

  static bool same_grid(const Grid<double>& a, const Grid<double>& b) {
    return a.mx() == b.mx() && a.my() == b.my() && a.dx() == b.dx() && a.dy() == b.dy() && a.x0() == b.x0() &&
           a.y0() == b.y0();
  }

  bool with_roll() const { return sides_.size() == 2; }

  Equilibrium finish(EquilibriumStatus status, const WheelsetPose& pose) {
    result_.status = status;
    result_.pose = pose;
    return std::move(result_);
  }

  const Track& track_;
  const Wheelset& wheelset_;
  std::vector<Side> sides_;
  double load_;
  const EquilibriumOptions& options_;
  Material<double> material_;
  Equilibrium result_;
  double dx_ = 0, ds_ = 0;
  std::vector<ContactPatch> patches_;
  std::vector<Solution<double>> solutions_;
  std::vector<Solver> solvers_;
  std::vector<std::size_t> solver_of_;                  // per patch, into solvers_
  std::vector<typename Solver::Workspace> workspaces_;  // per patch
};

inline void check_load(double load, const char* load_name) {
  FASTNORM_CHECK(std::isfinite(load) && load > 0,
                 fastnorm::detail::describe(std::string("equilibrium: ") + load_name + " must be positive (N)", load));
}

// A first guess of the elastic approach of a wheel: approach_at_100kN, scaled as Hertz (N^(2/3)).
inline double approach_guess(double wheel_load, const EquilibriumOptions& options) {
  return options.approach_at_100kN * std::cbrt(std::pow(wheel_load / 1e5, 2));
}

}  // namespace detail

/// The wheelset at rest under `load` (N, on the wheelset centre, downward) at lateral shift
/// y (m) and yaw (rad): z and roll such that the rails carry the load with no roll moment.
/// Starts from the rigid two-wheel contact (rigid_contact_pose) lowered by a Hertz estimate.
/// `Solver` (AnySolver by default: instantiated only when this is called) is built from
/// (options.solver, grid, material) for each patch grid size.
/// @throws fastnorm::invalid_argument for bad y, yaw, load or options
template <typename Solver = AnySolver<double>>
Equilibrium solve_equilibrium(const Track& track, const Wheelset& wheelset, double y, double yaw, double load,
                              const EquilibriumOptions& options = {}) {
  check_pose({y, 0, 0, yaw}, "equilibrium");
  detail::check_load(load, "load");
  options.validate();
  WheelsetPose start{y, 0, 0, yaw};
  if (options.start) {
    start.z = options.start->z;
    start.roll = options.start->roll;
  } else {
    start = rigid_contact_pose(track, wheelset, y, yaw, options.search);
    start.z += detail::approach_guess(load / 2, options);
  }
  return detail::EquilibriumSearch<Solver>(track, wheelset, {Side::left, Side::right}, load, options).run(start);
}

/// CONTACT's single-wheel mode: vertical force `vertical_force` (N) on the wheel of `side`,
/// roll fixed (0 by default), z found; the other wheel is ignored.
/// @throws fastnorm::invalid_argument for bad y, yaw, roll, force or options
template <typename Solver = AnySolver<double>>
Equilibrium solve_single_wheel(const Track& track, const Wheelset& wheelset, Side side, double y, double yaw,
                               double vertical_force, const EquilibriumOptions& options = {}, double roll = 0) {
  check_pose({y, 0, roll, yaw}, "solve_single_wheel");
  detail::check_load(vertical_force, "vertical_force");
  options.validate();
  WheelsetPose start{y, 0, roll, yaw};
  start.z = options.start ? options.start->z
                          : smallest_gap(track, wheelset, side, start, options.search).gap +
                                detail::approach_guess(vertical_force, options);
  return detail::EquilibriumSearch<Solver>(track, wheelset, {side}, vertical_force, options).run(start);
}

}  // namespace fastnorm::wheelrail
