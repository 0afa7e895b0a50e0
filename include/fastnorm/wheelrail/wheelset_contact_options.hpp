#pragma once
/// @file wheelset_contact_options.hpp
/// Settings of the wheelset contact model of the time loop (docs/wheel-rail.md §9),
/// fixed for a model's life; the equilibrium's options contain them.

#include <optional>
#include <string>

#include "fastnorm/error.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/solver_spec.hpp"
#include "fastnorm/wheelrail/contact_search.hpp"
#include "fastnorm/wheelrail/patch.hpp"
#include "fastnorm/wheelrail/undeformed_distance.hpp"

namespace fastnorm::wheelrail {

/// The fast tangential method of the time loop (docs/tangential.md §9–10).
enum class CreepMethod {
  strip_theory,  ///< StripTheory: Carter's strips calibrated to Kalker's linear theory
  fastsim,       ///< Kalker's simplified theory with the flexibilities of the equivalent ellipse
};

inline const char* to_string(CreepMethod method) {
  return method == CreepMethod::strip_theory ? "strip_theory" : "fastsim";
}

/// Creep forces of a WheelsetContact (docs/wheel-rail.md §10): computed on each patch's
/// pressure by `method` whenever evaluate is given the wheelset's velocities.
struct CreepOptions {
  /// Coulomb's coefficient μ of every patch; unset, evaluate with velocities is refused.
  std::optional<double> friction;
  CreepMethod method = CreepMethod::strip_theory;
  /// Also each patch's d(Fx, Fs, Mn)/d(ξ, η, φ) (PatchContact::creep_jacobian), for an
  /// implicit integrator's Jacobian. FASTSIM differentiates its sweep (about 2.3 times the
  /// plain solve); strip theory takes central differences, six more solves.
  bool sensitivities = false;

  /// @throws fastnorm::invalid_argument naming the offending field
  void validate() const {
    if (friction) fastnorm::detail::check_positive(*friction, "WheelsetContactOptions: creep.friction");
  }
};

/// Settings of a WheelsetContact, fixed for its life.
struct WheelsetContactOptions {
  /// The patch solver and its settings (NORM by default). With a model of a named solver
  /// type (WheelsetContact<NormSolver<>>, …) its kind must be that type's.
  SolverSpec<double> solver;
  /// Element sizes: element_length and element_width if both are given (m), else the sizes
  /// that put `elements` across the largest patch at `reference_pose`.
  PatchGridOptions grid;
  SearchOptions search;           ///< contact search and patch merging
  /// How exactly h is computed on the patches: by default interpolated along rows between
  /// exact nodes within 0.1 nm (docs/wheel-rail.md §4, item 7); `distance.tolerance = 0`:
  /// every element exactly.
  DistanceAccuracy distance;
  /// h on every element of a patch's grid. Off (default): only on the rows and columns
  /// where an element can interpenetrate, the rest of the grid box (kept for the steps to
  /// come) holding not_computed_gap (docs/wheel-rail.md §4, item 8). The solvers read h
  /// only where it is negative, so their answers move only by h's interpolation, within
  /// distance.tolerance (a row's nodes start at its span's first column).
  bool distance_everywhere = false;
  /// Elastic constants of wheel (body 1) and rail (body 2); steel for both by default.
  Material<double> material = Material<double>::steel();
  /// Where the element sizes are chosen when not given; by default the rigid two-wheel
  /// contact at y = 0, yaw = 0 lowered by `reference_approach`.
  std::optional<WheelsetPose> reference_pose;
  double reference_approach = 0.1e-3;  ///< m
  /// Patch grids on a lattice of the element sizes that moves with each patch only by whole
  /// elements (docs/wheel-rail.md §9): consecutive grids differ by whole elements and the previous contact set
  /// maps onto the new grid exactly. Off: each grid is centred on its patch's contact
  /// reference point, as the equilibrium does.
  bool snap_to_lattice = true;
  /// Start each NORM or CG solve from the patch's previous contact set (shifted onto the
  /// new grid); their answers do not depend on it, only their time.
  bool warm_start = true;
  /// The same for the reduced solvers, whose answer depends on the path of the active set,
  /// so that a warm answer may differ from the cold one. Unset: warm for every basis whose
  /// warm run of the benchmark trajectory had no larger force error against NORM and no
  /// larger contact-set difference than its cold run, every checked step within the cold
  /// bound (elliptic, polynomial, polynomial-edge); cold for the edge-enriched elliptic
  /// basis, whose warm sets differed from NORM's by one element more (docs/performance.md
  /// §8). Cold, a solve follows the cold path and reuses the assemblies of the previous
  /// solve where the grid is unchanged.
  std::optional<bool> reduced_warm_start;

  /// The largest patch box (elements, each direction) whose reduced solvers share one set
  /// of segment tables (docs/wheel-rail.md §9): each table is built once for the model, not
  /// once per box size, within one budget (SolverSpec::table_budget_bytes). 0 (default):
  /// 1.5 × grid.elements rounded up to a multiple of 8 (96 for 60). A larger box gets tables
  /// of its own.
  Eigen::Index shared_table_box = 0;
  /// shared_table_box, or its default.
  Eigen::Index table_box() const {
    return shared_table_box > 0 ? shared_table_box : (3 * grid.elements / 2 + 7) / 8 * 8;
  }
  /// The iterations (active-set iterations; CG's for CG) after which a warm-started patch
  /// solve may stop in one evaluate, as a real-time iteration. An active-set solve stops at
  /// its first settled iterate after them (pressures all positive, gaps violated by at most a
  /// hundredth of the deepest interpenetration: IterationStop::settled_residual) with
  /// Status::budget_reached (usable: forces, stiffness and creep forces as for a converged
  /// one), and goes on at the next evaluate from where it stopped (docs/wheel-rail.md §9).
  /// Until such an iterate comes it goes on, so a capped solve never fails for the cap and
  /// does not trail a fast-moving contact (a stop at any admissible iterate, as before
  /// 2026-12-08, erred by 16 % at 40 times the benchmark's speed: docs/performance.md §8).
  /// CG stops at the cap. A cold solve (a patch's first step, after reset, a cold start) is
  /// not capped, so a model evaluated once answers converged. 0 (default): no cap.
  int warm_solve_iterations = 0;
  bool stiffness = true;  ///< compute each patch's dFn/dδ (one extra solve with the last factor)
  CreepOptions creep;     ///< creep forces, when evaluate is given velocities

  /// Whether a solve of `solver` starts from the patch's previous contact set.
  bool starts_warm() const {
    if (!solver.is_reduced()) return warm_start;
    return reduced_warm_start.value_or(solver.kind != SolverSpec<double>::Kind::elliptic_edge);
  }

  /// @throws fastnorm::invalid_argument naming the offending field
  void validate() const {
    solver.validate();
    grid.validate();
    search.validate();
    distance.validate();
    creep.validate();
    fastnorm::detail::check_positive(reference_approach, "WheelsetContactOptions: reference_approach (m)");
    FASTNORM_CHECK(warm_solve_iterations >= 0,
                   fastnorm::detail::describe("WheelsetContactOptions: warm_solve_iterations must be >= 0",
                                              warm_solve_iterations));
    FASTNORM_CHECK(shared_table_box >= 0 && shared_table_box <= PatchGridOptions::max_elements,
                   fastnorm::detail::describe("WheelsetContactOptions: shared_table_box must lie in [0, " +
                                                  std::to_string(PatchGridOptions::max_elements) + "] (elements)",
                                              shared_table_box));
    FASTNORM_CHECK((grid.element_length > 0) == (grid.element_width > 0),
                   "WheelsetContactOptions: give both grid.element_length and grid.element_width, or neither");
    if (reference_pose) check_pose(*reference_pose, "WheelsetContactOptions: reference_pose");
  }
};

}  // namespace fastnorm::wheelrail
