#pragma once
/// @file wheelset_contact.hpp
/// Contact in the time loop (docs/wheel-rail.md §9): a wheelset contact model that a
/// vehicle-dynamics code calls at every step with the wheelset's pose and that returns
/// every wheel's patches, forces, moments and normal stiffness. It keeps its state between
/// calls: fixed element sizes, one solver per grid size (influence and segment tables
/// reused), and per patch the solver workspace and the previous contact set, shifted onto
/// the new grid to start the next solve.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fastnorm/any_solver.hpp"
#include "fastnorm/solver_from_spec.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/solver_spec.hpp"
#include "fastnorm/wheelrail/contact_search.hpp"
#include "fastnorm/wheelrail/creepage.hpp"
#include "fastnorm/wheelrail/model_storage.hpp"
#include "fastnorm/wheelrail/patch_lattice.hpp"
#include "fastnorm/wheelrail/patch.hpp"
#include "fastnorm/wheelrail/patch_creep.hpp"
#include "fastnorm/wheelrail/undeformed_distance.hpp"
#include "fastnorm/wheelrail/wheelset_contact_options.hpp"
#include "fastnorm/wheelrail/wheelset_contact_result.hpp"

namespace fastnorm::wheelrail {

namespace detail {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The element sizes (dx, ds) that `grid` asks for at `pose` (given sizes, or `elements`
/// across the largest patch of the wheels of `sides`), or the first of `sides` whose wheel
/// does not touch its rail there. The one place element sizes are chosen: by the model at
/// its reference pose and by each stage of the equilibrium.
struct ElementSizes {
  double length = 0, width = 0;  ///< dx, ds (m); 0 when a wheel does not touch
  std::optional<Side> untouched;
};

inline ElementSizes element_sizes_at(const Track& track, const Wheelset& wheelset, const WheelsetPose& pose,
                                     const std::vector<Side>& sides, const SearchOptions& search,
                                     const PatchGridOptions& grid) {
  if (grid.element_length > 0) return {grid.element_length, grid.element_width, std::nullopt};
  std::vector<PatchExtent> extents;
  for (Side side : sides) {
    const auto regions = contact_regions(track, wheelset, side, pose, search);
    if (regions.empty()) return {0, 0, side};
    for (const auto& region : regions) extents.push_back(patch_extent(patch_frame(track, region), region));
  }
  const auto [length, width] = element_sizes(extents, grid);
  return {length, width, std::nullopt};
}

}  // namespace detail

/// The contact model of one wheelset on its track (docs/wheel-rail.md §9).
///
/// **Example**
/// @code
/// fastnorm::wheelrail::WheelsetContactOptions options;
/// options.solver = fastnorm::SolverSpec<>::parse("elliptic");
/// fastnorm::wheelrail::WheelsetContact<> contact(track, wheelset, options);
/// for (each time step) {
///   const auto& result = contact.evaluate(pose);   // y, z, roll, yaw
///   apply(result.force, result.moment);            // on the wheelset, track frame
/// }
/// @endcode
///
/// A copy is a model of its own (its patches, workspaces and history copied) that shares the
/// original's solvers and their read-only tables (influence and segment tables; safe to read
/// from several threads): the way to make the models of a vehicle's wheelsets that have the
/// same track, wheelset and options. Copies of one model hold those tables once, where models
/// built one by one hold one set each (elliptic: 25 MB for four models against 87 MB;
/// docs/wheel-rail.md §9, "Models of a vehicle").
///
/// `Solver` is AnySolver by default: every kind of options.solver, and every solver compiled
/// in. A program that needs one solver names it, `WheelsetContact<NormSolver<>>`, and
/// compiles that one only (docs/contributing.md, compile cost): any solver type of the
/// concept of docs/architecture.md §2 with `normal_stiffness` and a SolverFromSpec
/// (solver_from_spec.hpp) will do.
template <typename Solver = AnySolver<double>>
class WheelsetContact {
  using State = detail::PatchState<typename Solver::Workspace>;

 public:
  using Workspace = typename Solver::Workspace;

  /// The model keeps its own copies of `track` and `wheelset` (cheap: a track and a wheelset
  /// hold a profile each), so nothing it uses can dangle; move them in to save the copy.
  /// @throws fastnorm::invalid_argument for invalid options (a solver spec of a kind that
  ///         `Solver` does not solve among them), or a reference pose at which a wheel does
  ///         not touch its rail
  WheelsetContact(Track track, Wheelset wheelset, WheelsetContactOptions options = {})
      : track_(std::move(track)),
        wheelset_(std::move(wheelset)),
        options_(std::move(options)),
        creep_(options_.material) {
    options_.validate();
    check_spec_for<Solver>(options_.solver, "WheelsetContactOptions: solver");
    choose_element_sizes();
    const Eigen::Index box = options_.table_box();
    solvers_.share_tables(Grid<double>(box, box, dx_, ds_), detail::box_quantum, options_.solver, options_.material);
  }

  const WheelsetContactOptions& options() const { return options_; }
  const Track& track() const { return track_; }
  const Wheelset& wheelset() const { return wheelset_; }
  /// The fixed element sizes (m): rolling dx, lateral ds.
  double element_length() const { return dx_; }
  double element_width() const { return ds_; }

  /// How many solvers (grid sizes) the model has built so far: each holds its influence
  /// table, and those of a reduced kind share the segment tables of boxes up to
  /// options().table_box() elements. When those tables are built with the model
  /// (tables_built), so is the solver of every box size up to that box whose sides are
  /// multiples of 8 elements (the lattice's sizes: 144 for a 96-element box).
  std::size_t solver_count() const { return solvers_.size(); }

  /// Whether the model built every segment table of its reduced solvers when it was built
  /// (they fit the spec's table budget together): then no step builds one
  /// (docs/wheel-rail.md §9). False for the other kinds, which have none.
  bool tables_built() const { return solvers_.tables_built(); }

  /// Contact of both wheels at `pose`, normal only; the result stays valid until the next
  /// call.
  /// @throws fastnorm::invalid_argument for a pose that is not finite or outside PoseLimits
  const WheelsetContactResult& evaluate(const WheelsetPose& pose) { return evaluate_both(pose, nullptr); }

  /// Contact of both wheels at `pose` moving with `velocity`: with each patch's creepages
  /// and creep forces (docs/wheel-rail.md §10), which the wheel's and wheelset's sums
  /// include.
  /// @throws fastnorm::invalid_argument as evaluate(pose), for velocities that are not finite
  ///         or a forward speed of zero, or when options.creep.friction is not set
  const WheelsetContactResult& evaluate(const WheelsetPose& pose, const WheelsetVelocity& velocity) {
    check_creep(velocity);
    return evaluate_both(pose, &velocity);
  }

  /// The result of the last evaluate, as it returned it (a single wheel's evaluate updates that
  /// wheel only); before the first, empty. Valid until the next call.
  const WheelsetContactResult& result() const { return result_; }

  /// Contact of the wheel of `side` only, at `pose` (CONTACT's single-wheel mode); the other
  /// wheel's state is kept for a later call, and the wheelset's sums are not updated. The
  /// result stays valid until the next call.
  /// @throws fastnorm::invalid_argument for a pose that is not finite or outside PoseLimits
  const WheelContact& evaluate(const WheelsetPose& pose, Side side) { return evaluate_one(pose, nullptr, side); }

  /// The same moving with `velocity`, with creep forces.
  /// @throws fastnorm::invalid_argument as evaluate(pose, velocity)
  const WheelContact& evaluate(const WheelsetPose& pose, const WheelsetVelocity& velocity, Side side) {
    check_creep(velocity);
    return evaluate_one(pose, &velocity, side);
  }

  /// The most solver iterations (active-set iterations; CG's for CG) an evaluate may spend
  /// over all its patch solves, in the order it solves them (left wheel first, tread
  /// first), as qpOASES' nWSR: each solve may take what the solves before it left, but at
  /// least one iteration, so a step spends at most the budget plus one per later patch. A
  /// solve that reaches its share answers with its last admissible iterate,
  /// Status::budget_reached (usable; Status::iteration_limit, which the step status names as
  /// a failure, if it has none), and goes on at the next step from where it stopped
  /// (docs/wheel-rail.md §9). WheelsetContactOptions::warm_solve_iterations caps each warm
  /// solve alike. What a step spent is `iterations` of its result. 0 (the
  /// default): no budget, each solve bounded by its solver's max_iterations alone.
  /// @throws fastnorm::invalid_argument for a negative budget
  void set_iteration_budget(int iterations) {
    FASTNORM_CHECK(iterations >= 0,
                   fastnorm::detail::describe("WheelsetContact::set_iteration_budget: iterations must be >= 0", iterations));
    iteration_budget_ = iterations;
  }
  int iteration_budget() const { return iteration_budget_; }

  /// Changes options().warm_solve_iterations, the cap of each warm patch solve, from the
  /// next evaluate on (0: none).
  /// @throws fastnorm::invalid_argument for a negative cap
  void set_warm_solve_iterations(int iterations) {
    FASTNORM_CHECK(iterations >= 0, fastnorm::detail::describe(
                                        "WheelsetContact::set_warm_solve_iterations: iterations must be >= 0", iterations));
    options_.warm_solve_iterations = iterations;
  }

  /// The next evaluate starts cold: no previous patches, no contact sets, no assemblies a
  /// solver kept (storage kept), so that what follows is bit for bit what a new model gives.
  void reset() {
    for (auto& sampler : samplers_) sampler.reset();
    for (auto& states : states_) {
      keep_spare_workspaces(states);
      detail::resize_keeping_storage(states, spare_states_, 0);
    }
  }

  /// What the next evaluate starts from: each patch's frame, lattice box, contact set and
  /// solver workspace, and each wheel's contact search (docs/wheel-rail.md §9, trial steps).
  /// Taken again into the same History (history(saved)), it is overwritten in its storage.
  class History {
    friend class WheelsetContact;
    std::array<std::vector<State>, 2> states;
    std::vector<State> spare_states;  // beyond a wheel's patch count, storage kept
    std::array<GapSampler, 2> samplers;
  };

  /// A copy of the committed history, for an integrator that evaluates trial poses and may
  /// reject them. It allocates; history(saved) into a History kept from step to step does not.
  History history() const {
    History saved;
    history(saved);
    return saved;
  }

  /// The committed history copied into `saved`, in the storage it holds from earlier
  /// copies: once it has held as many patches of the sizes met, nothing is allocated.
  void history(History& saved) const {
    for (std::size_t w = 0; w < 2; ++w) detail::copy_keeping_storage(states_[w], saved.states[w], saved.spare_states);
    saved.samplers = samplers_;
  }

  /// Back to `saved`: the next evaluate gives, bit for bit, what it would have given right
  /// after history() was taken, whatever was evaluated since. The patches' workspaces go
  /// back to their solvers' spares and the saved ones are copied into spares taken again,
  /// so that trials neither pile up storage nor, once their sizes repeat, allocate.
  /// Solvers and their tables built since are kept (they do not depend on the history);
  /// the last result stays readable.
  /// @throws fastnorm::invalid_argument for a history whose patches' grids this model has no
  ///         solver of (another model's, of other element sizes), the model left unchanged
  void restore(const History& saved) {
    for (const auto& states : saved.states) {
      for (const State& from : states) {
        FASTNORM_CHECK(from.solver < solvers_.size() && from.grid.dx() == dx_ && from.grid.dy() == ds_ &&
                           solvers_.solver(from.solver).grid().mx() == from.grid.mx() &&
                           solvers_.solver(from.solver).grid().my() == from.grid.my(),
                       "WheelsetContact::restore: the history is another model's (its patches' grids are not "
                       "this model's)");
      }
    }
    for (std::size_t w = 0; w < 2; ++w) {
      keep_spare_workspaces(states_[w]);
      detail::resize_keeping_storage(states_[w], spare_states_, saved.states[w].size());
      for (std::size_t k = 0; k < states_[w].size(); ++k) {
        State& state = states_[w][k];
        const State& from = saved.states[w][k];
        state.workspace = solvers_.take_workspace(from.solver, options_.solver.is_reduced());  // storage to copy into
        state = from;
      }
    }
    samplers_ = saved.samplers;
  }

 private:
  const WheelsetContactResult& evaluate_both(const WheelsetPose& pose, const WheelsetVelocity* velocity) {
    check_pose(pose, "WheelsetContact::evaluate");
    result_.pose = pose;
    result_.force.setZero();
    result_.moment.setZero();
    result_.status.set_ok(Side::left);
    result_.iterations = 0;
    iterations_left_ = iteration_budget_;
    for (Side side : {Side::left, Side::right}) {
      WheelContact& wheel = result_.wheels[wheel_index(side)];
      evaluate_wheel(side, pose, velocity, wheel);
      result_.force += wheel.force;
      result_.moment += wheel.moment;
      result_.iterations += wheel.iterations;
      if (result_.status.ok() && !wheel.status.ok()) result_.status = wheel.status;
    }
    return result_;
  }

  const WheelContact& evaluate_one(const WheelsetPose& pose, const WheelsetVelocity* velocity, Side side) {
    check_pose(pose, "WheelsetContact::evaluate");
    WheelContact& wheel = result_.wheels[wheel_index(side)];
    iterations_left_ = iteration_budget_;
    evaluate_wheel(side, pose, velocity, wheel);
    return wheel;
  }

  /// Before anything changes: creep forces asked for are possible.
  void check_creep(const WheelsetVelocity& velocity) const {
    FASTNORM_CHECK(options_.creep.friction.has_value(),
                   "WheelsetContact::evaluate: velocities given, but options.creep.friction is not set");
    check_velocity(velocity, "WheelsetContact::evaluate");
  }

  void choose_element_sizes() {
    WheelsetPose pose;
    if (options_.reference_pose) {
      pose = *options_.reference_pose;
    } else if (!(options_.grid.element_length > 0)) {
      pose = rigid_contact_pose(track_, wheelset_, 0, 0, options_.search);
      pose.z += options_.reference_approach;
    }
    const auto sizes = detail::element_sizes_at(track_, wheelset_, pose, {Side::left, Side::right}, options_.search,
                                                options_.grid);
    FASTNORM_CHECK(!sizes.untouched, std::string("WheelsetContact: the ") + to_string(*sizes.untouched) +
                                         " wheel does not touch its rail at the reference pose, where the element "
                                         "sizes are chosen");
    dx_ = sizes.length, ds_ = sizes.width;
  }

  /// Search, frames and grids, h, then a solve per patch started from its predecessors, and
  /// with `velocity` the creep forces.
  void evaluate_wheel(Side side, const WheelsetPose& pose, const WheelsetVelocity* velocity, WheelContact& wheel) {
    auto clock = std::chrono::steady_clock::now();
    wheel.side = side;
    const std::vector<ContactRegion>& regions = regions_;
    const std::size_t w = wheel_index(side);
    const std::size_t count = contact_regions(track_, wheelset_, side, pose, options_.search, samplers_[w], regions_);
    std::vector<State>& previous = states_[w];
    std::vector<State>& next = next_states_[w];  // storage of the call before the last
    detail::resize_keeping_storage(next, spare_states_, count);
    const auto& successors = match(regions, count, previous, wheel);
    wheel.flange_climb = false;
    for (std::size_t k = 0; k < count; ++k) {
      wheel.patches[k].centre = regions[k].centre;
      wheel.patches[k].profile_y = regions[k].profile_y;
      wheel.flange_climb = wheel.flange_climb || wheelset_.at_flange_climb(regions[k].profile_y);
      detail::place_grid(track_, regions[k], successors[k], previous, dx_, ds_, options_.snap_to_lattice, next[k]);
    }
    wheel.times.search = detail::seconds_since(clock);

    clock = std::chrono::steady_clock::now();
    for (std::size_t k = 0; k < count; ++k) {
      auto& patch = wheel.patches[k].patch;
      patch.frame = next[k].frame;
      patch.grid = next[k].grid;
      spare_storage_.fit(wheel.patches[k], patch.grid.size());
      if (options_.distance_everywhere) {
        undeformed_distance(track_, wheelset_, pose, patch.frame, patch.grid, options_.distance, patch.undeformed_distance);
      } else {
        touching_spans(patch.frame, regions[k], patch.grid, spans_);
        undeformed_distance(track_, wheelset_, pose, patch.frame, patch.grid, options_.distance, spans_,
                            patch.undeformed_distance);
      }
    }
    wheel.times.distance = detail::seconds_since(clock);

    clock = std::chrono::steady_clock::now();
    wheel.status.set_ok(side);
    wheel.iterations = 0;
    for (std::size_t k = 0; k < count; ++k) {
      const bool warm = start_from(successors[k], previous, next[k]);
      const PatchContact& patch = wheel.patches[k];
      limit_solve(warm, next[k].workspace.start());
      solve_patch(pose, next[k], wheel.patches[k]);
      wheel.iterations += patch.solution.iterations;
      iterations_left_ -= patch.solution.iterations;
      if (wheel.status.ok() && !patch.ok()) {
        wheel.status.set_patch_failed(side, static_cast<int>(k), count, patch.solution.status, patch.solution.message);
      }
    }
    keep_spare_workspaces(previous);
    std::swap(previous, next);
    wheel.times.solve = detail::seconds_since(clock);

    clock = std::chrono::steady_clock::now();
    for (std::size_t k = 0; k < count; ++k) {
      if (velocity) {
        creep_.add(wheelset_, options_, pose, *velocity, wheel.patches[k]);
      } else {
        PatchCreep::clear(wheel.patches[k], 0);
      }
    }
    wheel.times.tangential = velocity ? detail::seconds_since(clock) : 0.0;
    wheel.force.setZero();
    wheel.moment.setZero();
    wheel.normal_force = 0;
    for (std::size_t k = 0; k < count; ++k) {
      wheel.force += wheel.patches[k].force;
      wheel.moment += wheel.patches[k].moment;
      wheel.normal_force += wheel.patches[k].normal_force;
    }
  }

  /// For each new region, the previous patches whose reference point lies within the
  /// separation distance of its own; sets each patch's history and the wheel's vanished count.
  const std::vector<std::vector<std::size_t>>& match(const std::vector<ContactRegion>& regions, std::size_t count,
                                                     const std::vector<State>& previous, WheelContact& wheel) {
    auto& predecessors = predecessors_;
    if (predecessors.size() < count) predecessors.resize(count);  // never shrunk: the lists keep their storage
    for (std::size_t k = 0; k < count; ++k) predecessors[k].clear();
    auto& successors = successor_counts_;
    successors.assign(previous.size(), 0);
    for (std::size_t k = 0; k < count; ++k) {
      for (std::size_t p = 0; p < previous.size(); ++p) {
        if ((regions[k].centre - previous[p].centre).norm() <= options_.search.separation_distance) {
          predecessors[k].push_back(p);
          ++successors[p];
        }
      }
    }
    detail::resize_keeping_storage(wheel.patches, spare_patches_, count);
    for (std::size_t k = 0; k < count; ++k) {
      const auto& from = predecessors[k];
      wheel.patches[k].history = from.empty()                 ? PatchHistory::appeared
                                 : from.size() > 1             ? PatchHistory::merged
                                 : successors[from[0]] > 1     ? PatchHistory::split
                                                               : PatchHistory::continued;
    }
    wheel.vanished = static_cast<int>(std::count(successors.begin(), successors.end(), 0));
    return predecessors;
  }

  /// The starting contact set of a patch: its predecessors' sets mapped element by element
  /// onto its grid (a pure shift on the lattice); cold when it has none. True if warm.
  bool start_from(const std::vector<std::size_t>& predecessors, std::vector<State>& previous, State& state) {
    // The workspace follows the patch while its grid keeps its size; otherwise the patch
    // takes a spare one of its new size's solver (the storage of that size, no allocation),
    // or for a reduced solver a spare of another size (its storage reused).
    state.solver = solvers_.index_for(state.grid, options_.solver, options_.material);
    if (!predecessors.empty() && previous[predecessors.front()].solver == state.solver) {
      state.workspace = std::move(previous[predecessors.front()].workspace);
      previous[predecessors.front()].solver = detail::no_solver;  // its workspace moved on
    } else {
      state.workspace = solvers_.take_workspace(state.solver, options_.solver.is_reduced());
      // A new workspace's start gets room for its grid's sets (a spare has it already).
      state.workspace.start().reserve(static_cast<std::size_t>(state.grid.size()));
    }
    if (!options_.starts_warm() || predecessors.empty()) {
      state.workspace.start().clear();
      return false;
    }
    if (options_.snap_to_lattice && detail::same_box(state, predecessors, previous)) {
      // The same box: NORM's set and CG's pressures are in place in the workspace; a reduced
      // solver keeps no start of its own, so it gets the patch's last contact set as it is.
      const State& from = previous[predecessors.front()];
      if (options_.solver.is_reduced()) state.workspace.start().set_contact_set(from.contact_set);
      return true;
    }
    detail::shifted_contact_set(predecessors, previous, state, dx_, ds_, shifted_set_);
    state.workspace.start().set_contact_set(shifted_set_);
    return true;
  }

  /// The limits of the next patch solve: what the budget left, at least one, and for a
  /// warm solve the per-solve cap (WheelsetContactOptions::warm_solve_iterations).
  void limit_solve(bool warm, WarmStart<double>& start) const {
    start.limit_iterations(iteration_budget_ > 0 ? std::max(1, iterations_left_) : 0);
    start.cap_iterations(warm ? options_.warm_solve_iterations : 0);
  }

  /// Solves one patch in approach control and fills its forces and stiffness.
  void solve_patch(const WheelsetPose& pose, State& state, PatchContact& out) {
    const Solver& solver = solvers_.solver(state.solver);
    auto& patch = out.patch;
    state.workspace.recycle(std::move(out.solution));  // the last call's answer: its storage
    out.solution = solver.solve(patch.undeformed_distance, Loading<double>::approach(), state.workspace);
    const auto& solution = out.solution;
    // The next step starts from this one's contact set; after a solve its iteration budget
    // cut, from the start the solver left, where its iteration would have gone on (the
    // active-set loop's next set; CG's cut answer), so that a budgeted patch keeps its joins
    // and converges over the next steps (docs/wheel-rail.md §9).
    if (solution.stopped_early()) {
      const auto& continuation = state.workspace.start().contact_set();
      state.contact_set.assign(continuation.begin(), continuation.end());
    } else {
      state.contact_set.clear();
      for (Eigen::Index k = 0; k < solution.in_contact.size(); ++k) {
        if (solution.in_contact(k)) state.contact_set.push_back(k);
      }
    }
    out.normal_force = solution.normal_force;
    out.contact_elements = solution.contact_count();
    out.max_pressure = solution.pressure.size() > 0 ? solution.pressure.maxCoeff() : 0.0;
    out.approach = -patch.undeformed_distance.minCoeff();
    out.contact_angle = patch.frame.contact_angle();
    // Pressure centroid in the tangent plane, then force and moment on the wheel.
    double x_mean = 0, s_mean = 0;
    if (out.normal_force > 0) {
      const double area = patch.grid.element_area();
      for (Eigen::Index k : state.contact_set) {
        x_mean += solution.pressure(k) * area * patch.grid.x_of(k);
        s_mean += solution.pressure(k) * area * patch.grid.y_of(k);
      }
      x_mean /= out.normal_force;
      s_mean /= out.normal_force;
    }
    out.pressure_centre = patch.frame.reference + x_mean * Eigen::Vector3d::UnitX() + s_mean * patch.frame.lateral_axis();
    out.force = -out.normal_force * patch.frame.normal();
    out.moment = detail::cross(out.pressure_centre - wheelset_.centre(pose), out.force);
    out.stiffness = options_.stiffness && solution.ok() ? solver.normal_stiffness(solution, state.workspace)
                                                        : std::nan("");
  }

  /// After a call: the workspaces of patches that vanished or changed size go back to their
  /// solver's spares.
  void keep_spare_workspaces(std::vector<State>& states) {
    for (State& state : states) {
      if (state.solver != detail::no_solver) solvers_.give_back(state.solver, std::move(state.workspace));
      state.solver = detail::no_solver;
    }
  }

  Track track_;
  Wheelset wheelset_;
  WheelsetContactOptions options_;
  double dx_ = 0, ds_ = 0;
  int iteration_budget_ = 0;  // set_iteration_budget
  int iterations_left_ = 0;   // of the budget, in the evaluate under way
  detail::SolverCache<Solver> solvers_;     // one per grid size met (dx, ds fixed), with spare workspaces
  std::array<std::vector<State>, 2> states_;  // per wheel (left, right), per patch
  std::array<std::vector<State>, 2> next_states_;  // the same, being filled by a call
  std::vector<State> spare_states_;                    // states beyond the patch count, storage kept
  std::vector<PatchContact> spare_patches_;            // result patches beyond the patch count, storage kept
  detail::StorageByLength spare_storage_;              // h, solutions and tractions by length
  PatchCreep creep_;                                   // the creep forces' workspaces
  std::vector<std::vector<std::size_t>> predecessors_;  // of each new patch (match); the first `count` in use
  std::vector<int> successor_counts_;                  // of each previous patch (match)
  std::vector<ContactRegion> regions_;                 // of the wheel being evaluated, and spares
  std::array<GapSampler, 2> samplers_;                 // per wheel: the contact search, continued
  std::vector<Eigen::Index> shifted_set_;              // a predecessor's set on the new grid (start_from)
  std::vector<RowSpan> spans_;                         // of the patch whose h is computed (evaluate_wheel)
  WheelsetContactResult result_;
};

}  // namespace fastnorm::wheelrail
