#include <catch2/catch.hpp>
#include <fastnorm/any_solver.hpp>
#include <fastnorm/detail/galerkin_set_solver.hpp>
#include <fastnorm/detail/in_place_cholesky.hpp>
#include <fastnorm/hertz.hpp>
#include <fastnorm/norm_solver.hpp>
#include <fastnorm/reduced_solver.hpp>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "support/random_gaps.hpp"
#include "support/surfaces.hpp"

using Catch::Matchers::Contains;

namespace {

using fastnorm::test::steel;

// A random symmetric positive definite matrix of n × n (Cholesky tests).
Eigen::MatrixXd positive_definite(Eigen::Index n) {
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(n, n);
  return b * b.transpose() + Eigen::MatrixXd::Identity(n, n);
}

// Never fewer elements than functions: every segment keeps one unknown per element, so
// the reduced solver must reproduce full NORM.
struct IdentityBasis : fastnorm::CoordinateBasis<IdentityBasis> {
  Eigen::Index unknowns() const { return std::numeric_limits<Eigen::Index>::max(); }
  std::string name() const { return "identity"; }
  template <typename Scalar>
  fastnorm::BasisBlock<Scalar> evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& xi) const {
    return fastnorm::BasisBlock<Scalar>::Identity(xi.size(), xi.size());
  }
};

// A constant per segment, once or twice: the second has two equal columns, so Aᵀ C A is
// singular, yet spans the same space and must give the same pressures.
template <int Copies>
struct ConstantBasis : fastnorm::CoordinateBasis<ConstantBasis<Copies>> {
  Eigen::Index unknowns() const { return Copies; }
  std::string name() const { return "constant"; }
  template <typename Scalar>
  fastnorm::BasisBlock<Scalar> evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& xi) const {
    return fastnorm::BasisBlock<Scalar>::Ones(xi.size(), Copies);
  }
};

double relative_force_error(const fastnorm::Solution<>& solution, const fastnorm::Solution<>& reference) {
  return std::abs(solution.normal_force / reference.normal_force - 1);
}

}  // namespace

TEST_CASE("With an identity basis the reduced solver is full NORM", "[reduced]") {
  const auto& grid = fastnorm::test::two_bumps_grid;
  const Eigen::VectorXd h = fastnorm::test::two_bumps(grid, 3e-5);
  const fastnorm::NormSolver<> norm(grid, steel);
  const fastnorm::ReducedSolver<IdentityBasis> identity(grid, steel);
  for (const auto& loading : {fastnorm::Loading<>::approach(), fastnorm::Loading<>::force(2e3)}) {
    const auto reference = norm.solve(h, loading);
    const auto reduced = identity.solve(h, loading);
    REQUIRE(reference.status == fastnorm::Status::converged);
    REQUIRE(reduced.status == fastnorm::Status::converged);
    CHECK(reduced.iterations == reference.iterations);
    CHECK((reduced.in_contact == reference.in_contact).all());
    CHECK((reduced.pressure - reference.pressure).cwiseAbs().maxCoeff() <= 1e-11 * reference.pressure.maxCoeff());
    CHECK(reduced.approach == Approx(reference.approach).margin(1e-12 * h.cwiseAbs().maxCoeff()));
  }
}

TEST_CASE("A rank-deficient basis takes the minimum-norm solve and the same answer", "[reduced]") {
  const auto& grid = fastnorm::test::two_bumps_grid;
  const Eigen::VectorXd h = fastnorm::test::two_bumps(grid, 3e-5);
  const auto single = fastnorm::ReducedSolver<ConstantBasis<1>>(grid, steel).solve(h, fastnorm::Loading<>::approach());
  const auto doubled = fastnorm::ReducedSolver<ConstantBasis<2>>(grid, steel).solve(h, fastnorm::Loading<>::approach());
  REQUIRE(single.ok());
  REQUIRE(doubled.ok());
  CHECK(doubled.status == single.status);
  CHECK((doubled.pressure - single.pressure).cwiseAbs().maxCoeff() <= 1e-9 * single.pressure.maxCoeff());
}

TEST_CASE("A factorisation continued from a kept leading factor is the factorisation", "[reduced]") {
  // The incremental solve keeps the rows of the previous set's factor for its leading
  // unknowns and computes the rest (detail/in_place_cholesky.hpp): checked against Eigen's
  // LLT of the whole matrix, for every size of the kept part; at 300 unknowns the update
  // runs in several tiles of rows and columns (kept 70: 64, kept 150 and 299: 54 and 27).
  for (const auto& [n, kept_sizes] : {std::pair<Eigen::Index, std::vector<Eigen::Index>>{23, {0, 1, 7, 22, 23}},
                                      std::pair<Eigen::Index, std::vector<Eigen::Index>>{300, {70, 150, 299}}}) {
    const Eigen::MatrixXd matrix = positive_definite(n);
    const Eigen::MatrixXd reference = Eigen::LLT<Eigen::MatrixXd>(matrix).matrixL();
    const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
    for (const Eigen::Index kept : kept_sizes) {
      fastnorm::detail::InPlaceCholesky<double> cholesky;
      cholesky.resize(n);
      cholesky.matrix() = matrix;
      cholesky.matrix().topLeftCorner(kept, kept) = reference.topLeftCorner(kept, kept);
      REQUIRE(cholesky.factorise_from(kept));
      const Eigen::MatrixXd factor = cholesky.factor().triangularView<Eigen::Lower>();
      INFO("n " << n << ", kept " << kept);
      CHECK((factor - reference).cwiseAbs().maxCoeff() <= 1e-13 * reference.cwiseAbs().maxCoeff());
      Eigen::VectorXd solution = rhs;
      cholesky.solve_in_place(solution);
      CHECK((matrix * solution - rhs).norm() <= 1e-12 * matrix.norm() * solution.norm());
    }
  }
  // A trailing block that is not positive definite is reported, not factored.
  const Eigen::Index n = 23;
  const Eigen::MatrixXd matrix = positive_definite(n);
  const Eigen::MatrixXd reference = Eigen::LLT<Eigen::MatrixXd>(matrix).matrixL();
  fastnorm::detail::InPlaceCholesky<double> cholesky;
  cholesky.resize(n);
  cholesky.matrix() = matrix;
  cholesky.matrix()(n - 1, n - 1) = -1.0;
  cholesky.matrix().topLeftCorner(7, 7) = reference.topLeftCorner(7, 7);
  CHECK_FALSE(cholesky.factorise_from(7));
  CHECK_FALSE(cholesky.factored());
}

TEST_CASE("A rank update of a factor's trailing rows is the factor of the updated matrix", "[reduced]") {
  // A set that drops unknowns keeps the other rows of the previous factor and adds back the
  // dropped columns' outer products by rank-one updates (GalerkinSetSolver::factorise):
  // checked against Eigen's LLT of A + v vᵀ, for updates from the first row and from inside,
  // on the whole storage and on its leading block, and chained a thousand times.
  const Eigen::Index n = 23;
  const Eigen::MatrixXd matrix = positive_definite(n);
  for (const auto& [first, size] : {std::pair<Eigen::Index, Eigen::Index>{0, n}, {9, n}, {9, 17}, {16, 17}}) {
    INFO("first " << first << ", size " << size);
    Eigen::VectorXd v = Eigen::VectorXd::Zero(size);
    v.tail(size - first) = Eigen::VectorXd::LinSpaced(size - first, 0.7, -1.3);
    v(size - 1) = 0.0;  // a zero entry leaves its column as it is
    const Eigen::MatrixXd updated = matrix.topLeftCorner(size, size) + v * v.transpose();
    const Eigen::MatrixXd reference = Eigen::LLT<Eigen::MatrixXd>(updated).matrixL();
    fastnorm::detail::InPlaceCholesky<double> cholesky;
    cholesky.resize(n);
    cholesky.matrix() = matrix;
    REQUIRE(cholesky.factorise());
    Eigen::VectorXd work = v.tail(size - first);
    cholesky.update_rank(first, size, work);
    const Eigen::MatrixXd factor = cholesky.factor().topLeftCorner(size, size).triangularView<Eigen::Lower>();
    CHECK((factor - reference).cwiseAbs().maxCoeff() <= 1e-13 * reference.cwiseAbs().maxCoeff());
    // Rows past the block are not touched.
    if (size < n) {
      const Eigen::MatrixXd untouched = Eigen::LLT<Eigen::MatrixXd>(matrix).matrixL();
      const Eigen::MatrixXd lower = cholesky.factor().triangularView<Eigen::Lower>();
      CHECK((lower.bottomRows(n - size) - untouched.bottomRows(n - size)).cwiseAbs().maxCoeff() <=
            1e-13 * untouched.cwiseAbs().maxCoeff());
    }
  }
  // Several vectors at once, zero above different rows, as the dropped unknowns of a set.
  {
    Eigen::MatrixXd vectors = Eigen::MatrixXd::Zero(n - 4, 3);
    for (Eigen::Index k = 0; k < 3; ++k) {
      for (Eigen::Index i = 2 * k; i < n - 4; ++i) vectors(i, k) = std::cos(0.3 * static_cast<double>(i + 5 * k));
    }
    const Eigen::MatrixXd updated = matrix + [&] {
      Eigen::MatrixXd padded = Eigen::MatrixXd::Zero(n, 3);
      padded.bottomRows(n - 4) = vectors;
      return Eigen::MatrixXd(padded * padded.transpose());
    }();
    const Eigen::MatrixXd reference = Eigen::LLT<Eigen::MatrixXd>(updated).matrixL();
    fastnorm::detail::InPlaceCholesky<double> cholesky;
    cholesky.resize(n);
    cholesky.matrix() = matrix;
    REQUIRE(cholesky.factorise());
    cholesky.update_rank(4, n, vectors);
    const Eigen::MatrixXd factor = cholesky.factor().triangularView<Eigen::Lower>();
    CHECK((factor - reference).cwiseAbs().maxCoeff() <= 1e-13 * reference.cwiseAbs().maxCoeff());
  }
  // A thousand updates in a row, each by a different vector: the factor stays the one of
  // the sum to round-off (no drift a time loop's chains of updates would feel).
  fastnorm::detail::InPlaceCholesky<double> cholesky;
  cholesky.resize(n);
  cholesky.matrix() = matrix;
  REQUIRE(cholesky.factorise());
  Eigen::MatrixXd sum = matrix;
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Index first = k % n;
    Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
    for (Eigen::Index i = first; i < n; ++i) v(i) = 0.01 * std::sin(0.37 * static_cast<double>(k + 3 * i));
    sum += v * v.transpose();
    Eigen::VectorXd work = v.tail(n - first);
    cholesky.update_rank(first, n, work);
  }
  const Eigen::MatrixXd factor = cholesky.factor().triangularView<Eigen::Lower>();
  CHECK((factor * factor.transpose() - sum).norm() <= 1e-14 * sum.norm());
}

TEST_CASE("A factor copied by its lower triangle solves as the original, bit for bit", "[reduced]") {
  // WheelsetContact's trial steps copy Galerkin systems and factors by their lower triangles
  // (GalerkinMemory's copy): the upper triangle of the target keeps whatever it held.
  const Eigen::Index n = 37;
  const Eigen::MatrixXd matrix = positive_definite(n);
  fastnorm::detail::InPlaceCholesky<double> original, copy;
  original.resize(n);
  original.matrix() = matrix;
  REQUIRE(original.factorise());
  copy.resize(n + 5);
  copy.matrix().setConstant(std::numeric_limits<double>::quiet_NaN());  // stale storage, larger
  copy.assign_lower(original);
  REQUIRE(copy.factored());
  REQUIRE(copy.factor().rows() == n);
  const Eigen::MatrixXd lower = original.factor().triangularView<Eigen::Lower>();
  CHECK(Eigen::MatrixXd(copy.factor().triangularView<Eigen::Lower>()) == lower);
  CHECK(copy.factor().triangularView<Eigen::StrictlyUpper>().toDenseMatrix().hasNaN());  // not copied
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  Eigen::VectorXd from_original = rhs, from_copy = rhs;
  original.solve_in_place(from_original);
  copy.solve_in_place(from_copy);
  CHECK(from_copy == from_original);
  CHECK_FALSE(from_copy.hasNaN());
}

TEST_CASE("A new Galerkin assembly starts at the largest size recycled", "[reduced]") {
  // The systems of a time loop creep up one segment at a time: an assembly made from nothing
  // when no spare is left would climb the sizes again (docs/performance.md §8).
  fastnorm::detail::GalerkinMemory<double> memory;
  memory.reserve(8, 4);
  auto first = memory.take_spare();
  CHECK(first.matrix.capacity() == 0);
  first.matrix.resize(40, 40);
  first.cholesky.resize(40);
  memory.path.push_back(std::move(first));
  memory.next_problem();  // this solve's sets become the ones to look up
  memory.next_problem();  // and then spares
  REQUIRE(memory.spare.size() == 1);
  auto reused = memory.take_spare(), fresh = memory.take_spare();
  CHECK(reused.matrix.capacity() >= 1600);
  CHECK(fresh.matrix.capacity() >= 1600);
  CHECK(fresh.cholesky.capacity() >= 1600);
  CHECK(fresh.segments.capacity() >= 8);
}

TEST_CASE("Reduced solvers against full NORM on Hertz contacts", "[reduced][hertz]") {
  // Measured relative force errors (approach control, 41 × 41 over ±1.25 semi-axes):
  // see docs/method.md §4; bounds here are the targets, all met on Hertz.
  struct Shape {
    double radius_x, radius_y, force;
  };
  for (const Shape& shape : {Shape{0.3, 0.3, 5e4}, Shape{0.46, 0.3, 1e5}}) {
    const auto hertz = fastnorm::hertz_from_force(shape.radius_x, shape.radius_y, steel.combined_modulus(), shape.force);
    const auto grid = fastnorm::hertz_grid(hertz, 41, 1.25);
    const Eigen::VectorXd h =
        fastnorm::hertz_undeformed_distance(grid, shape.radius_x, shape.radius_y).array() - hertz.approach;
    const auto reference = fastnorm::NormSolver<>(grid, steel).solve(h, fastnorm::Loading<>::approach());
    REQUIRE(reference.status == fastnorm::Status::converged);
    for (const auto& [name, bound] : std::vector<std::pair<std::string, double>>{
             {"elliptic", 5e-4}, {"polynomial:4", 5e-4}, {"elliptic-edge", 2e-5}, {"polynomial-edge", 2e-5}}) {
      const auto solution = fastnorm::AnySolver<>(name, grid, steel).solve(h, fastnorm::Loading<>::approach());
      INFO(name << " on R = (" << shape.radius_x << ", " << shape.radius_y << "): force error "
                << relative_force_error(solution, reference) << ", status " << fastnorm::to_string(solution.status));
      REQUIRE(solution.ok());
      CHECK(relative_force_error(solution, reference) <= bound);
      CHECK((solution.in_contact != reference.in_contact).count() <= reference.contact_count() / 100);
    }
  }
}

TEST_CASE("Solvers are found by name", "[reduced][any]") {
  const auto& grid = fastnorm::test::two_bumps_grid;
  CHECK(fastnorm::AnySolver<>("norm", grid, steel).name() == "norm");
  CHECK(fastnorm::AnySolver<>("cg", grid, steel).name() == "cg");
  CHECK(fastnorm::AnySolver<>("elliptic", grid, steel).name() == "elliptic");
  CHECK(fastnorm::AnySolver<>("polynomial", grid, steel).name() == "polynomial:4");
  CHECK(fastnorm::AnySolver<>("polynomial:7", grid, steel).name() == "polynomial:7");
  CHECK(fastnorm::AnySolver<>("elliptic-edge", grid, steel).name() == "elliptic-edge:1");
  CHECK(fastnorm::AnySolver<>("elliptic-edge:2", grid, steel).name() == "elliptic-edge:2");
  CHECK(fastnorm::AnySolver<>("polynomial-edge", grid, steel).name() == "polynomial-edge:4:1");
  CHECK(fastnorm::AnySolver<>("polynomial-edge:6:2", grid, steel).name() == "polynomial-edge:6:2");
  CHECK_THROWS_WITH(fastnorm::AnySolver<>("multigrid", grid, steel), Contains("unknown solver 'multigrid'"));
  CHECK_THROWS_WITH(fastnorm::AnySolver<>("polynomial:x", grid, steel), Contains("grade G"));
  CHECK_THROWS_WITH(fastnorm::AnySolver<>("polynomial:40", grid, steel), Contains("grade"));
  CHECK_THROWS_WITH(fastnorm::AnySolver<>("elliptic-edge:0", grid, steel), Contains("edge_elements"));
  CHECK_THROWS_WITH(fastnorm::AnySolver<>("elliptic:3", grid, steel), Contains("too many"));
  const Eigen::VectorXd h = fastnorm::test::two_bumps(grid, 3e-5);
  CHECK_THROWS_WITH(fastnorm::AnySolver<>("elliptic", grid, steel).solve(h.head(3), fastnorm::Loading<>::approach()),
                    Contains("undeformed_distance"));
}

TEST_CASE("The join check's bound skips candidates, never changes an answer", "[reduced][norm]") {
  // docs/method.md §3, "Pruning the join check": with the bound and without it the loop must
  // take the same steps to the same pressures, bit for bit: on wavy random gaps (many joins
  // and drops per solve), both controls, cold and along a warm sequence (where the floors
  // are carried from one solve to the next).
  const auto solve_both = [](auto make_solver, const std::string& name) {
    for (const std::uint32_t seed : {3u, 17u, 29u}) {
      const auto gap = fastnorm::test::random_gap(seed, 48);
      auto bounded = make_solver(gap.grid, true);
      auto plain = make_solver(gap.grid, false);
      for (int step = 0; step < 4; ++step) {
        INFO(name << ", seed " << seed << ", step " << step);
        const Eigen::VectorXd h = gap.unloaded.array() - gap.approach * (1 + 0.02 * step);
        const auto by_approach = fastnorm::Loading<>::approach();
        const auto a = bounded.solve_next(h, by_approach), b = plain.solve_next(h, by_approach);
        REQUIRE(a.ok());
        CHECK(a.iterations > 1);
        CHECK(a.status == b.status);
        CHECK(a.iterations == b.iterations);
        CHECK(a.residual == b.residual);
        CHECK(a.pressure == b.pressure);
        // The next step starts from this set (a reduced solver leaves that to its caller).
        bounded.workspace().start().remember_set(a);
        plain.workspace().start().remember_set(b);
        const auto by_force = fastnorm::Loading<>::force(1.1 * a.normal_force);
        const auto c = bounded.solve(gap.unloaded, by_force), d = plain.solve(gap.unloaded, by_force);
        CHECK(c.iterations == d.iterations);
        CHECK(c.approach == d.approach);
        CHECK(c.pressure == d.pressure);
      }
    }
  };
  solve_both(
      [](const fastnorm::Grid<>& grid, bool bound) {
        fastnorm::ActiveSetOptions<> options;
        options.bound_join_check = bound;
        return fastnorm::NormSolver<>(grid, steel, options);
      },
      "norm");
  const auto reduced = [](auto basis, const std::string& name, auto& solve) {
    solve(
        [basis](const fastnorm::Grid<>& grid, bool bound) {
          fastnorm::ReducedOptions<> options;
          options.active_set.bound_join_check = bound;
          return fastnorm::ReducedSolver<decltype(basis)>(grid, steel, basis, options);
        },
        name);
  };
  reduced(fastnorm::EllipticBasis(), "elliptic", solve_both);
  reduced(fastnorm::PolynomialBasis(4), "polynomial:4", solve_both);
  reduced(fastnorm::PolynomialEdgeBasis(fastnorm::PolynomialBasis(4), 1), "polynomial-edge:4:1", solve_both);
}

TEST_CASE("A workspace moved to another solver does not carry the join check's floors", "[reduced][norm]") {
  // The floors a warm solve starts from bound displacements on the influence table they were
  // computed with; on a stiffer material's table they can overstate the displacements and
  // skip candidates that must join. A workspace that moves from one solver to another must
  // give what a fresh one gives from the same start: here from a solve of one random gap on
  // a soft material to another random gap (another shape on the same grid) on a stiff one,
  // started from the core of its interpenetration, so that elements join.
  const fastnorm::Material<> stiffer(20 * 2.1e11, 0.3);
  const auto by_approach = fastnorm::Loading<>::approach();
  int differ = 0;
  for (const std::uint32_t seed : {2u, 5u, 7u, 11u, 13u, 19u, 23u, 31u}) {
    const auto first = fastnorm::test::random_gap(seed, 40), second = fastnorm::test::random_gap(seed + 100, 40);
    const Eigen::VectorXd h_first = first.unloaded.array() - first.approach;
    const Eigen::VectorXd h_second = second.unloaded.array() - second.approach;
    std::vector<Eigen::Index> core;
    for (Eigen::Index k = 0; k < h_second.size(); ++k) {
      if (h_second(k) < 0.5 * h_second.minCoeff()) core.push_back(k);
    }
    const auto moved_and_fresh = [&](const auto& soft, const auto& stiff, auto workspace) {
      REQUIRE(soft.solve(h_first, by_approach, workspace).ok());
      workspace.start().set_contact_set(core);
      decltype(workspace) fresh;
      fresh.start().set_contact_set(core);
      const auto moved = stiff.solve(h_second, by_approach, workspace);
      const auto reference = stiff.solve(h_second, by_approach, fresh);
      REQUIRE(reference.ok());
      if (!(moved.pressure == reference.pressure)) ++differ;
    };
    moved_and_fresh(fastnorm::NormSolver<>(first.grid, steel), fastnorm::NormSolver<>(first.grid, stiffer),
                    fastnorm::NormWorkspace<>());
    moved_and_fresh(fastnorm::ReducedSolver<fastnorm::EllipticBasis>(first.grid, steel),
                    fastnorm::ReducedSolver<fastnorm::EllipticBasis>(first.grid, stiffer),
                    fastnorm::ReducedWorkspace<>());
  }
  CHECK(differ == 0);
}
