/* fastnorm_c.h: the C API of fastnorm (C99; docs/bindings.md).
 *
 * Every function returns an int status code, FASTNORM_OK (0) on success; on failure
 * fastnorm_last_error() gives the message, kept per thread until the next failing call of
 * that thread. No C++ exception crosses this interface. Units are SI: m, Pa, N, rad.
 * Arrays over a grid hold element k = i + mx*j (i along x, the rolling direction).
 * A handle may be used by one thread at a time; different handles by different threads
 * at once. */
#ifndef FASTNORM_C_H
#define FASTNORM_C_H

#ifdef __cplusplus
extern "C" {
#endif

#if defined(_WIN32) && defined(FASTNORM_C_BUILDING)
#define FASTNORM_C_API __declspec(dllexport)
#elif defined(_WIN32)
#define FASTNORM_C_API __declspec(dllimport)
#else
#define FASTNORM_C_API __attribute__((visibility("default")))
#endif

/* Return codes. */
enum {
  FASTNORM_OK = 0,
  FASTNORM_ERROR_ARGUMENT = 1, /* bad input: the message names the argument */
  FASTNORM_ERROR_MEMORY = 2,   /* out of memory */
  FASTNORM_ERROR_INTERNAL = 3, /* anything else: a bug, please report the message */
  /* fastnorm_wheelset_evaluate: a patch solve gave no usable answer. The message names the
   * wheel, the patch and why (fastnorm_wheelset_step_status has it as numbers); forces and
   * patches are written as for FASTNORM_OK, the failed patch's with its own status. */
  FASTNORM_ERROR_PATCH_FAILED = 4
};

/* How a solve ended (fastnorm::Status). */
enum {
  FASTNORM_NOT_SOLVED = 0,
  FASTNORM_CONVERGED = 1,
  FASTNORM_NO_CONTACT = 2,
  FASTNORM_ITERATION_LIMIT = 3,
  FASTNORM_CYCLED = 4, /* reduced bases: the last set with positive pressures, usable */
  FASTNORM_NUMERICAL_ISSUE = 5,
  /* a caller's iteration budget stopped the solve at its last iterate with every pressure
   * positive: usable; the next evaluate goes on where it stopped (docs/wheel-rail.md §9) */
  FASTNORM_BUDGET_REACHED = 6
};

/* The fast tangential methods of the wheelset model (docs/tangential.md §9-10). */
enum { FASTNORM_STRIP_THEORY = 0, FASTNORM_FASTSIM = 1 };

/* The message of this thread's last failing call ("" if none). */
FASTNORM_C_API const char* fastnorm_last_error(void);
/* "converged", "no contact", ... for a FASTNORM_* status; "unknown" otherwise. */
FASTNORM_C_API const char* fastnorm_status_name(int status);
/* The library version, "major.minor.patch". */
FASTNORM_C_API const char* fastnorm_version(void);

/* A regular grid of mx x my rectangles dx x dy (m); (x0, y0) the centre of element 0. */
typedef struct fastnorm_grid {
  int mx, my;
  double dx, dy, x0, y0;
} fastnorm_grid;

/* Elastic constants of body 1 (wheel) and body 2 (rail): E in Pa, nu in (-1, 0.5]. */
typedef struct fastnorm_material {
  double young_modulus_1, poisson_ratio_1, young_modulus_2, poisson_ratio_2;
} fastnorm_material;

/* What a solve returns besides the pressures. */
typedef struct fastnorm_result {
  int status;          /* FASTNORM_CONVERGED, ... */
  int iterations;      /* active-set solves or CG iterations */
  int contact_count;   /* elements in contact */
  int at_edge;         /* 1: contact touches the grid boundary (make the grid larger) */
  double normal_force; /* Fn (N) */
  double approach;     /* rigid approach found in force control, 0 in approach control (m) */
  double residual;     /* the solver's own measure of the Signorini conditions (relative) */
} fastnorm_result;

/* Solver settings; 0 (or 0.0) in a field keeps the solver's default. */
typedef struct fastnorm_solver_options {
  int max_iterations;   /* active-set solves (default 200) or CG iterations (5000) */
  double tolerance;     /* CG only: its stopping (complementarity) tolerance (default 1e-9) */
  double gap_tolerance; /* NORM and the reduced solvers only: the join tolerance, relative to max|h|
                           (default 1000 eps for NORM, 3e-5 for the reduced solvers; docs/norm.md §2) */
} fastnorm_solver_options;
/* A tolerance set (> 0) for a solver it does not apply to is refused (FASTNORM_ERROR_ARGUMENT). */

typedef struct fastnorm_solver fastnorm_solver;

/* A solver on a grid and material. name: "norm", "cg", "elliptic", "polynomial[:G]",
 * "elliptic-edge[:K]", "polynomial-edge[:G[:K]]". options may be NULL. */
FASTNORM_C_API int fastnorm_solver_create(const char* name, const fastnorm_grid* grid, const fastnorm_material* material,
                                          const fastnorm_solver_options* options, fastnorm_solver** solver);
/* NULL is allowed. */
FASTNORM_C_API void fastnorm_solver_destroy(fastnorm_solver* solver);

/* Solves with h, the undeformed distance (m, + = gap, mx*my values). Approach control: h
 * already holds the approach. Force control: Fn (N) > 0 is met by a rigid approach.
 * pressure: mx*my values (Pa), written. A cold solve: its answer does not depend on what
 * the handle solved before. */
FASTNORM_C_API int fastnorm_solve_approach(fastnorm_solver* solver, const double* h, double* pressure,
                                           fastnorm_result* result);
FASTNORM_C_API int fastnorm_solve_force(fastnorm_solver* solver, const double* h, double normal_force,
                                        double* pressure, fastnorm_result* result);
/* The next problem of a sequence: starts from the contact set of the handle's previous
 * solve_next (NORM and CG give the cold answer, sooner; a reduced solver's may differ
 * within its accuracy). normal_force <= 0 means approach control; NaN or inf is refused. */
FASTNORM_C_API int fastnorm_solve_next(fastnorm_solver* solver, const double* h, double normal_force,
                                       double* pressure, fastnorm_result* result);
/* dFn/d(approach) (N/m) at the contact set of the handle's last solve_next. */
FASTNORM_C_API int fastnorm_normal_stiffness(fastnorm_solver* solver, double* stiffness);

/* Creepages of the rail (body 1) against the wheel, CONTACT's definition: the rigid slip is
 * (xi - phi (y - y0), eta + phi (x - x0)) (docs/tangential.md §5). */
typedef struct fastnorm_creepage {
  double longitudinal;              /* xi */
  double lateral;                   /* eta */
  double spin;                      /* phi (rad/m) */
  double spin_centre_x, spin_centre_y; /* (x0, y0) in the grid's coordinates (m) */
} fastnorm_creepage;
/* What a steady-rolling solve returns besides the tractions. */
typedef struct fastnorm_tangential_result {
  int status;                 /* FASTNORM_CONVERGED, FASTNORM_ITERATION_LIMIT, FASTNORM_NO_CONTACT */
  int sweeps;                 /* Gauss-Seidel sweeps */
  int adhesion_elements, slip_elements;
  double force_x, force_y;    /* on the rail (N); a positive xi gives a negative force_x */
  double spin_moment;         /* sum dA (x p_y - y p_x) about the grid's origin (N m) */
  double frictional_power_per_speed; /* sum dA |p||s| over the slip area (N); times the speed: W */
  double residual;            /* the last sweep's traction changes by the stopping rule: the
                                 largest / (mu max p_n), or their rms / the tractions' */
} fastnorm_tangential_result;
/* When the sweeps stop (docs/tangential.md §7). */
enum { FASTNORM_STOP_LARGEST_CHANGE = 0, FASTNORM_STOP_RMS_CHANGE = 1 };
typedef struct fastnorm_tangential_options {
  int stop;          /* FASTNORM_STOP_LARGEST_CHANGE (default): no traction changes by more than
                        tolerance * mu max p_n in a sweep; FASTNORM_STOP_RMS_CHANGE: CONTACT's
                        rule, the rms of a sweep's traction changes at most tolerance times the
                        tractions' (its EPS: 1e-5 in its wheel-rail runs) */
  int max_sweeps;    /* 0: the default, 2000 */
  double tolerance;  /* in (0, 1); 0: the default, 1e-9 */
} fastnorm_tangential_options;
/* Steady rolling with Coulomb friction (mu > 0) on the normal pressures `pressure` (Pa, the
 * contact area where they are positive, as a solve wrote them) of a grid and material;
 * rolling: +1 the contact moves towards +x (CONTACT's chi = 0), -1 towards -x; options may
 * be NULL (the defaults). Writes the tractions on the rail (Pa) into traction_x and
 * traction_y (grid-sized). */
FASTNORM_C_API int fastnorm_steady_rolling(const fastnorm_grid* grid, const fastnorm_material* material,
                                           const double* pressure, double friction, const fastnorm_creepage* creepage,
                                           int rolling, const fastnorm_tangential_options* options,
                                           double* traction_x, double* traction_y,
                                           fastnorm_tangential_result* result);

/* .case files (docs/case-format.md). */
typedef struct fastnorm_case fastnorm_case;

FASTNORM_C_API int fastnorm_case_read(const char* path, fastnorm_case** problem);
FASTNORM_C_API void fastnorm_case_destroy(fastnorm_case* problem);
/* Grid, material (body 2 = body 1), control: force_control 1 with its Fn (N), or 0 with the
 * stated approach (m). Any output pointer may be NULL. */
FASTNORM_C_API int fastnorm_case_info(const fastnorm_case* problem, fastnorm_grid* grid, fastnorm_material* material,
                                      int* force_control, double* control_value);
/* h: mx*my values (m), written. */
FASTNORM_C_API int fastnorm_case_undeformed_distance(const fastnorm_case* problem, double* h);
/* The stored solution part, if the case has one (else FASTNORM_ERROR_ARGUMENT): pressure
 * mx*my values (Pa), written; result's normal_force, approach, contact_count and
 * iterations filled, status FASTNORM_NOT_SOLVED (a file does not store it). */
FASTNORM_C_API int fastnorm_case_result(const fastnorm_case* problem, double* pressure, fastnorm_result* result);
/* The case's steady-rolling problem, its tangential line (docs/case-format.md), if it has
 * one (else FASTNORM_ERROR_ARGUMENT): friction, the creepages about the spin centre, and
 * rolling +1 (towards +x) or -1; what fastnorm_steady_rolling takes. */
FASTNORM_C_API int fastnorm_case_rolling(const fastnorm_case* problem, double* friction, fastnorm_creepage* creepage,
                                         int* rolling);
/* Writes a case; pressure and result may both be NULL (no solution part) or both given. */
FASTNORM_C_API int fastnorm_case_write(const char* path, const char* name, const fastnorm_grid* grid,
                                       const fastnorm_material* material, int force_control, double control_value,
                                       const double* h, const double* pressure, const fastnorm_result* result);

/* The wheelset contact model of the time loop (docs/wheel-rail.md §9) and the static
 * equilibrium of a loaded wheelset (§5). Wheels: 0 left, 1 right. */
typedef struct fastnorm_wheelset_options {
  const char* solver;         /* patch solver, as for fastnorm_solver_create */
  const char* wheel_profile;  /* profile file (SIMPACK, or two columns in mm); NULL or "": S1002 */
  const char* rail_profile;   /* the same; NULL or "": UIC60 (MBench) */
  double nominal_radius;      /* wheel rolling radius at the taping line (m) */
  double gauge;               /* track gauge (m); the taping lines are 65 mm wider */
  double cant;                /* rail inclination towards the track centre (rad) */
  fastnorm_material material; /* wheel (body 1) and rail (body 2) */
  int elements;               /* elements across the largest patch, in [4, 2000] */
  int stiffness;              /* 1: each patch's dFn/d(approach) as well; 0: not */
  int max_iterations;         /* of each patch solve, as in fastnorm_solver_options; 0: the default */
  double distance_tolerance;  /* h interpolated along rows within this (m, default 1e-10, >= 0);
                                 0: exact at every element (docs/wheel-rail.md §4, item 7) */
  double friction;            /* Coulomb's mu of every patch for the creep forces of
                                 fastnorm_wheelset_evaluate_moving (> 0); 0: none (default) */
  int creep_method;           /* FASTNORM_STRIP_THEORY (default) or FASTNORM_FASTSIM */
  int distance_everywhere;    /* 1: h on every element of a patch's grid; 0 (default): only where an
                                 element can interpenetrate, 1e-3 m elsewhere (docs/wheel-rail.md §4,
                                 item 8) */
  int warm_solve_iterations;  /* the iterations after which each warm-started patch solve in an
                                 evaluate stops at its first settled iterate (FASTNORM_BUDGET_REACHED,
                                 continued at the next); cold solves uncapped; 0 (default): none
                                 (docs/wheel-rail.md §9) */
  double tolerance;           /* of each patch solve, as in fastnorm_solver_options (CG only); 0: the default */
  double gap_tolerance;       /* of each patch solve, as in fastnorm_solver_options (not CG); 0: the default */
  double distance_node_spacing; /* distance between the exact nodes of h along a row (m, default 4e-3, > 0;
                                   docs/wheel-rail.md §4, item 7; docs/performance.md §8 its cost) */
} fastnorm_wheelset_options;

/* Fills the defaults: "norm", S1002 on UIC60, radius 0.45 m, gauge 1.435 m, cant 1/40,
 * steel (E 210 GPa, nu 0.3) for both bodies, 60 elements, stiffness on, h within 1e-10 m
 * between nodes 3 mm apart.
 * Change fields after. */
FASTNORM_C_API void fastnorm_wheelset_options_default(fastnorm_wheelset_options* options);

/* The wheelset's position on the track (m, rad): lateral shift y, vertical z (down),
 * roll about x, yaw about the rolled z axis. */
typedef struct fastnorm_pose {
  double y, z, roll, yaw;
} fastnorm_pose;

/* The wheelset's velocities, the rates of its pose (m/s, rad/s; docs/wheel-rail.md §10):
 * forward speed V along the track (not 0), dy/dt, dz/dt, roll and yaw rates, and the
 * rotation rate about the axle (-V/r rolling without slip on radius r; z is down). */
typedef struct fastnorm_velocity {
  double forward, lateral, vertical, roll_rate, yaw_rate, pitch_rate;
} fastnorm_velocity;

/* How a patch relates to the patches of its wheel at the previous evaluate. */
enum {
  FASTNORM_PATCH_CONTINUED = 0, /* the continuation of one previous patch */
  FASTNORM_PATCH_APPEARED = 1,  /* no previous patch near it */
  FASTNORM_PATCH_MERGED = 2,    /* two or more previous patches became this one */
  FASTNORM_PATCH_SPLIT = 3      /* one previous patch became this and another */
};

/* One contact patch (fastnorm::wheelrail::PatchContact). Track frame: x forward, y right,
 * z down. Element k of the grid, at (x_k, s_k) = (x0 + i dx, y0 + j dy), lies at the track
 * point reference + x_k e_x + s_k t_s: the pressures placed in the track frame. A zeroed
 * struct reads status FASTNORM_NOT_SOLVED. */
typedef struct fastnorm_patch {
  int status;               /* of its solve, FASTNORM_CONVERGED, ... */
  int at_edge;              /* contact touches its grid's boundary */
  int flange_climb;         /* the reference point lies on the flange's steepest flank or beyond */
  int history;              /* FASTNORM_PATCH_CONTINUED, ... */
  int contact_elements;     /* elements in contact */
  fastnorm_grid grid;       /* the patch's grid in its tangent plane, relative to reference */
  double reference[3];      /* the grid's origin P, on the rail (m) */
  double e_x[3];            /* the grid's x axis: rolling direction (1, 0, 0) */
  double t_s[3];            /* the grid's y axis: lateral, in the tangent plane */
  double normal[3];         /* n, the normal into the rail */
  double centre[3];         /* the contact reference point: interpenetration-weighted centre (m) */
  double pressure_centre[3];/* the centroid of the pressure in the tangent plane (m) */
  double profile_y;         /* wheel profile coordinate y_w of the reference point (m) */
  double normal_force;      /* Fn (N) */
  double force[3];          /* the contact force on the wheel, track frame (N): -Fn n, plus creep_force */
  double moment[3];         /* its moment about the wheelset centre (N m) */
  double contact_angle;     /* of the normal from the vertical, + towards the track centre (rad) */
  double approach;          /* rigid interpenetration, -min h (m) */
  double max_pressure;      /* Pa */
  double stiffness;         /* dFn/d(approach) (N/m); NaN when not asked for */
  /* After fastnorm_wheelset_evaluate_moving (else zero, creep.status FASTNORM_NOT_SOLVED): the
   * creepages of the rail against the wheel at reference (the spin centre), the creep
   * forces on the rail in the patch frame (creep.force_x = Fx along e_x, creep.force_y = Fs
   * along t_s, creep.spin_moment = Mn about reference; options.creep_method's, sweeps 1), and the creep
   * force on the wheel, -(Fx e_x + Fs t_s), track frame (N). */
  fastnorm_creepage creepage;
  fastnorm_tangential_result creep;
  double creep_force[3];
} fastnorm_patch;

/* How the last fastnorm_wheelset_evaluate ended (fastnorm::wheelrail::StepStatus). A zeroed
 * struct, and the model before its first evaluate or after an equilibrium, read
 * FASTNORM_STEP_NOT_SOLVED. */
enum { FASTNORM_STEP_NOT_SOLVED = 0, FASTNORM_STEP_OK = 1, FASTNORM_STEP_PATCH_FAILED = 2 };
typedef struct fastnorm_step_status {
  int code;          /* FASTNORM_STEP_* */
  int wheel;         /* of the first failed patch: 0 left, 1 right; -1 if none failed */
  int patch;         /* its index in that wheel's patches; -1 if none failed */
  int solver_status; /* its solve's FASTNORM_ITERATION_LIMIT, ...; FASTNORM_NOT_SOLVED if none failed */
} fastnorm_step_status;

typedef struct fastnorm_wheelset fastnorm_wheelset;

FASTNORM_C_API int fastnorm_wheelset_create(const fastnorm_wheelset_options* options, fastnorm_wheelset** model);
FASTNORM_C_API void fastnorm_wheelset_destroy(fastnorm_wheelset* model);
/* A model of its own (*copy, to destroy as any) that answers as model would: its patches,
 * history, saved history and budget copied, the patches of model's last call readable in it.
 * It shares model's solvers' read-only tables (influence and segment tables), so the copies
 * of one model hold them once: the way to make the wheelset models of a vehicle
 * (docs/wheel-rail.md §9, "Models of a vehicle"). A model and its copies may be evaluated on
 * different threads at once; each one by one thread at a time, as any model. */
FASTNORM_C_API int fastnorm_wheelset_copy(const fastnorm_wheelset* model, fastnorm_wheelset** copy);
/* Evaluates every wheel's contact at pose; force[3] and moment[3] (may be NULL) receive the
 * totals on the wheelset (N, N m about its centre). The patches stay readable until the
 * next evaluate. FASTNORM_ERROR_PATCH_FAILED when a patch solve gave no usable answer. */
FASTNORM_C_API int fastnorm_wheelset_evaluate(fastnorm_wheelset* model, const fastnorm_pose* pose, double* force,
                                              double* moment);
/* The same with the wheelset moving at velocity: every patch's creepages and creep forces as
 * well (strip theory or FASTSIM, options.creep_method; docs/wheel-rail.md §10), which force
 * and moment include; needs
 * options.friction > 0. */
FASTNORM_C_API int fastnorm_wheelset_evaluate_moving(fastnorm_wheelset* model, const fastnorm_pose* pose,
                                                     const fastnorm_velocity* velocity, double* force, double* moment);
FASTNORM_C_API int fastnorm_wheelset_step_status(const fastnorm_wheelset* model, fastnorm_step_status* status);
/* The most solver iterations an evaluate may spend over its patch solves, in order, each at
 * least one (docs/wheel-rail.md §9): a solve cut short ends at FASTNORM_BUDGET_REACHED with
 * its last iterate whose pressures are all positive (usable), or, if it had none, at
 * FASTNORM_ITERATION_LIMIT, and the evaluate returns FASTNORM_ERROR_PATCH_FAILED naming it;
 * either goes on at the next evaluate; 0 (the default): none. */
FASTNORM_C_API int fastnorm_wheelset_set_iteration_budget(fastnorm_wheelset* model, int iterations);
/* The solver iterations the last evaluate spent over its patch solves (0 before any). */
FASTNORM_C_API int fastnorm_wheelset_iterations(const fastnorm_wheelset* model, int* iterations);
/* The next evaluate starts cold: no previous patches, contact sets or search (storage kept);
 * the patches and status read as after create. */
FASTNORM_C_API int fastnorm_wheelset_reset(fastnorm_wheelset* model);
/* Trial steps (docs/wheel-rail.md §9): saves the model's history, what its next evaluate
 * starts from, in the model's one slot (the last save overwritten, in its storage). An
 * integrator saves at the accepted step and restores before it evaluates again. */
FASTNORM_C_API int fastnorm_wheelset_save_history(fastnorm_wheelset* model);
/* Back to the saved history: the next evaluate gives, bit for bit, what it would have given
 * right after the save, whatever was evaluated since; the patches of the last evaluate stay
 * readable. FASTNORM_ERROR_ARGUMENT if nothing was saved. */
FASTNORM_C_API int fastnorm_wheelset_restore_history(fastnorm_wheelset* model);
FASTNORM_C_API int fastnorm_wheelset_patch_count(const fastnorm_wheelset* model, int wheel, int* count);
FASTNORM_C_API int fastnorm_wheelset_patch(const fastnorm_wheelset* model, int wheel, int patch, fastnorm_patch* out);
/* The patch's pressures (Pa), grid.mx*grid.my values, written. */
FASTNORM_C_API int fastnorm_wheelset_patch_pressure(const fastnorm_wheelset* model, int wheel, int patch,
                                                    double* pressure);
/* The patch's tractions on the rail along e_x and t_s (Pa), grid.mx*grid.my values each,
 * written; after fastnorm_wheelset_evaluate_moving (else FASTNORM_ERROR_ARGUMENT). */
FASTNORM_C_API int fastnorm_wheelset_patch_traction(const fastnorm_wheelset* model, int wheel, int patch,
                                                    double* traction_x, double* traction_s);

/* Static equilibrium: z and roll such that the rails carry load (N) at lateral shift y (m)
 * and yaw (rad). */
typedef struct fastnorm_equilibrium {
  int status;             /* FASTNORM_EQUILIBRIUM_* */
  int iterations;         /* contact evaluations */
  fastnorm_pose pose;     /* z and roll found */
  double vertical_force;  /* what the rails carry (N) */
  double lateral_force;   /* lateral force needed to hold y (N) */
  int patch_count[2];     /* patches per wheel at pose */
} fastnorm_equilibrium;

enum {
  FASTNORM_EQUILIBRIUM_NOT_SOLVED = 0, /* a zeroed struct */
  FASTNORM_EQUILIBRIUM_CONVERGED = 1,
  FASTNORM_EQUILIBRIUM_LOST_CONTACT = 2,
  FASTNORM_EQUILIBRIUM_NOT_CONVERGED = 3,
  FASTNORM_EQUILIBRIUM_SOLVER_FAILED = 4,
  FASTNORM_EQUILIBRIUM_FLANGE_CLIMB = 5
};

/* The equilibrium of this model as it is (its solver, element sizes, grids and starts; every
 * pose tried is evaluated from the model's state before the call, and the model's state is
 * then that of the pose returned), so that an evaluate at the pose found carries the load to
 * the force tolerance 1e-6; the model then holds its patches (fastnorm_wheelset_patch reads
 * them), also when the search ends not converged (its pose of smallest residual). */
FASTNORM_C_API int fastnorm_wheelset_equilibrium(fastnorm_wheelset* model, double load, double y, double yaw,
                                                 fastnorm_equilibrium* result);

/* Contact tables (docs/tables.md §4): results precomputed over (lateral shift y in m, yaw in
 * rad, load in N) per wheel/rail profile pair, read from the file `fastnorm-table export`
 * writes, looked up in well under a microsecond (multilinear) or about one (PCHIP). A table is
 * read-only once read: one table may be looked up by many threads at once. */
typedef struct fastnorm_table fastnorm_table;

enum { FASTNORM_TABLE_MULTILINEAR = 0, FASTNORM_TABLE_PCHIP = 1 };

/* What a lookup found (an answer, not an error: fastnorm_table_lookup returns FASTNORM_OK). */
enum {
  FASTNORM_TABLE_FOUND = 0,           /* the outputs are written */
  FASTNORM_TABLE_OUT_OF_RANGE = 1,    /* a coordinate outside its axis, or NaN; nothing written */
  FASTNORM_TABLE_TOPOLOGY_CHANGE = 2, /* the cell's corners differ in patches or status: evaluate directly */
  FASTNORM_TABLE_FAILED_CASE = 3      /* the cell's corners hold failed cases; nothing written */
};

FASTNORM_C_API int fastnorm_table_read(const char* path, fastnorm_table** table);
FASTNORM_C_API void fastnorm_table_destroy(fastnorm_table* table);
/* Its profile pairs and outputs per case (either pointer may be NULL). */
FASTNORM_C_API int fastnorm_table_info(const fastnorm_table* table, int* pairs, int* outputs);
/* The position of the output called name (e.g. "fn_left_n"), or FASTNORM_ERROR_ARGUMENT. */
FASTNORM_C_API int fastnorm_table_output_index(const fastnorm_table* table, const char* name, int* index);
/* The name and unit of output `index` (pointers into the table, valid while it lives). */
FASTNORM_C_API int fastnorm_table_output_name(const fastnorm_table* table, int index, const char** name,
                                              const char** unit);
/* The outputs of pair `pair` (0-based) at (y, yaw, load) into out[0 .. outputs) when *found is
 * FASTNORM_TABLE_FOUND; out is not touched otherwise. interpolation: FASTNORM_TABLE_*. */
FASTNORM_C_API int fastnorm_table_lookup(const fastnorm_table* table, int pair, double y, double yaw, double load,
                                         int interpolation, double* out, int* found);

#ifdef __cplusplus
}
#endif

#endif /* FASTNORM_C_H */
