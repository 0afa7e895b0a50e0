#pragma once
/// @file solver_from_spec.hpp
/// A solver of a type named at compile time, built from a SolverSpec (docs/architecture.md
/// §3): what a model templated on its solver (wheelrail::WheelsetContact<Solver>, the
/// equilibrium) uses to build one solver per grid, so that a program naming one solver
/// compiles that solver only. AnySolver (any_solver.hpp) builds any kind through the same
/// traits. Including this header instantiates nothing.

#include <string>
#include <type_traits>
#include <utility>

#include "fastnorm/bases.hpp"
#include "fastnorm/cg_solver.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/norm_solver.hpp"
#include "fastnorm/reduced_solver.hpp"
#include "fastnorm/solver_spec.hpp"

namespace fastnorm {

/// How a solver type is built from a spec: `accepts(kind)` says which kinds of spec it
/// solves, `make(spec, grid, material)` builds it with the spec's settings. Specialised for
/// every solver of fastnorm; a user's solver type specialises it to serve the models.
template <typename Solver>
struct SolverFromSpec;

/// The basis of a reduced kind: its kind and the basis built from a spec's G and K.
template <typename Basis>
struct BasisFromSpec;

template <>
struct BasisFromSpec<EllipticBasis> {
  template <typename Scalar>
  static constexpr typename SolverSpec<Scalar>::Kind kind() { return SolverSpec<Scalar>::Kind::elliptic; }
  template <typename Scalar>
  static EllipticBasis make(const SolverSpec<Scalar>&) { return EllipticBasis(); }
};

template <>
struct BasisFromSpec<PolynomialBasis> {
  template <typename Scalar>
  static constexpr typename SolverSpec<Scalar>::Kind kind() { return SolverSpec<Scalar>::Kind::polynomial; }
  template <typename Scalar>
  static PolynomialBasis make(const SolverSpec<Scalar>& spec) { return PolynomialBasis(spec.grade); }
};

template <typename Inner>
struct BasisFromSpec<EdgeEnriched<Inner>> {
  template <typename Scalar>
  static constexpr typename SolverSpec<Scalar>::Kind kind() {
    using Kind = typename SolverSpec<Scalar>::Kind;
    return BasisFromSpec<Inner>::template kind<Scalar>() == Kind::elliptic ? Kind::elliptic_edge : Kind::polynomial_edge;
  }
  template <typename Scalar>
  static EdgeEnriched<Inner> make(const SolverSpec<Scalar>& spec) {
    return EdgeEnriched<Inner>(BasisFromSpec<Inner>::make(spec), spec.edge_elements);
  }
};

template <typename Scalar>
struct SolverFromSpec<NormSolver<Scalar>> {
  static bool accepts(typename SolverSpec<Scalar>::Kind kind) { return kind == SolverSpec<Scalar>::Kind::norm; }
  static NormSolver<Scalar> make(const SolverSpec<Scalar>& spec, const Grid<Scalar>& grid,
                                 const Material<Scalar>& material) {
    return NormSolver<Scalar>(grid, material, spec.active_set);
  }
};

template <typename Scalar>
struct SolverFromSpec<CgSolver<Scalar>> {
  static bool accepts(typename SolverSpec<Scalar>::Kind kind) { return kind == SolverSpec<Scalar>::Kind::cg; }
  static CgSolver<Scalar> make(const SolverSpec<Scalar>& spec, const Grid<Scalar>& grid,
                               const Material<Scalar>& material) {
    return CgSolver<Scalar>(grid, material, spec.cg);
  }
};

template <typename Basis, typename Scalar>
struct SolverFromSpec<ReducedSolver<Basis, Scalar>> {
  static bool accepts(typename SolverSpec<Scalar>::Kind kind) {
    return kind == BasisFromSpec<Basis>::template kind<Scalar>();
  }
  static ReducedSolver<Basis, Scalar> make(const SolverSpec<Scalar>& spec, const Grid<Scalar>& grid,
                                           const Material<Scalar>& material) {
    return ReducedSolver<Basis, Scalar>(grid, material, BasisFromSpec<Basis>::make(spec), spec.reduced_options());
  }
};

namespace detail {
/// Whether `Solver` has tables that solvers of other grids can share: `for_grid(grid)`, a
/// solver for another grid that shares them where they reach, and `build_tables()`, which
/// builds them ahead (ReducedSolver, AnySolver). A model builds its solvers per grid size
/// through them.
template <typename Solver, typename = void>
inline constexpr bool shares_tables = false;
template <typename Solver>
inline constexpr bool shares_tables<
    Solver, std::void_t<decltype(std::declval<const Solver&>().for_grid(std::declval<const Solver&>().grid())),
                        decltype(std::declval<const Solver&>().build_tables())>> = true;
}  // namespace detail

/// Checks that a solver of type `Solver` can solve `spec` (its kind is the type's, its
/// settings valid); `where` names the field in the message.
/// @throws fastnorm::invalid_argument naming `where`
template <typename Solver, typename Scalar>
void check_spec_for(const SolverSpec<Scalar>& spec, const std::string& where) {
  spec.validate();
  FASTNORM_CHECK(SolverFromSpec<Solver>::accepts(spec.kind),
                 where + " is '" + spec.name() +
                     "', a kind this model's solver type does not solve: name a spec of its kind "
                     "(e.g. SolverSpec<>::parse(...)) or use AnySolver");
}

/// A `Solver` built from `spec`.
/// @throws fastnorm::invalid_argument for a spec of another kind or invalid settings
template <typename Solver, typename Scalar>
Solver make_solver(const SolverSpec<Scalar>& spec, const Grid<Scalar>& grid, const Material<Scalar>& material) {
  check_spec_for<Solver>(spec, "solver spec");
  return SolverFromSpec<Solver>::make(spec, grid, material);
}

}  // namespace fastnorm
