#pragma once
/// @file equilibrium.hpp
/// Static equilibrium of a loaded wheelset on the track (docs/wheel-rail.md §5): Newton–Raphson
/// on the vertical position z and roll φ with the patches of a WheelsetContact, and the
/// single-wheel mode of CONTACT's benchmark (vertical force prescribed on one wheel, roll 0).

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "fastnorm/any_solver.hpp"
#include "fastnorm/bases.hpp"
#include "fastnorm/reduced_solver.hpp"
#include "fastnorm/solver_spec.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/wheelrail/contact_search.hpp"
#include "fastnorm/wheelrail/patch.hpp"
#include "fastnorm/wheelrail/wheelset_contact.hpp"

namespace fastnorm::wheelrail {

/// Settings of an equilibrium search.
struct EquilibriumOptions {
  /// The contact model the search evaluates: its patch solver (NORM by default), element
  /// sizes, contact search and materials. Element sizes: contact.grid's element_length and
  /// element_width if both are given (m), else what `contact.grid.elements` gives across the
  /// largest patch near the equilibrium (docs/wheel-rail.md §5). The search sets the rest
  /// for its own needs: grids centred on the contact reference points (snap_to_lattice
  /// off), reduced solves that do not depend on their history (reduced_warm_start off), and
  /// each patch's stiffness on (the Newton Jacobian); reference_pose is not used.
  WheelsetContactOptions contact;
  double force_tolerance = 1e-6;   ///< |vertical residual| ≤ tol·load and |roll moment| ≤ tol·load·d
  int max_iterations = 40;         ///< contact evaluations in all (each solves every loaded patch once)
  /// First guess of a wheel's elastic approach at 100 kN (m), scaled as Hertz (N^(2/3)).
  double approach_at_100kN = 0.09e-3;
  /// Start from this z (and roll, with two wheels) instead of the rigid contact lowered by
  /// a Hertz estimate: e.g. an equilibrium found by a reduced solver, or the previous time
  /// step's, so that full NORM needs fewer solves. y and yaw come from the call.
  std::optional<WheelsetPose> start;

  /// @throws fastnorm::invalid_argument naming the offending field
  void validate() const {
    contact.validate();
    // Newton needs each pose's converged force, not a capped iterate that depends on the
    // steps before (docs/wheel-rail.md §9); a model given to the search has its cap lifted
    // while it runs instead (detail::ConvergedSolves).
    FASTNORM_CHECK(contact.warm_solve_iterations == 0,
                   fastnorm::detail::describe(
                       "EquilibriumOptions: contact.warm_solve_iterations must be 0 (Newton needs converged patch solves)",
                       contact.warm_solve_iterations));
    using fastnorm::detail::check_positive;
    check_positive(force_tolerance, "EquilibriumOptions: force_tolerance");
    check_positive(approach_at_100kN, "EquilibriumOptions: approach_at_100kN (m)");
    FASTNORM_CHECK(max_iterations >= 1,
                   fastnorm::detail::describe("EquilibriumOptions: max_iterations must be >= 1", max_iterations));
    if (start) check_pose(*start, "EquilibriumOptions: start");
  }
};

enum class EquilibriumStatus {
  not_solved,     ///< a default-constructed Equilibrium: no search has filled it
  converged,      ///< residuals below tolerance
  lost_contact,   ///< a wheel that must carry load has no contact with its rail
  not_converged,  ///< the step limit was reached
  solver_failed,  ///< a patch solve did not give a usable answer
  /// A wheel is at flange climb (docs/wheel-rail.md §5): at the equilibrium found, a
  /// patch's reference point lies on the steepest flank of its flange or beyond it
  /// (Wheelset::at_flange_climb; pose and patches are that equilibrium's); or no
  /// equilibrium was found and the search met such a contact, or, with two wheels, a
  /// flange contact so steep that its line of action passes the wheelset centre on the far
  /// side and lifts the other wheel (no patches then; the pose is the last one accepted).
  /// The message says which.
  flange_climb,
};

inline const char* to_string(EquilibriumStatus status) {
  switch (status) {
    case EquilibriumStatus::not_solved: return "not solved";
    case EquilibriumStatus::converged: return "converged";
    case EquilibriumStatus::lost_contact: return "lost contact";
    case EquilibriumStatus::not_converged: return "not converged";
    case EquilibriumStatus::solver_failed: return "solver failed";
    case EquilibriumStatus::flange_climb: return "flange climb";
  }
  return "unknown";
}

/// The loaded wheelset at rest. A search that ends not_converged gives its accepted pose of
/// smallest residual, with that pose's patches, forces and residuals.
struct Equilibrium {
  EquilibriumStatus status = EquilibriumStatus::not_solved;
  std::string message;
  WheelsetPose pose;                  ///< z and roll found (y, yaw as given)
  /// Every patch of the loaded wheel(s) at `pose`, as WheelsetContact gives it: exact h,
  /// pressures at approach 0, forces, stiffness (left wheel first, tread before flange).
  std::vector<PatchContact> patches;
  double vertical_force = 0;          ///< Σ N cos δ (N), what the rails carry
  double lateral_force = 0;           ///< Σ N sin δ (N): the lateral force needed to hold y
  double vertical_residual = 0;       ///< vertical_force − load (N)
  double roll_residual = 0;           ///< −Σ N·L about the wheelset centre (N·m); 0 in single-wheel mode
  int iterations = 0;                 ///< contact evaluations (solves of every loaded patch), the best pose's again included

  bool ok() const { return status == EquilibriumStatus::converged; }
};

/// The largest load an equilibrium takes (N): 1000 t, far beyond any wheelset's, and small
/// enough that the approach guess and the patch sizes stay finite.
inline constexpr double max_equilibrium_load = 1e7;

namespace detail {

/// Relative force tolerance of the first stage of the search, whose pose chooses the
/// element sizes (docs/wheel-rail.md §5); its solver is the elliptic basis, whose forces are
/// within 5e-4 of NORM's.
inline constexpr double sizing_tolerance = 1e-3;

// A first guess of the elastic approach of a wheel: approach_at_100kN, scaled as Hertz (N^(2/3)).
inline double approach_guess(double wheel_load, const EquilibriumOptions& options) {
  return options.approach_at_100kN * std::cbrt(std::pow(wheel_load / 1e5, 2));
}

/// A model's iteration budget and per-solve cap lifted for the scope of an equilibrium
/// search on it (Newton needs converged solves), and put back after, so that the model goes
/// on as a capped time loop from the equilibrium found.
template <typename Solver>
class ConvergedSolves {
 public:
  explicit ConvergedSolves(WheelsetContact<Solver>& model)
      : model_(model), budget_(model.iteration_budget()), cap_(model.options().warm_solve_iterations) {
    model_.set_iteration_budget(0);
    model_.set_warm_solve_iterations(0);
  }
  ~ConvergedSolves() {
    model_.set_iteration_budget(budget_);
    model_.set_warm_solve_iterations(cap_);
  }
  ConvergedSolves(const ConvergedSolves&) = delete;
  ConvergedSolves& operator=(const ConvergedSolves&) = delete;

 private:
  WheelsetContact<Solver>& model_;
  int budget_, cap_;
};

/// The equilibrium search (docs/wheel-rail.md §5) for the wheels in `sides` carrying `load`;
/// roll is an unknown only when both wheels are loaded. Newton on (z, roll) with a
/// WheelsetContact evaluated at every step: exact h at each pose, and the Jacobian from
/// the patches' stiffnesses dFn/dδ, since a rigid motion (dz, dφ) changes the approach of
/// patch k by c_k·dz + L_k·dφ. Two stages: the elliptic basis with element sizes from the
/// patches at the start, Newton to sizing_tolerance; then the chosen solver with sizes from
/// the patches at that pose, Newton to force_tolerance.
template <typename Solver>
class EquilibriumSearch {
 public:
  EquilibriumSearch(const Track& track, const Wheelset& wheelset, std::vector<Side> sides, double load,
                    const EquilibriumOptions& options)
      : track_(track), wheelset_(wheelset), sides_(std::move(sides)), load_(load), options_(options) {}

  Equilibrium run(WheelsetPose pose) {
    SolverSpec<double> sizing_solver = options_.contact.solver;  // its active-set options and table budget
    sizing_solver.kind = SolverSpec<double>::Kind::elliptic;
    if (!stage<SizingSolver>(sizing_solver, std::max(sizing_tolerance, options_.force_tolerance), pose, false) ||
        !stage<Solver>(options_.contact.solver, options_.force_tolerance, pose, true)) {
      return finish(failure_, pose);
    }
    return finish_balanced(pose);
  }

  /// The search on a given model, as it is (its element sizes, grids and starts): one stage
  /// to force_tolerance, every pose evaluated from the model's state before the search; the
  /// model's state is then that of its evaluation at the pose returned.
  template <typename Model>
  Equilibrium run_on(Model& model, WheelsetPose pose) {
    FromCommitted<Model> trials{model};
    if (!settle(trials, options_.force_tolerance, pose, true)) return finish(failure_, pose);
    return finish_balanced(pose);
  }

 private:
  /// How a Newton stage ended. force_jump: steps too short to be checked (unchecked_length)
  /// no longer lower the residual, because the model's force jumps across the load there
  /// (a reduced basis's, as elements join its contact set).
  enum class Step { balanced, out_of_steps, lost_contact, solver_failed, force_jump };

  /// A pose the Newton search accepted, and its residual (vertical N, roll moment N·m).
  struct Accepted {
    WheelsetPose pose;
    Eigen::Vector2d residual;
  };

  /// A model evaluated from its state at construction every time: the search's trial poses
  /// leave no trace in each other's answers (WheelsetContact::history and restore, §9), so a
  /// model that starts warm answers as a function of the pose during the search.
  template <typename Model>
  struct FromCommitted {
    Model& model;
    typename Model::History committed = model.history();
    const WheelsetContactResult& evaluate(const WheelsetPose& pose) {
      model.restore(committed);
      return model.evaluate(pose);
    }
    const WheelContact& evaluate(const WheelsetPose& pose, Side side) {
      model.restore(committed);
      return model.evaluate(pose, side);
    }
  };

  /// The first stage's solver: the elliptic basis, of the same family as `Solver` (a program
  /// that names its solver does not compile AnySolver).
  using SizingSolver = std::conditional_t<std::is_same_v<Solver, AnySolver<double>>, AnySolver<double>,
                                          ReducedSolver<EllipticBasis, double>>;

  /// One stage: element sizes from the patches at `pose`, a model with `solver`, Newton to
  /// `tolerance`; `pose` ends at the last accepted pose. False (and failure_ set) when the
  /// stage did not balance; after the `last` stage the result holds its patches.
  template <typename StageSolver>
  bool stage(const SolverSpec<double>& solver, double tolerance, WheelsetPose& pose, bool last) {
    const auto sizes =
        detail::element_sizes_at(track_, wheelset_, pose, sides_, options_.contact.search, options_.contact.grid);
    if (sizes.untouched) {
      result_.message = std::string("the ") + to_string(*sizes.untouched) + " wheel does not touch its rail";
      failure_ = EquilibriumStatus::lost_contact;
      return false;
    }
    WheelsetContact<StageSolver> model(track_, wheelset_, contact_options(sizes, solver));
    return settle(model, tolerance, pose, last);
  }

  /// Newton on `model` to `tolerance`; false (and failure_ set) when it did not balance.
  /// When it did not converge, `pose` is then the accepted pose of smallest residual and the
  /// result holds its patches and residuals.
  template <typename Model>
  bool settle(Model& model, double tolerance, WheelsetPose& pose, bool last) {
    const Step outcome = newton(model, pose, tolerance);
    if (outcome == Step::balanced) {
      if (last) store();  // the patches, which the model holds
      return true;
    }
    if (!climb_.empty()) {
      result_.message = climb_ + "; no equilibrium found";
      failure_ = EquilibriumStatus::flange_climb;
    } else {
      switch (outcome) {
        case Step::lost_contact: failure_ = EquilibriumStatus::lost_contact; break;
        case Step::solver_failed: failure_ = EquilibriumStatus::solver_failed; break;
        case Step::force_jump: failure_ = EquilibriumStatus::not_converged; break;
        default:
          result_.message = "no equilibrium within " + std::to_string(options_.max_iterations) + " steps";
          failure_ = EquilibriumStatus::not_converged;
      }
    }
    if (failure_ == EquilibriumStatus::not_converged && best_) store_best(model, pose);
    return false;
  }

  /// The result at the accepted pose of smallest residual (`pose` becomes it): evaluated
  /// once more (counted in iterations), since the last evaluation may have been a trial.
  template <typename Model>
  void store_best(Model& model, WheelsetPose& pose) {
    pose = best_->pose;
    const std::string message = result_.message;
    ++result_.iterations;
    if (evaluate(model, pose)) return;  // it was evaluated before; a model that now fails keeps the message
    result_.message = message;
    store();
  }

  WheelsetContactOptions contact_options(const detail::ElementSizes& sizes, const SolverSpec<double>& solver) const {
    WheelsetContactOptions contact = options_.contact;
    contact.solver = solver;
    contact.grid.element_length = sizes.length;
    contact.grid.element_width = sizes.width;
    contact.reference_pose.reset();
    contact.snap_to_lattice = false;     // grids centred on the contact reference points, as CONTACT's
    contact.reduced_warm_start = false;  // a reduced answer that does not depend on the path to it
    contact.stiffness = true;            // the Newton Jacobian
    contact.distance_everywhere = true;  // the patches' h reported on the whole grid
    return contact;
  }

  /// Newton steps on (z, roll) until the residuals at an evaluated pose are within
  /// `tolerance`; `pose` ends at the last accepted pose. Damped (docs/wheel-rail.md §5): a
  /// step moves no point of the wheelset by more than a trust length and, unless shorter
  /// than unchecked_length, is accepted only when it lowers the scaled residual. The first Jacobian comes from the patches'
  /// stiffnesses, which see the approach but not the contact point running along a curved
  /// profile: at the flange root a full step can land millimetres off. So a rejected step
  /// (more residual, a loaded wheel without contact, or a failed solve at the trial pose)
  /// returns to the accepted pose with a quarter of the length and from then on takes the
  /// Jacobian from finite differences at each accepted pose.
  template <typename Model>
  Step newton(Model& model, WheelsetPose& pose, double tolerance) {
    best_.reset();
    if (result_.iterations >= options_.max_iterations) return Step::out_of_steps;
    ++result_.iterations;
    if (const auto failed = evaluate(model, pose)) return *failed;
    if (!every_wheel_carries()) return Step::lost_contact;
    best_ = Accepted{pose, residual_};
    double trust = initial_trust();
    bool differences = false;
    int unchecked_without_gain = 0;  // accepted unchecked steps in a row that left the best residual
                                     // within a tenth (a search that converges, even slowly, lowers it)
    while (!balanced(residual_, tolerance)) {
      const Eigen::Vector2d residual = residual_;  // at the accepted pose
      Eigen::Matrix2d jacobian = newton_jacobian();
      if (differences) {
        if (const auto failed = difference_jacobian(model, pose, residual, jacobian)) return *failed;
      } else if (jacobian(0, 0) <= 0) {  // nothing pressed yet: press on by the deepest overlap
        if (result_.iterations >= options_.max_iterations) return Step::out_of_steps;
        double deepest = 0;
        for (const PatchContact* patch : patches_) deepest = std::max(deepest, patch->approach);
        pose.z += deepest + 1e-6;
        ++result_.iterations;
        if (const auto failed = evaluate(model, pose)) return *failed;
        continue;
      }
      if (result_.iterations >= options_.max_iterations) return Step::out_of_steps;
      Eigen::Vector2d motion = -jacobian.partialPivLu().solve(residual);
      const double length = std::max(std::abs(motion(0)), std::abs(motion(1)) * half_gauge());
      if (!(length > 0)) return Step::out_of_steps;
      if (length > trust) motion *= trust / length;
      WheelsetPose trial = pose;
      trial.z += motion(0);
      trial.roll += motion(1);
      ++result_.iterations;
      const auto failed = evaluate(model, trial);
      Step rejection = Step::out_of_steps;  // more residual
      if (failed) {
        rejection = *failed;
      } else if (!every_wheel_carries()) {
        rejection = Step::lost_contact;
      } else if (length <= unchecked_length || scaled_norm(residual_) < scaled_norm(residual)) {
        const WheelsetPose before = pose;
        pose = trial;
        trust = std::max(trust, 2 * std::min(length, trust));
        result_.message.clear();
        const bool gain = scaled_norm(residual_) <= 0.9 * scaled_norm(best_->residual);
        unchecked_without_gain = length <= unchecked_length && !gain ? unchecked_without_gain + 1 : 0;
        if (scaled_norm(residual_) < scaled_norm(best_->residual)) best_ = Accepted{pose, residual_};
        if (unchecked_without_gain == stalled_steps) {
          result_.message = force_jump_message({before, residual}, {pose, residual_});
          return Step::force_jump;
        }
        continue;
      }
      trust = std::min(length, trust) / 4;
      if (trust < smallest_trust) return rejection;
      differences = true;
      residual_ = residual;  // the accepted pose's; the differences evaluate around it
    }
    result_.message.clear();
    return Step::balanced;
  }

  /// ∂R/∂(z, roll) at `pose` (whose residual is `residual`) by forward differences, two
  /// evaluations: a drop of difference_length, and a roll lowering the less loaded wheel
  /// by as much at the taping line, so that neither loses contact.
  template <typename Model>
  std::optional<Step> difference_jacobian(Model& model, const WheelsetPose& pose,
                                          const Eigen::Vector2d& residual, Eigen::Matrix2d& jacobian) {
    const double roll_sign = with_roll() && load_on(Side::right) < load_on(Side::left) ? 1.0 : -1.0;
    const Eigen::Vector2d moves(difference_length, roll_sign * difference_length / half_gauge());
    for (int column = 0; column < (with_roll() ? 2 : 1); ++column) {
      if (result_.iterations >= options_.max_iterations) return Step::out_of_steps;
      WheelsetPose moved = pose;
      (column == 0 ? moved.z : moved.roll) += moves(column);
      ++result_.iterations;
      if (const auto failed = evaluate(model, moved)) return failed;
      jacobian.col(column) = (residual_ - residual) / moves(column);
    }
    return std::nullopt;
  }

  /// The finite-difference step (m).
  static constexpr double difference_length = 1e-6;

  /// Σ Fn of the patches of `side` at the last evaluation (N).
  double load_on(Side side) const {
    double carried = 0;
    for (const PatchContact* patch : patches_) {
      if (patch->patch.frame.side == side) carried += patch->normal_force;
    }
    return carried;
  }

  /// The first trust length (m): four times the first guess of a wheel's approach.
  double initial_trust() const { return 4 * approach_guess(load_ / static_cast<double>(sides_.size()), options_); }
  /// Below this trust length (m) the search gives up.
  static constexpr double smallest_trust = 1e-9;
  /// Steps up to this length (m) are taken whatever the residual there: within it the
  /// profiles' curvature hardly moves the contact, and a reduced solver's force, which
  /// jumps as elements join its contact set (up to about 5e-4 of the load at 20 elements),
  /// would otherwise stop a search that full Newton steps finish.
  static constexpr double unchecked_length = 1e-6;
  /// Unchecked steps in a row that do not lower the best residual by a tenth, after which
  /// the search ends at a force jump.
  static constexpr int stalled_steps = 3;

  /// Why the search ended at a jump of the model's force: the residuals at the last two
  /// accepted poses, and how far apart these are (at the taping line).
  std::string force_jump_message(const Accepted& before, const Accepted& after) const {
    using fastnorm::detail::to_text;
    const double apart = std::max(std::abs(after.pose.z - before.pose.z),
                                  std::abs(after.pose.roll - before.pose.roll) * half_gauge());
    return "the model's forces jump across the load: poses " + to_text(apart * 1e9) +
           " nm apart leave vertical residuals of " + to_text(before.residual(0)) + " N and " +
           to_text(after.residual(0)) + " N (roll moments " + to_text(before.residual(1)) + " and " +
           to_text(after.residual(1)) + " N m); no pose of this discrete model carries the load within force_tolerance " +
           to_text(options_.force_tolerance) + " of it (the accepted pose of smallest residual is given)";
  }

  double half_gauge() const { return wheelset_.layout().taping_line_half_distance; }

  /// |R| scaled as the tolerance: vertical by the load, roll moment by load × d.
  double scaled_norm(const Eigen::Vector2d& residual) const {
    return std::hypot(residual(0) / load_, residual(1) / (load_ * half_gauge()));
  }

  /// The loaded wheels' patches at `pose` and the residuals; a failure step, if any.
  template <typename Model>
  std::optional<Step> evaluate(Model& model, const WheelsetPose& pose) {
    patches_.clear();
    const WheelsetContactResult* both = with_roll() ? &model.evaluate(pose) : nullptr;
    for (Side side : sides_) {
      const WheelContact& wheel = both ? both->wheel(side) : model.evaluate(pose, side);
      if (wheel.patches.empty()) {
        result_.message = std::string("the ") + to_string(side) + " wheel does not touch its rail";
        return Step::lost_contact;
      }
      for (const auto& patch : wheel.patches) patches_.push_back(&patch);
    }
    const auto count = static_cast<Eigen::Index>(patches_.size());
    force_.resize(count), stiffness_.resize(count), cosine_.resize(count), lever_.resize(count);
    for (Eigen::Index k = 0; k < count; ++k) {
      const PatchContact& patch = *patches_[static_cast<std::size_t>(k)];
      if (!patch.ok()) {
        result_.message = "patch " + std::to_string(k + 1) + ": " + patch.solution.message;
        return Step::solver_failed;
      }
      const PatchFrame& frame = patch.patch.frame;
      const Eigen::Vector3d arm = frame.reference - wheelset_.centre(pose);
      force_(k) = patch.normal_force;
      stiffness_(k) = patch.stiffness;
      cosine_(k) = std::cos(frame.inclination);
      lever_(k) = arm.y() * std::cos(frame.inclination) + arm.z() * std::sin(frame.inclination);
      if (wheelset_.at_flange_climb(patch.profile_y)) {
        climb_ = on_flange(patch);
      } else if (with_roll() && force_(k) > 0 && lever_(k) * side_sign(frame.side) < 0) {
        climb_ = std::string("the ") + to_string(frame.side) + " wheel's flange contact (contact angle " +
                 fastnorm::detail::to_text(patch.contact_angle) +
                 " rad) has its line of action beyond the wheelset centre and lifts the other wheel";
      }
    }
    residual_ = {force_.dot(cosine_) - load_, with_roll() ? -force_.dot(lever_) : 0.0};
    return std::nullopt;
  }

  Eigen::Matrix2d newton_jacobian() const {
    Eigen::Matrix2d jacobian = Eigen::Matrix2d::Identity();
    jacobian(0, 0) = (stiffness_.array() * cosine_.array().square()).sum();
    if (with_roll()) {
      const double coupled = (stiffness_.array() * cosine_.array() * lever_.array()).sum();
      jacobian << jacobian(0, 0), coupled, -coupled, -(stiffness_.array() * lever_.array().square()).sum();
    }
    return jacobian;
  }

  bool balanced(const Eigen::Vector2d& residual, double tolerance) const {
    return std::abs(residual(0)) <= tolerance * load_ &&
           std::abs(residual(1)) <= tolerance * load_ * half_gauge();
  }

  /// With two loaded wheels each must carry force, or the Newton step is undetermined.
  bool every_wheel_carries() {
    if (!with_roll()) return true;
    for (Side side : sides_) {
      if (load_on(side) <= 0) {
        result_.message = std::string("the ") + to_string(side) + " wheel carries no load";
        return false;
      }
    }
    return true;
  }

  /// The last evaluation's patches and sums into the result.
  void store() {
    for (const PatchContact* patch : patches_) {
      result_.patches.push_back(*patch);
      result_.lateral_force += patch->normal_force * std::sin(patch->patch.frame.inclination);
    }
    result_.vertical_force = force_.dot(cosine_);
    result_.vertical_residual = residual_(0);
    result_.roll_residual = residual_(1);
  }

  bool with_roll() const { return sides_.size() == 2; }

  std::string on_flange(const PatchContact& patch) const {
    return std::string("the ") + to_string(patch.patch.frame.side) + " wheel's contact lies at y_w = " +
           fastnorm::detail::to_text(patch.profile_y * 1e3) + " mm, on or past the steepest flank of its flange (from " +
           fastnorm::detail::to_text(wheelset_.flange_climb_point() * 1e3) + " mm): flange climb";
  }

  /// Balanced at `pose`: converged, or at flange climb when a patch lies on the flank.
  Equilibrium finish_balanced(const WheelsetPose& pose) {
    for (const PatchContact& patch : result_.patches) {
      if (wheelset_.at_flange_climb(patch.profile_y)) {
        result_.message = on_flange(patch);
        return finish(EquilibriumStatus::flange_climb, pose);
      }
    }
    return finish(EquilibriumStatus::converged, pose);
  }

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
  Equilibrium result_;
  EquilibriumStatus failure_ = EquilibriumStatus::not_converged;  // why a stage did not balance
  std::string climb_;  // what the search last saw of flange climb (empty: nothing)
  // The last evaluation: the loaded wheels' patches (in the model's result), their forces,
  // stiffnesses dFn/dδ, cos δ and lever arms L, and the residuals (vertical, roll).
  std::vector<const PatchContact*> patches_;
  Eigen::VectorXd force_, stiffness_, cosine_, lever_;
  Eigen::Vector2d residual_ = Eigen::Vector2d::Zero();
  std::optional<Accepted> best_;  // the accepted pose of smallest scaled residual in the current stage
};

/// Where the two-wheel search starts: options.start's z and roll, or the rigid contact at
/// (y, yaw) lowered by the approach guess.
inline WheelsetPose equilibrium_start(const Track& track, const Wheelset& wheelset, double y, double yaw, double load,
                                      const EquilibriumOptions& options, const SearchOptions& search) {
  if (options.start) return {y, options.start->z, options.start->roll, yaw};
  WheelsetPose start = rigid_contact_pose(track, wheelset, y, yaw, search);
  start.z += approach_guess(load / 2, options);
  return start;
}

inline void check_load(double load, const char* load_name) {
  FASTNORM_CHECK(std::isfinite(load) && load > 0 && load <= max_equilibrium_load,
                 fastnorm::detail::describe(std::string("equilibrium: ") + load_name + " must lie in (0, " +
                                                fastnorm::detail::to_text(max_equilibrium_load) + "] N",
                                            load));
}

/// The arguments of the two-wheel equilibrium, checked by name.
inline void check_two_wheel_input(double y, double yaw, double load, const EquilibriumOptions& options) {
  check_pose({y, 0, 0, yaw}, "equilibrium");
  check_load(load, "load");
  options.validate();
}

}  // namespace detail

/// The wheelset at rest under `load` (N, on the wheelset centre, downward) at lateral shift
/// y (m) and yaw (rad): z and roll such that the rails carry the load with no roll moment.
/// Starts from the rigid two-wheel contact (rigid_contact_pose) lowered by a Hertz estimate.
/// `Solver` is the solver type of the WheelsetContact<Solver> that the search evaluates:
/// AnySolver by default (every kind of options.contact.solver), or a named one such as
/// NormSolver<>, whose program then compiles that solver and the elliptic basis of the
/// first stage only.
/// @throws fastnorm::invalid_argument for bad y, yaw, load or options
template <typename Solver = AnySolver<double>>
Equilibrium solve_equilibrium(const Track& track, const Wheelset& wheelset, double y, double yaw, double load,
                              const EquilibriumOptions& options = {}) {
  detail::check_two_wheel_input(y, yaw, load, options);
  check_spec_for<Solver>(options.contact.solver, "EquilibriumOptions: contact.solver");
  const WheelsetPose start = detail::equilibrium_start(track, wheelset, y, yaw, load, options, options.contact.search);
  return detail::EquilibriumSearch<Solver>(track, wheelset, {Side::left, Side::right}, load, options).run(start);
}

/// The same on a given contact model, as it is: its solver, element sizes, lattice grids and
/// starts (options.contact is not used; the model's options must compute the stiffness),
/// so that the pose found is in equilibrium for that model itself, e.g. the first pose of
/// a time integration with it (docs/wheel-rail.md §5). One Newton stage to
/// options.force_tolerance. Every pose tried is evaluated from the model's state before the
/// search (history() and restore()), so that a warm model's force is a function of the pose
/// during the search; the model's state is then that of its evaluation at the pose returned
/// (model.reset() forgets it). The model's iteration budget and per-solve cap are lifted
/// during the search (its solves converge) and put back after.
/// @throws fastnorm::invalid_argument for bad y, yaw, load or options, or a model without
///         stiffness
template <typename Solver>
Equilibrium solve_equilibrium(WheelsetContact<Solver>& model, double y, double yaw, double load,
                              const EquilibriumOptions& options = {}) {
  detail::check_two_wheel_input(y, yaw, load, options);
  FASTNORM_CHECK(model.options().stiffness,
                 "equilibrium: the model's options.stiffness must be on (the Newton Jacobian needs it)");
  const detail::ConvergedSolves<Solver> converged(model);
  const WheelsetPose start = detail::equilibrium_start(model.track(), model.wheelset(), y, yaw, load, options,
                                                       model.options().search);
  return detail::EquilibriumSearch<Solver>(model.track(), model.wheelset(), {Side::left, Side::right}, load, options)
      .run_on(model, start);
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
  check_spec_for<Solver>(options.contact.solver, "EquilibriumOptions: contact.solver");
  WheelsetPose start{y, 0, roll, yaw};
  start.z = options.start ? options.start->z
                          : smallest_gap(track, wheelset, side, start, options.contact.search).gap +
                                detail::approach_guess(vertical_force, options);
  return detail::EquilibriumSearch<Solver>(track, wheelset, {side}, vertical_force, options).run(start);
}

}  // namespace fastnorm::wheelrail
