// Solves a small sphere-on-plane problem through the installed package and checks the
// answer against Hertz: exits 0 only if the force matches within 5 %. Built with
// CONSUMER_ANY_SOLVER it chooses NORM at run time through AnySolver, from
// fastnorm::precompiled.
#include <fastnorm/fastnorm.hpp>

#include <cmath>
#include <iostream>

int main() {
  const fastnorm::Material<> steel(2.1e11, 0.3);
  const auto hertz = fastnorm::hertz_from_force(0.3, 0.3, steel.combined_modulus(), 5e4);
  const fastnorm::Grid<> grid = fastnorm::hertz_grid(hertz, 20, 1.3);
  Eigen::VectorXd h = fastnorm::hertz_undeformed_distance(grid, 0.3, 0.3);
  h.array() -= hertz.approach;
#ifdef CONSUMER_ANY_SOLVER
  const fastnorm::AnySolver<> solver("norm", grid, steel);
#else
  const fastnorm::NormSolver<> solver(grid, steel);
#endif
  const auto solution = solver.solve(h, fastnorm::Loading<>::approach());
  const double error = std::abs(solution.normal_force / hertz.normal_force - 1);
  std::cout << "fastnorm consumer: Fn = " << solution.normal_force << " N, Hertz "
            << hertz.normal_force << " N, relative difference " << error << "\n";
  return solution.status == fastnorm::Status::converged && error < 0.05 ? 0 : 1;
}
