/* The C API from C (a CTest test): a CONTACT peer case solved by NORM through the API
 * agrees with CONTACT's stored solution as the C++ tests require (force 1e-7, pressures 1e-6
 * of the peak, the same contact count); a .case written and read back is unchanged; the
 * sequence call gives the cold answer; bad input returns FASTNORM_ERROR_ARGUMENT with a
 * message naming the argument; the wheelset model's equilibrium carries its load, and its
 * copies step as a model alone; steady rolling gives CONTACT's creep forces on its large-spin
 * Hertz example; a case's tangential line is read; a contact table written by hand from its
 * documented format is looked up.
 * Usage: fastnorm_c_api_test PEER_CASE_FILE SCRATCH_DIR */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fastnorm_c.h"

static int failures = 0;

#define EXPECT(condition)                                                     \
  do {                                                                        \
    if (!(condition)) {                                                       \
      fprintf(stderr, "%s:%d: FAILED: %s\n", __FILE__, __LINE__, #condition); \
      ++failures;                                                             \
    }                                                                         \
  } while (0)

/* Stops the test when a call that must work fails. */
#define REQUIRE_OK(call)                                                                         \
  do {                                                                                           \
    if ((call) != FASTNORM_OK) {                                                                 \
      fprintf(stderr, "%s:%d: %s failed: %s\n", __FILE__, __LINE__, #call, fastnorm_last_error()); \
      exit(1);                                                                                   \
    }                                                                                            \
  } while (0)

static double max_abs_difference(const double* a, const double* b, int count) {
  double largest = 0;
  for (int k = 0; k < count; ++k) largest = fmax(largest, fabs(a[k] - b[k]));
  return largest;
}

static double largest(const double* values, int count) {
  double result = values[0];
  for (int k = 1; k < count; ++k) result = fmax(result, values[k]);
  return result;
}

static void peer_case_through_the_api(const char* path, const char* scratch) {
  fastnorm_case* problem = NULL;
  REQUIRE_OK(fastnorm_case_read(path, &problem));
  fastnorm_grid grid;
  fastnorm_material material;
  int force_control = 0;
  double control = 0;
  REQUIRE_OK(fastnorm_case_info(problem, &grid, &material, &force_control, &control));
  EXPECT(force_control == 1);
  const int size = grid.mx * grid.my;
  double* h = malloc(sizeof(double) * (size_t)size);
  double* stored = malloc(sizeof(double) * (size_t)size);
  double* pressure = malloc(sizeof(double) * (size_t)size);
  double* again = malloc(sizeof(double) * (size_t)size);
  fastnorm_result reference, result, next;
  REQUIRE_OK(fastnorm_case_undeformed_distance(problem, h));
  REQUIRE_OK(fastnorm_case_result(problem, stored, &reference));

  fastnorm_solver* solver = NULL;
  REQUIRE_OK(fastnorm_solver_create("norm", &grid, &material, NULL, &solver));
  REQUIRE_OK(fastnorm_solve_force(solver, h, control, pressure, &result));
  const double peak = largest(stored, size);
  printf("%s: status %s, Fn %.9g N (CONTACT %.9g), max |dp|/pmax %.3g, %d elements in contact\n", path,
         fastnorm_status_name(result.status), result.normal_force, reference.normal_force,
         max_abs_difference(pressure, stored, size) / peak, result.contact_count);
  EXPECT(result.status == FASTNORM_CONVERGED);
  EXPECT(fabs(result.normal_force / reference.normal_force - 1) < 1e-7);
  EXPECT(max_abs_difference(pressure, stored, size) < 1e-6 * peak);
  EXPECT(result.contact_count == reference.contact_count);
  EXPECT(result.at_edge == 0);

  /* The sequence call: the cold answer, then the stiffness at its contact set. */
  REQUIRE_OK(fastnorm_solve_next(solver, h, control, again, &next));
  EXPECT(max_abs_difference(again, pressure, size) <= 1e-12 * peak);
  double stiffness = 0;
  REQUIRE_OK(fastnorm_normal_stiffness(solver, &stiffness));
  EXPECT(stiffness > 0 && isfinite(stiffness));

  /* Written with its solution and read back: the same numbers. */
  char written[4096];
  snprintf(written, sizeof written, "%s/c_api_roundtrip.case", scratch);
  REQUIRE_OK(fastnorm_case_write(written, "written by the C API test", &grid, &material, 1, control, h, pressure,
                                 &result));
  fastnorm_case* reread = NULL;
  REQUIRE_OK(fastnorm_case_read(written, &reread));
  fastnorm_result reread_result;
  REQUIRE_OK(fastnorm_case_undeformed_distance(reread, again));
  EXPECT(max_abs_difference(again, h, size) == 0);
  REQUIRE_OK(fastnorm_case_result(reread, again, &reread_result));
  EXPECT(max_abs_difference(again, pressure, size) == 0);
  EXPECT(reread_result.normal_force == result.normal_force);

  fastnorm_case_destroy(reread);
  fastnorm_solver_destroy(solver);
  fastnorm_case_destroy(problem);
  free(h);
  free(stored);
  free(pressure);
  free(again);
}

static void expect_error(int code, const char* fragment) {
  EXPECT(code == FASTNORM_ERROR_ARGUMENT);
  if (!strstr(fastnorm_last_error(), fragment)) {
    fprintf(stderr, "FAILED: message '%s' does not name '%s'\n", fastnorm_last_error(), fragment);
    ++failures;
  }
}

static void bad_input_is_named(void) {
  const fastnorm_grid grid = {8, 8, 1e-4, 1e-4, -3.5e-4, -3.5e-4};
  const fastnorm_grid no_rows = {8, 0, 1e-4, 1e-4, 0, 0};
  const fastnorm_material steel = {2.1e11, 0.3, 2.1e11, 0.3};
  const fastnorm_material rubber_ratio = {2.1e11, 0.7, 2.1e11, 0.3};
  fastnorm_solver* solver = NULL;
  expect_error(fastnorm_solver_create("newton", &grid, &steel, NULL, &solver), "newton");
  EXPECT(solver == NULL);
  expect_error(fastnorm_solver_create("norm", &no_rows, &steel, NULL, &solver), "my");
  expect_error(fastnorm_solver_create("norm", &grid, &rubber_ratio, NULL, &solver), "poisson_ratio_1");
  expect_error(fastnorm_solver_create("norm", NULL, &steel, NULL, &solver), "grid");
  REQUIRE_OK(fastnorm_solver_create("elliptic", &grid, &steel, NULL, &solver));
  double h[64], pressure[64];
  fastnorm_result result;
  for (int k = 0; k < 64; ++k) h[k] = 1e-6;
  h[17] = NAN;
  expect_error(fastnorm_solve_approach(solver, h, pressure, &result), "undeformed_distance[17]");
  expect_error(fastnorm_solve_approach(solver, NULL, pressure, &result), "h must not be NULL");
  expect_error(fastnorm_solve_force(solver, h, -5.0, pressure, &result), "normal_force");
  for (int k = 0; k < 64; ++k) h[k] = 1e-6;
  expect_error(fastnorm_solve_next(solver, h, NAN, pressure, &result), "normal_force must be finite");
  fastnorm_solver_destroy(solver);
  fastnorm_case* problem = NULL;
  expect_error(fastnorm_case_read("/nonexistent/file.case", &problem), "/nonexistent/file.case");
  EXPECT(strcmp(fastnorm_status_name(FASTNORM_CYCLED), "cycled") == 0);
  EXPECT(strcmp(fastnorm_status_name(42), "unknown") == 0);
}

/* The wheelset model's defaults with the elliptic basis on 30 elements: quick to solve. */
static fastnorm_wheelset_options elliptic_on_30_elements(void) {
  fastnorm_wheelset_options options;
  fastnorm_wheelset_options_default(&options);
  options.solver = "elliptic";
  options.elements = 30;
  return options;
}

static void wheelset_equilibrium_and_time_step(void) {
  fastnorm_wheelset_options options = elliptic_on_30_elements();
  fastnorm_wheelset* model = NULL;
  REQUIRE_OK(fastnorm_wheelset_create(&options, &model));
  /* Zeroed structs, and the model before any evaluate, read "not solved". */
  fastnorm_equilibrium zeroed;
  memset(&zeroed, 0, sizeof zeroed);
  EXPECT(zeroed.status == FASTNORM_EQUILIBRIUM_NOT_SOLVED);
  fastnorm_step_status step;
  REQUIRE_OK(fastnorm_wheelset_step_status(model, &step));
  EXPECT(step.code == FASTNORM_STEP_NOT_SOLVED);
  const double load = 2e5;
  fastnorm_equilibrium found;
  REQUIRE_OK(fastnorm_wheelset_equilibrium(model, load, 3e-3, 0.0, &found));
  printf("equilibrium at y = 3 mm: status %d, z %.6g m, roll %.6g rad, vertical force %.6g N, patches %d + %d\n",
         found.status, found.pose.z, found.pose.roll, found.vertical_force, found.patch_count[0],
         found.patch_count[1]);
  EXPECT(found.status == FASTNORM_EQUILIBRIUM_CONVERGED);
  EXPECT(fabs(found.vertical_force / load - 1) < 1e-5);
  EXPECT(found.patch_count[0] >= 1 && found.patch_count[1] >= 1);

  /* One time step at the pose found: per patch, the pressures sum to its force. */
  double force[3], moment[3];
  REQUIRE_OK(fastnorm_wheelset_evaluate(model, &found.pose, force, moment));
  double vertical = 0;
  for (int wheel = 0; wheel < 2; ++wheel) {
    int count = 0;
    REQUIRE_OK(fastnorm_wheelset_patch_count(model, wheel, &count));
    for (int n = 0; n < count; ++n) {
      fastnorm_patch patch;
      REQUIRE_OK(fastnorm_wheelset_patch(model, wheel, n, &patch));
      const int size = patch.grid.mx * patch.grid.my;
      double* pressure = malloc(sizeof(double) * (size_t)size);
      REQUIRE_OK(fastnorm_wheelset_patch_pressure(model, wheel, n, pressure));
      double sum = 0;
      for (int k = 0; k < size; ++k) sum += pressure[k];
      EXPECT(fabs(sum * patch.grid.dx * patch.grid.dy / patch.normal_force - 1) < 1e-9);
      EXPECT(patch.stiffness > 0);
      EXPECT(patch.flange_climb == 0);
      EXPECT(patch.status == FASTNORM_CONVERGED);
      /* The pressures placed in the track frame (reference + x e_x + s t_s): their centroid
       * is the library's pressure centre, and the force on the wheel is -Fn n. */
      double placed[3] = {0, 0, 0};
      for (int j = 0; j < patch.grid.my; ++j) {
        for (int i = 0; i < patch.grid.mx; ++i) {
          const double p = pressure[i + patch.grid.mx * j];
          const double x = patch.grid.x0 + i * patch.grid.dx, s = patch.grid.y0 + j * patch.grid.dy;
          for (int c = 0; c < 3; ++c) placed[c] += p * (patch.reference[c] + x * patch.e_x[c] + s * patch.t_s[c]);
        }
      }
      for (int c = 0; c < 3; ++c) {
        EXPECT(fabs(placed[c] / sum - patch.pressure_centre[c]) < 1e-12);
        EXPECT(fabs(patch.force[c] + patch.normal_force * patch.normal[c]) <= 1e-9 * patch.normal_force);
      }
      vertical += patch.force[2];
      free(pressure);
    }
  }
  printf("time step at that pose: vertical force on the wheelset %.6g N\n", force[2]);
  EXPECT(fabs(vertical - force[2]) <= 1e-9 * fabs(force[2]));
  /* The equilibrium is the model's own: at its pose the model carries the load. */
  EXPECT(fabs(-force[2] / load - 1) <= 1e-6);
  REQUIRE_OK(fastnorm_wheelset_step_status(model, &step));
  EXPECT(step.code == FASTNORM_STEP_OK && step.wheel == -1 && step.patch == -1);
  /* A reset forgets the history: status and patches read as after create. */
  REQUIRE_OK(fastnorm_wheelset_reset(model));
  REQUIRE_OK(fastnorm_wheelset_step_status(model, &step));
  EXPECT(step.code == FASTNORM_STEP_NOT_SOLVED);
  int after_reset = -1;
  REQUIRE_OK(fastnorm_wheelset_patch_count(model, 1, &after_reset));
  EXPECT(after_reset == 0);
  fastnorm_patch unused;
  expect_error(fastnorm_wheelset_patch(model, 2, 0, &unused), "wheel");
  fastnorm_wheelset_destroy(model);

  /* h's accuracy is checked by name. */
  options.distance_tolerance = -1;
  expect_error(fastnorm_wheelset_create(&options, &model), "tolerance");
  options.distance_tolerance = 1e-10;

  /* A failed patch solve is a status: one active-set iteration cannot reach NORM's set. */
  options.solver = "norm";
  options.max_iterations = 1;
  REQUIRE_OK(fastnorm_wheelset_create(&options, &model));
  const int code = fastnorm_wheelset_evaluate(model, &found.pose, force, moment);
  printf("a starved solve: %s\n", fastnorm_last_error());
  EXPECT(code == FASTNORM_ERROR_PATCH_FAILED);
  EXPECT(strstr(fastnorm_last_error(), "left wheel, patch 0") != NULL);
  EXPECT(strstr(fastnorm_last_error(), "iteration limit") != NULL);
  REQUIRE_OK(fastnorm_wheelset_step_status(model, &step));
  EXPECT(step.code == FASTNORM_STEP_PATCH_FAILED && step.wheel == 0 && step.patch == 0 &&
         step.solver_status == FASTNORM_ITERATION_LIMIT);
  REQUIRE_OK(fastnorm_wheelset_patch(model, 0, 0, &unused));
  EXPECT(unused.status == FASTNORM_ITERATION_LIMIT);
  fastnorm_wheelset_destroy(model);
}

/* Trial steps (docs/wheel-rail.md §9): a model that saves its history, evaluates a trial pose
 * far off and restores, then evaluates the next step, gives bit for bit the forces of a model
 * that evaluated the steps alone; a restore with nothing saved is refused by name. */
static void wheelset_trial_steps(void) {
  fastnorm_wheelset_options options = elliptic_on_30_elements();
  fastnorm_wheelset *tried = NULL, *plain = NULL;
  REQUIRE_OK(fastnorm_wheelset_create(&options, &tried));
  REQUIRE_OK(fastnorm_wheelset_create(&options, &plain));
  expect_error(fastnorm_wheelset_restore_history(tried), "no history saved");
  fastnorm_equilibrium found; /* both models in the same state: the same equilibrium */
  REQUIRE_OK(fastnorm_wheelset_equilibrium(tried, 2e5, 1e-3, 0.0, &found));
  REQUIRE_OK(fastnorm_wheelset_equilibrium(plain, 2e5, 1e-3, 0.0, &found));
  double tried_force[3], plain_force[3];
  for (int step = 1; step <= 3; ++step) {
    fastnorm_pose pose = found.pose;
    pose.y += 0.2e-3 * step;
    REQUIRE_OK(fastnorm_wheelset_save_history(tried));
    fastnorm_pose trial = pose;
    trial.y += 1.5e-3;
    trial.z += 0.03e-3;
    REQUIRE_OK(fastnorm_wheelset_evaluate(tried, &trial, tried_force, NULL));
    REQUIRE_OK(fastnorm_wheelset_restore_history(tried));
    REQUIRE_OK(fastnorm_wheelset_evaluate(tried, &pose, tried_force, NULL));
    REQUIRE_OK(fastnorm_wheelset_evaluate(plain, &pose, plain_force, NULL));
    for (int c = 0; c < 3; ++c) EXPECT(tried_force[c] == plain_force[c]);
  }
  printf("trial steps restored: vertical force %.10g N, as without the trials\n", tried_force[2]);
  fastnorm_wheelset_destroy(tried);
  fastnorm_wheelset_destroy(plain);
}

/* The patches of `wheel` that two models read: the same Fn and pressures, bit for bit. */
static void expect_same_patches(const fastnorm_wheelset* model, const fastnorm_wheelset* other, int wheel) {
  int count = -1, other_count = -2;
  REQUIRE_OK(fastnorm_wheelset_patch_count(model, wheel, &count));
  REQUIRE_OK(fastnorm_wheelset_patch_count(other, wheel, &other_count));
  EXPECT(count == other_count && count >= 1);
  for (int n = 0; n < count && n < other_count; ++n) {
    fastnorm_patch patch, other_patch;
    REQUIRE_OK(fastnorm_wheelset_patch(model, wheel, n, &patch));
    REQUIRE_OK(fastnorm_wheelset_patch(other, wheel, n, &other_patch));
    EXPECT(patch.normal_force == other_patch.normal_force);
    const int size = patch.grid.mx * patch.grid.my;
    EXPECT(size == other_patch.grid.mx * other_patch.grid.my);
    double* pressure = malloc(sizeof(double) * (size_t)size);
    double* other_pressure = malloc(sizeof(double) * (size_t)size);
    REQUIRE_OK(fastnorm_wheelset_patch_pressure(model, wheel, n, pressure));
    REQUIRE_OK(fastnorm_wheelset_patch_pressure(other, wheel, n, other_pressure));
    EXPECT(memcmp(pressure, other_pressure, sizeof(double) * (size_t)size) == 0);
    free(pressure);
    free(other_pressure);
  }
}

/* Copies (docs/wheel-rail.md §9, "Models of a vehicle"): a copy reads the patches of its
 * original's last call, an equilibrium's or an evaluate's, and keeps them when the original
 * is destroyed; it steps on from its original's history as a model that took the same calls
 * itself, bit for bit; a missing argument is refused by name. */
static void wheelset_copies(void) {
  fastnorm_wheelset_options options = elliptic_on_30_elements();
  fastnorm_wheelset *original = NULL, *after_equilibrium = NULL, *after_step = NULL, *alone = NULL;
  REQUIRE_OK(fastnorm_wheelset_create(&options, &original));
  REQUIRE_OK(fastnorm_wheelset_create(&options, &alone));
  fastnorm_equilibrium found;
  REQUIRE_OK(fastnorm_wheelset_equilibrium(original, 2e5, 1e-3, 0.0, &found));
  REQUIRE_OK(fastnorm_wheelset_equilibrium(alone, 2e5, 1e-3, 0.0, &found));
  REQUIRE_OK(fastnorm_wheelset_copy(original, &after_equilibrium));
  for (int wheel = 0; wheel < 2; ++wheel) expect_same_patches(after_equilibrium, alone, wheel);

  fastnorm_pose pose = found.pose;
  double force[3], alone_force[3];
  pose.y += 0.2e-3;
  REQUIRE_OK(fastnorm_wheelset_evaluate(original, &pose, force, NULL));
  REQUIRE_OK(fastnorm_wheelset_evaluate(alone, &pose, alone_force, NULL));
  REQUIRE_OK(fastnorm_wheelset_copy(original, &after_step));
  fastnorm_wheelset_destroy(original); /* the copies hold what they read and share */
  for (int wheel = 0; wheel < 2; ++wheel) expect_same_patches(after_step, alone, wheel);

  /* The equilibrium's copy takes the step the others took; then all three step on alike. */
  double copy_force[3];
  REQUIRE_OK(fastnorm_wheelset_evaluate(after_equilibrium, &pose, copy_force, NULL));
  for (int c = 0; c < 3; ++c) EXPECT(copy_force[c] == alone_force[c]);
  for (int step = 2; step <= 3; ++step) {
    pose.y += 0.2e-3;
    pose.yaw = 1e-3 * step;
    REQUIRE_OK(fastnorm_wheelset_evaluate(alone, &pose, alone_force, NULL));
    REQUIRE_OK(fastnorm_wheelset_evaluate(after_step, &pose, force, NULL));
    REQUIRE_OK(fastnorm_wheelset_evaluate(after_equilibrium, &pose, copy_force, NULL));
    for (int c = 0; c < 3; ++c) EXPECT(force[c] == alone_force[c] && copy_force[c] == alone_force[c]);
  }
  printf("copies step as a model alone: vertical force %.10g N\n", force[2]);

  fastnorm_wheelset* unused = NULL;
  expect_error(fastnorm_wheelset_copy(NULL, &unused), "model");
  EXPECT(unused == NULL);
  expect_error(fastnorm_wheelset_copy(alone, NULL), "copy");
  fastnorm_wheelset_destroy(after_equilibrium);
  fastnorm_wheelset_destroy(after_step);
  fastnorm_wheelset_destroy(alone);
}

/* Creep forces in the time loop (docs/wheel-rail.md §10): a rolling wheelset with a yaw
 * angle; per patch the tractions sum to the creep forces on the rail, the creep force on the
 * wheel is their opposite along e_x and t_s, and the patch force is -Fn n plus it. */
static void wheelset_creep_forces(void) {
  fastnorm_wheelset_options options = elliptic_on_30_elements();
  fastnorm_wheelset* model = NULL;
  REQUIRE_OK(fastnorm_wheelset_create(&options, &model));
  fastnorm_equilibrium found; /* 200 kN on the wheelset at yaw 3 mrad */
  REQUIRE_OK(fastnorm_wheelset_equilibrium(model, 2e5, 0.0, 3e-3, &found));
  const fastnorm_pose pose = found.pose;
  const fastnorm_velocity velocity = {30, 0, 0, 0, 0, -30 / 0.45};
  double force[3];
  expect_error(fastnorm_wheelset_evaluate_moving(model, &pose, &velocity, force, NULL), "friction");
  fastnorm_wheelset_destroy(model);
  options.friction = 0.3;
  REQUIRE_OK(fastnorm_wheelset_create(&options, &model));
  REQUIRE_OK(fastnorm_wheelset_evaluate(model, &pose, force, NULL));
  fastnorm_patch patch;
  REQUIRE_OK(fastnorm_wheelset_patch(model, 1, 0, &patch));
  EXPECT(patch.creep.status == FASTNORM_NOT_SOLVED);
  double* traction_x = malloc(sizeof(double) * (size_t)(patch.grid.mx * patch.grid.my));
  double* traction_s = malloc(sizeof(double) * (size_t)(patch.grid.mx * patch.grid.my));
  expect_error(fastnorm_wheelset_patch_traction(model, 1, 0, traction_x, traction_s), "evaluate_moving");
  free(traction_x);
  free(traction_s);

  REQUIRE_OK(fastnorm_wheelset_evaluate_moving(model, &pose, &velocity, force, NULL));
  double lateral = 0;
  for (int wheel = 0; wheel < 2; ++wheel) {
    int count = 0;
    REQUIRE_OK(fastnorm_wheelset_patch_count(model, wheel, &count));
    for (int n = 0; n < count; ++n) {
      REQUIRE_OK(fastnorm_wheelset_patch(model, wheel, n, &patch));
      const int size = patch.grid.mx * patch.grid.my;
      traction_x = malloc(sizeof(double) * (size_t)size);
      traction_s = malloc(sizeof(double) * (size_t)size);
      REQUIRE_OK(fastnorm_wheelset_patch_traction(model, wheel, n, traction_x, traction_s));
      double fx = 0, fs = 0;
      for (int k = 0; k < size; ++k) fx += traction_x[k], fs += traction_s[k];
      fx *= patch.grid.dx * patch.grid.dy, fs *= patch.grid.dx * patch.grid.dy;
      printf("wheel %d patch %d: xi %.4g eta %.4g phi %.4g rad/m, Fx %.6g N, Fs %.6g N on the rail, %d adhesion, %d slip\n",
             wheel, n, patch.creepage.longitudinal, patch.creepage.lateral, patch.creepage.spin, patch.creep.force_x,
             patch.creep.force_y, patch.creep.adhesion_elements, patch.creep.slip_elements);
      EXPECT(patch.creep.status == FASTNORM_CONVERGED);
      EXPECT(patch.creepage.lateral > 2e-3 && patch.creepage.lateral < 4e-3); /* yaw 3 mrad */
      EXPECT(fabs(fx - patch.creep.force_x) <= 1e-9 * fabs(patch.creep.force_y));
      EXPECT(fabs(fs - patch.creep.force_y) <= 1e-9 * fabs(patch.creep.force_y));
      EXPECT(patch.creep.force_y < 0); /* against eta > 0 on the rail */
      for (int c = 0; c < 3; ++c) {
        const double creep = -(patch.creep.force_x * patch.e_x[c] + patch.creep.force_y * patch.t_s[c]);
        EXPECT(fabs(patch.creep_force[c] - creep) <= 1e-9 * patch.normal_force);
        EXPECT(fabs(patch.force[c] - (-patch.normal_force * patch.normal[c] + creep)) <= 1e-9 * patch.normal_force);
      }
      lateral += patch.force[1];
      free(traction_x);
      free(traction_s);
    }
  }
  EXPECT(fabs(lateral - force[1]) <= 1e-9 * fabs(force[2]));
  /* FASTSIM instead of strip theory: the same kind of answer, a few per cent of muFn apart. */
  fastnorm_wheelset* fastsim_model = NULL;
  options.creep_method = FASTNORM_FASTSIM;
  REQUIRE_OK(fastnorm_wheelset_create(&options, &fastsim_model));
  double fastsim_force[3];
  REQUIRE_OK(fastnorm_wheelset_evaluate_moving(fastsim_model, &pose, &velocity, fastsim_force, NULL));
  EXPECT(fastsim_force[1] != force[1]);
  EXPECT(fabs(fastsim_force[1] - force[1]) <= 0.1 * 0.3 * fabs(force[2]));
  fastnorm_wheelset_destroy(fastsim_model);
  options.creep_method = 7;
  expect_error(fastnorm_wheelset_create(&options, &fastsim_model), "creep_method");
  options.creep_method = FASTNORM_STRIP_THEORY;
  const fastnorm_velocity standing = {0, 0, 0, 0, 0, 0};
  expect_error(fastnorm_wheelset_evaluate_moving(model, &pose, &standing, force, NULL), "velocity.forward");
  expect_error(fastnorm_wheelset_evaluate_moving(model, &pose, NULL, force, NULL), "velocity");
  fastnorm_wheelset_destroy(model);
  options.friction = -1;
  expect_error(fastnorm_wheelset_create(&options, &model), "friction");
}

/* CONTACT's large-spin Hertz example (docs/tangential.md §5): NORM in force control, then
 * steady rolling; CONTACT's exact answer is Fs = -14940 N, Mz = -48.21 N m, 356 elements in
 * adhesion and 920 in slip. */
/* A case's tangential line read through the API, as the case file states it; a case
 * without one (the round trip's) says so. */
static void case_rolling_is_read(const char* scratch) {
  char path[4096];
  snprintf(path, sizeof path, "%s/c_api_rolling.case", scratch);
  FILE* out = fopen(path, "w");
  EXPECT(out != NULL);
  if (!out) return;
  fprintf(out,
          "fastnorm-case 1\nname rolling\nsource c_api_test\n"
          "grid mx 2 my 2 dx 1e-3 dy 1e-3 x0 0 y0 0\nmaterial E 2.1e11 nu 0.3\ncontrol approach 1e-6\n"
          "tangential friction 0.3 xi 1e-3 eta -5e-4 phi 0.4 xc 1e-4 yc -2e-4 rolling -x\n"
          "h\n-1e-6 -1e-6\n-1e-6 -1e-6\n");
  fclose(out);
  fastnorm_case* problem = NULL;
  REQUIRE_OK(fastnorm_case_read(path, &problem));
  double friction = 0;
  fastnorm_creepage creepage;
  int rolling = 0;
  REQUIRE_OK(fastnorm_case_rolling(problem, &friction, &creepage, &rolling));
  EXPECT(friction == 0.3 && rolling == -1);
  EXPECT(creepage.longitudinal == 1e-3 && creepage.lateral == -5e-4 && creepage.spin == 0.4);
  EXPECT(creepage.spin_centre_x == 1e-4 && creepage.spin_centre_y == -2e-4);
  fastnorm_case_destroy(problem);
  snprintf(path, sizeof path, "%s/c_api_roundtrip.case", scratch);
  REQUIRE_OK(fastnorm_case_read(path, &problem));
  expect_error(fastnorm_case_rolling(problem, &friction, &creepage, &rolling), "no tangential line");
  expect_error(fastnorm_case_rolling(problem, NULL, &creepage, &rolling), "friction");
  fastnorm_case_destroy(problem);
}

static void steady_rolling_meets_contact(void) {
  const fastnorm_grid grid = {44, 44, 0.4e-3, 0.2e-3, -43 * 0.4e-3 / 2, -43 * 0.2e-3 / 2};
  const fastnorm_material material = {2 * 82e9 * 1.28, 0.28, 2 * 82e9 * 1.28, 0.28};
  const int size = grid.mx * grid.my;
  double* h = malloc(sizeof(double) * (size_t)size);
  double* pressure = malloc(sizeof(double) * (size_t)size);
  double* traction_x = malloc(sizeof(double) * (size_t)size);
  double* traction_y = malloc(sizeof(double) * (size_t)size);
  for (int k = 0; k < size; ++k) {
    const double x = grid.x0 + grid.dx * (k % grid.mx), y = grid.y0 + grid.dy * (k / grid.mx);
    h[k] = 0.8464 * x * x + 2.406 * y * y;
  }
  fastnorm_solver* norm = NULL;
  fastnorm_result normal;
  REQUIRE_OK(fastnorm_solver_create("norm", &grid, &material, NULL, &norm));
  REQUIRE_OK(fastnorm_solve_force(norm, h, 82e3, pressure, &normal));
  fastnorm_solver_destroy(norm);
  const fastnorm_creepage creepage = {0, -6.25e-4, 0.625, 0, 0};
  fastnorm_tangential_result rolling;
  REQUIRE_OK(fastnorm_steady_rolling(&grid, &material, pressure, 0.3, &creepage, 1, NULL, traction_x, traction_y,
                                     &rolling));
  const double mu_fn = 0.3 * 82e3;
  EXPECT(rolling.status == FASTNORM_CONVERGED);
  EXPECT(fabs(rolling.force_y + 14940) <= 0.015 * mu_fn);
  EXPECT(fabs(rolling.spin_moment + 48.21) <= 0.02 * mu_fn * sqrt(8e-3 * 4e-3));
  EXPECT(rolling.adhesion_elements == 356 && rolling.slip_elements == 920);
  double sum = 0;
  for (int k = 0; k < size; ++k) sum += traction_y[k] * grid.dx * grid.dy;
  EXPECT(fabs(sum - rolling.force_y) <= 1e-9 * mu_fn);
  /* CONTACT's stopping rule at its EPS of 1e-5: fewer sweeps, the same areas, the forces
   * within 1e-6 mu Fn (docs/tangential.md §7), its residual the rms ratio it bounds. */
  fastnorm_tangential_options options = {FASTNORM_STOP_RMS_CHANGE, 0, 1e-5};
  fastnorm_tangential_result loose;
  REQUIRE_OK(fastnorm_steady_rolling(&grid, &material, pressure, 0.3, &creepage, 1, &options, traction_x, traction_y,
                                     &loose));
  EXPECT(loose.status == FASTNORM_CONVERGED && loose.residual <= 1e-5);
  EXPECT(loose.sweeps < rolling.sweeps);
  EXPECT(loose.adhesion_elements == 356 && loose.slip_elements == 920);
  EXPECT(fabs(loose.force_y - rolling.force_y) <= 1e-6 * mu_fn);
  options.max_sweeps = 3; /* a limit met first */
  REQUIRE_OK(fastnorm_steady_rolling(&grid, &material, pressure, 0.3, &creepage, 1, &options, traction_x, traction_y,
                                     &loose));
  EXPECT(loose.status == FASTNORM_ITERATION_LIMIT && loose.sweeps == 3);
  expect_error(fastnorm_steady_rolling(&grid, &material, pressure, -0.3, &creepage, 1, NULL, traction_x, traction_y,
                                       &rolling),
               "friction");
  expect_error(fastnorm_steady_rolling(&grid, &material, pressure, 0.3, &creepage, 0, NULL, traction_x, traction_y,
                                       &rolling),
               "rolling");
  expect_error(fastnorm_steady_rolling(&grid, &material, pressure, 0.3, NULL, 1, NULL, traction_x, traction_y, &rolling),
               "creepage");
  const fastnorm_tangential_options bad_stop = {2, 0, 0}, bad_sweeps = {0, -1, 0}, bad_tolerance = {0, 0, 1.5};
  expect_error(fastnorm_steady_rolling(&grid, &material, pressure, 0.3, &creepage, 1, &bad_stop, traction_x, traction_y,
                                       &rolling),
               "options.stop");
  expect_error(fastnorm_steady_rolling(&grid, &material, pressure, 0.3, &creepage, 1, &bad_sweeps, traction_x,
                                       traction_y, &rolling),
               "options.max_sweeps");
  expect_error(fastnorm_steady_rolling(&grid, &material, pressure, 0.3, &creepage, 1, &bad_tolerance, traction_x,
                                       traction_y, &rolling),
               "options.tolerance");
  free(h);
  free(pressure);
  free(traction_x);
  free(traction_y);
}

/* A contact table written here byte by byte from docs/tables.md's description of the file
 * (so the format, not only the C++ writer, is what the reader accepts), then looked up:
 * y = (-1, 0, 2) mm, yaw = (0, 10) mrad, one load, outputs fn = 1000 + 2e5 y + 3e3 yaw (N)
 * and y itself (m); the case (y = 2 mm, yaw = 10 mrad) has another topology. */
static void write_u32(FILE* file, unsigned value) {
  const uint32_t v = (uint32_t)value;
  fwrite(&v, sizeof v, 1, file);
}

static void write_text(FILE* file, const char* text) {
  write_u32(file, (unsigned)strlen(text));
  fwrite(text, 1, strlen(text), file);
}

static double table_fn(double y, double yaw) { return 1000 + 2e5 * y + 3e3 * yaw; }

static void contact_table_lookup(const char* scratch) {
  char path[1024];
  snprintf(path, sizeof path, "%s/c_api_test.fntable", scratch);
  const double shifts[3] = {-1e-3, 0.0, 2e-3}, yaws[2] = {0.0, 0.01}, load = 1e5;
  FILE* file = fopen(path, "wb");
  EXPECT(file != NULL);
  if (!file) return;
  fwrite("FNTABLE\0", 1, 8, file);
  write_u32(file, 2);                                          /* version */
  write_u32(file, 1), write_u32(file, 3), write_u32(file, 2);  /* pairs, shifts, yaws */
  write_u32(file, 1), write_u32(file, 2);                      /* loads, outputs */
  fwrite(shifts, sizeof(double), 3, file);
  fwrite(yaws, sizeof(double), 2, file);
  fwrite(&load, sizeof(double), 1, file);
  write_text(file, "S1002/UIC60");
  write_text(file, "fn_n"), write_text(file, "shift_m");
  write_text(file, "N"), write_text(file, "m");
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) {
      const double values[2] = {table_fn(shifts[i], yaws[j]), shifts[i]};
      fwrite(values, sizeof(double), 2, file);
    }
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) {
      const int32_t code = (i == 2 && j == 1) ? 3 : 1;
      fwrite(&code, sizeof code, 1, file);
    }
  write_u32(file, 1); /* measured derivatives along y follow: the data's own, 2e5 and 1 */
  for (int c = 0; c < 6; ++c) {
    const double derivatives[2] = {2e5, 1.0};
    fwrite(derivatives, sizeof(double), 2, file);
  }
  fclose(file);

  fastnorm_table* table = NULL;
  REQUIRE_OK(fastnorm_table_read(path, &table));
  int pairs = 0, outputs = 0, index = -1;
  REQUIRE_OK(fastnorm_table_info(table, &pairs, &outputs));
  EXPECT(pairs == 1 && outputs == 2);
  REQUIRE_OK(fastnorm_table_output_index(table, "shift_m", &index));
  EXPECT(index == 1);
  const char *name = NULL, *unit = NULL;
  REQUIRE_OK(fastnorm_table_output_name(table, 0, &name, &unit));
  EXPECT(strcmp(name, "fn_n") == 0 && strcmp(unit, "N") == 0);

  double out[2] = {-1, -1};
  int found = -1;
  for (int interpolation = FASTNORM_TABLE_MULTILINEAR; interpolation <= FASTNORM_TABLE_PCHIP; ++interpolation) {
    /* Linear data: both interpolations give it back. */
    REQUIRE_OK(fastnorm_table_lookup(table, 0, -0.4e-3, 0.003, load, interpolation, out, &found));
    EXPECT(found == FASTNORM_TABLE_FOUND);
    EXPECT(fabs(out[0] - table_fn(-0.4e-3, 0.003)) < 1e-9 && fabs(out[1] + 0.4e-3) < 1e-15);
    REQUIRE_OK(fastnorm_table_lookup(table, 0, 1e-3, 0.005, load, interpolation, out, &found));
    EXPECT(found == FASTNORM_TABLE_TOPOLOGY_CHANGE);
    REQUIRE_OK(fastnorm_table_lookup(table, 0, 3e-3, 0.005, load, interpolation, out, &found));
    EXPECT(found == FASTNORM_TABLE_OUT_OF_RANGE);
  }
  expect_error(fastnorm_table_lookup(table, 0, 0, 0, load, 7, out, &found), "interpolation");
  expect_error(fastnorm_table_lookup(table, 1, 0, 0, load, FASTNORM_TABLE_PCHIP, out, &found), "pair");
  expect_error(fastnorm_table_output_index(table, "pmax", &index), "pmax");
  fastnorm_table_destroy(table);
  remove(path);
  expect_error(fastnorm_table_read(path, &table), "cannot open");
  EXPECT(table == NULL);
}

int main(int argc, char** argv) {
  if (argc != 3) {
    fprintf(stderr, "usage: %s PEER_CASE_FILE SCRATCH_DIR\n", argv[0]);
    return 2;
  }
  printf("fastnorm %s through its C API\n", fastnorm_version());
  FILE* peer_case = fopen(argv[1], "r");
  if (!peer_case) {  /* ../shared absent: skip (CTest code 77), unless CI requires the data */
    fprintf(stderr, "peer case %s not found\n", argv[1]);
    return getenv("FASTNORM_REQUIRE_SHARED") ? 1 : 77;
  }
  fclose(peer_case);
  peer_case_through_the_api(argv[1], argv[2]);
  bad_input_is_named();
  wheelset_equilibrium_and_time_step();
  wheelset_trial_steps();
  wheelset_copies();
  wheelset_creep_forces();
  steady_rolling_meets_contact();
  case_rolling_is_read(argv[2]);
  contact_table_lookup(argv[2]);
  if (failures) fprintf(stderr, "%d checks failed\n", failures);
  return failures ? 1 : 0;
}
