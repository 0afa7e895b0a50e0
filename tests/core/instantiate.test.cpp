// Every public class template instantiated in full for float, double and long double,
// so that each member compiles for each scalar, plus one solve in each.
#include <catch2/catch.hpp>
#include <fastnorm/fastnorm.hpp>

#define FASTNORM_INSTANTIATE(Scalar)                             \
  template class fastnorm::Grid<Scalar>;                         \
  template class fastnorm::Material<Scalar>;                     \
  template class fastnorm::InfluenceTable<Scalar>;               \
  template class fastnorm::NormSolver<Scalar>;                   \
  template class fastnorm::ReducedSolver<fastnorm::EllipticBasis, Scalar>;       \
  template class fastnorm::ReducedSolver<fastnorm::PolynomialBasis, Scalar>;     \
  template class fastnorm::ReducedSolver<fastnorm::PolynomialEdgeBasis, Scalar>; \
  template class fastnorm::AnySolver<Scalar>;                    \
  template class fastnorm::wheelrail::S1002<Scalar>;             \
  template class fastnorm::wheelrail::Uic60<Scalar>;             \
  template struct fastnorm::Solution<Scalar>;                    \
  template struct fastnorm::HertzContact<Scalar>;                \
  template fastnorm::Case<Scalar> fastnorm::read_case<Scalar>(std::istream&, const std::string&); \
  template void fastnorm::write_case<Scalar>(std::ostream&, const fastnorm::Case<Scalar>&);

FASTNORM_INSTANTIATE(float)
FASTNORM_INSTANTIATE(double)
FASTNORM_INSTANTIATE(long double)

TEMPLATE_TEST_CASE("Every solver solves a small sphere in every scalar type", "[instantiate]", float, double,
                   long double) {
  using S = TestType;
  const fastnorm::Material<S> steel(S(2.1e11), S(0.3));
  const auto hertz = fastnorm::hertz_from_force(S(0.3), S(0.3), steel.combined_modulus(), S(5e4));
  const fastnorm::Grid<S> grid = fastnorm::hertz_grid(hertz, 16, S(1.3));
  for (const char* name : {"norm", "elliptic", "polynomial-edge"}) {
    const fastnorm::AnySolver<S> solver(name, grid, steel);
    const auto solution =
        solver.solve(fastnorm::hertz_undeformed_distance(grid, S(0.3), S(0.3)), fastnorm::Loading<S>::force(S(5e4)));
    INFO(name);
    REQUIRE(solution.ok());
    CHECK(static_cast<double>(solution.normal_force) == Approx(5e4).epsilon(1e-5));
    // Coarse grid: the approach is within 5 % of Hertz in every precision and solver.
    CHECK(static_cast<double>(solution.approach) == Approx(static_cast<double>(hertz.approach)).epsilon(0.05));
  }
}
