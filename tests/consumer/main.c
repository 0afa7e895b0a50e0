/* A C program outside fastnorm that links the installed C API, fastnorm::c. */
#include <fastnorm_c.h>
#include <stdio.h>

int main(void) {
  const fastnorm_grid grid = {16, 16, 2e-4, 2e-4, -1.5e-3, -1.5e-3};
  const fastnorm_material steel = {2.1e11, 0.3, 2.1e11, 0.3};
  double h[256], pressure[256];
  for (int j = 0; j < grid.my; ++j) {
    for (int i = 0; i < grid.mx; ++i) {
      const double x = grid.x0 + i * grid.dx, y = grid.y0 + j * grid.dy;
      h[i + grid.mx * j] = (x * x + y * y) / (2 * 0.05);  /* a sphere of radius 50 mm */
    }
  }
  fastnorm_solver* solver = NULL;
  fastnorm_result result;
  if (fastnorm_solver_create("norm", &grid, &steel, NULL, &solver) != FASTNORM_OK ||
      fastnorm_solve_force(solver, h, 1000.0, pressure, &result) != FASTNORM_OK) {
    fprintf(stderr, "consumer_c: %s\n", fastnorm_last_error());
    return 1;
  }
  fastnorm_solver_destroy(solver);
  printf("consumer_c: fastnorm %s, %s, Fn %.6g N on %d elements\n", fastnorm_version(),
         fastnorm_status_name(result.status), result.normal_force, result.contact_count);
  return result.status == FASTNORM_CONVERGED ? 0 : 1;
}
