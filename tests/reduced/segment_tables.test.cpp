#include <catch2/catch.hpp>
#include <fastnorm/bases.hpp>
#include <fastnorm/influence.hpp>
#include <fastnorm/reduced_solver.hpp>
#include <fastnorm/detail/segment_tables.hpp>

#include <functional>
#include <memory>

#include "support/surfaces.hpp"

namespace {

using fastnorm::test::steel;

/// Element numbers of `count` consecutive elements of strip j from i = first.
std::vector<Eigen::Index> run_of(const fastnorm::Grid<>& grid, Eigen::Index first, Eigen::Index count,
                                 Eigen::Index strip) {
  std::vector<Eigen::Index> elements;
  for (Eigen::Index i = first; i < first + count; ++i) elements.push_back(grid.index(i, strip));
  return elements;
}

/// Checks the segment tables of `basis` on a small grid against dense products; the tables
/// are made for a grid `extra` elements larger either way (read through an offset).
template <typename Basis>
struct TableCheck {
  TableCheck(const Basis& b, Eigen::Index extra = 0)
      : basis(b), extent(grid.mx() + extra, grid.my() + extra, grid.dx(), grid.dy()) {}
  Basis basis;
  Eigen::Index q = basis.unknowns();
  fastnorm::Grid<> grid{23, 9, 3e-4, 4e-4};
  fastnorm::Grid<> extent;
  fastnorm::InfluenceTable<> influence{grid, steel};
  fastnorm::detail::SegmentTables<double> tables{std::make_shared<const fastnorm::InfluenceTable<>>(extent, steel),
                                                 std::size_t(1) << 24};
  std::function<Eigen::MatrixXd(Eigen::Index)> block_of = [this](Eigen::Index count) {
    return basis.template block<double>(count);
  };

  /// Every block of Eq. (M2) against A_tᵀ C_ts A_s with C_ts the dense block of the table.
  void blocks() {
    for (Eigen::Index n_t : {q + 1, q + 4, Eigen::Index(17), grid.mx()}) {
      for (Eigen::Index n_s : {q + 2, Eigen::Index(11), grid.mx() - 1}) {
        for (Eigen::Index strip_t : {Eigen::Index(0), Eigen::Index(5)}) {
          const Eigen::Index first_t = (grid.mx() - n_t) / 2, first_s = grid.mx() - n_s, strip_s = 3;
          const auto target = run_of(grid, first_t, n_t, strip_t), source = run_of(grid, first_s, n_s, strip_s);
          const Eigen::MatrixXd expected =
              block_of(n_t).transpose() * influence.dense_block(target, source) * block_of(n_s);
          const auto* table = tables.correlation(n_t, n_s, block_of);
          REQUIRE(table != nullptr);
          const Eigen::VectorXd entries =
              table->transpose() * influence.run(first_t - first_s - (n_s - 1), strip_t - strip_s, n_t + n_s - 1);
          const Eigen::MatrixXd block = Eigen::Map<const Eigen::MatrixXd>(entries.data(), q, q);
          INFO("n_t " << n_t << " n_s " << n_s << " strip " << strip_t);
          CHECK((block - expected).cwiseAbs().maxCoeff() <= 1e-13 * expected.cwiseAbs().maxCoeff());
        }
      }
    }
  }

  /// The Galerkin blocks as the solver reads them from the displacement table of the longer
  /// segment, Σ_m A_short(m, a) W_b(Δ + m, dj), against A_tᵀ C_ts A_s with the dense block.
  void blocks_from_displacement() {
    for (Eigen::Index n_long : {q + 1, Eigen::Index(11), grid.mx()}) {
      for (Eigen::Index n_short : {Eigen::Index(1), q, q + 1, Eigen::Index(7)}) {
        if (n_short > n_long) continue;
        const auto table = tables.displacement(n_long, block_of, grid.mx());
        REQUIRE(table);
        for (Eigen::Index strip_short : {Eigen::Index(0), Eigen::Index(3), Eigen::Index(8)}) {
          const Eigen::Index first_long = grid.mx() - n_long, strip_long = 3, first_short = (grid.mx() - n_short) / 3;
          const auto shorter = run_of(grid, first_short, n_short, strip_short);
          const auto longer = run_of(grid, first_long, n_long, strip_long);
          const Eigen::MatrixXd short_block =
              n_short <= q ? Eigen::MatrixXd(Eigen::MatrixXd::Identity(n_short, n_short)) : block_of(n_short);
          const Eigen::MatrixXd expected =
              short_block.transpose() * influence.dense_block(shorter, longer) * block_of(n_long);
          Eigen::MatrixXd block = Eigen::MatrixXd::Zero(short_block.cols(), q);
          const double* w = table.at(first_short - first_long + grid.mx() - n_long, std::abs(strip_short - strip_long));
          for (Eigen::Index m = 0; m < n_short; ++m, w += table.functions()) {
            for (Eigen::Index b = 0; b < q; ++b) block.col(b) += w[b] * short_block.row(m).transpose();
          }
          INFO("n_long " << n_long << " n_short " << n_short << " strip " << strip_short);
          CHECK((block - expected).cwiseAbs().maxCoeff() <= 1e-13 * expected.cwiseAbs().maxCoeff());
        }
      }
    }
  }

  /// Eq. (M3): u at every element of a strip due to p = A α on a source segment, from the
  /// displacement table, against the dense block of the influence table times p.
  void displacements() {
    const Eigen::VectorXd alpha = Eigen::VectorXd::LinSpaced(q, 1.0, -0.5);
    for (Eigen::Index n_s : {q + 1, Eigen::Index(11), grid.mx()}) {
      REQUIRE(tables.covers(influence));
      const auto table = tables.displacement(n_s, block_of, grid.mx());
      REQUIRE(table);
      for (Eigen::Index first_s : {Eigen::Index(0), grid.mx() - n_s}) {
        const Eigen::Index strip_s = 3;
        const auto source = run_of(grid, first_s, n_s, strip_s);
        const Eigen::VectorXd pressure = block_of(n_s) * alpha;
        for (Eigen::Index strip_t : {Eigen::Index(0), Eigen::Index(3), Eigen::Index(8)}) {
          const auto target = run_of(grid, 0, grid.mx(), strip_t);
          const Eigen::VectorXd expected = influence.dense_block(target, source) * pressure;
          Eigen::VectorXd by_table = Eigen::VectorXd::Zero(grid.mx());
          // Rows d + mx − n_s for d = i_t − i_s, i_t = 0…
          table.add_to(alpha, grid.mx() - n_s - first_s, std::abs(strip_t - strip_s), by_table);
          INFO("n_s " << n_s << " first " << first_s << " strip " << strip_t);
          CHECK((by_table - expected).cwiseAbs().maxCoeff() <= 1e-13 * expected.cwiseAbs().maxCoeff());
        }
      }
    }
  }
};

}  // namespace

TEST_CASE("Correlation tables give the Galerkin blocks A_t' C_ts A_s", "[reduced][correlation]") {
  TableCheck<fastnorm::EllipticBasis>(fastnorm::EllipticBasis()).blocks();
  TableCheck<fastnorm::PolynomialBasis>(fastnorm::PolynomialBasis(4)).blocks();
  TableCheck<fastnorm::PolynomialEdgeBasis>(fastnorm::PolynomialEdgeBasis(fastnorm::PolynomialBasis(2), 2)).blocks();
}

TEST_CASE("Displacement tables give the Galerkin blocks A_t' C_ts A_s of their longer segment",
          "[reduced][correlation]") {
  for (Eigen::Index extra : {0, 7}) {
    INFO("tables made for a grid " << extra << " elements larger");
    TableCheck<fastnorm::EllipticBasis>(fastnorm::EllipticBasis(), extra).blocks_from_displacement();
    TableCheck<fastnorm::PolynomialBasis>(fastnorm::PolynomialBasis(4), extra).blocks_from_displacement();
    TableCheck<fastnorm::PolynomialEdgeBasis>(fastnorm::PolynomialEdgeBasis(fastnorm::PolynomialBasis(2), 2), extra)
        .blocks_from_displacement();
  }
}

TEST_CASE("Displacement tables give the displacement of a segment's basis functions", "[reduced][correlation]") {
  for (Eigen::Index extra : {0, 7}) {  // tables of this grid, and of a larger one read by offset
    INFO("tables made for a grid " << extra << " elements larger");
    TableCheck<fastnorm::EllipticBasis>(fastnorm::EllipticBasis(), extra).displacements();
    TableCheck<fastnorm::PolynomialBasis>(fastnorm::PolynomialBasis(4), extra).displacements();
    TableCheck<fastnorm::PolynomialEdgeBasis>(fastnorm::PolynomialEdgeBasis(fastnorm::PolynomialBasis(2), 2), extra)
        .displacements();
  }
}

TEST_CASE("Segment tables cover grids of their element sizes and E* up to their extent", "[reduced][correlation]") {
  const fastnorm::Grid<> extent(30, 20, 3e-4, 4e-4);
  const fastnorm::detail::SegmentTables<double> tables(
      std::make_shared<const fastnorm::InfluenceTable<>>(extent, steel), std::size_t(1) << 20);
  auto covers = [&](const fastnorm::Grid<>& grid, const fastnorm::Material<>& material) {
    return tables.covers(fastnorm::InfluenceTable<>(grid, material));
  };
  CHECK(covers(extent, steel));
  CHECK(covers(fastnorm::Grid<>(12, 20, 3e-4, 4e-4, -1e-3, 2e-3), steel));  // the origin does not matter
  CHECK_FALSE(covers(fastnorm::Grid<>(31, 20, 3e-4, 4e-4), steel));
  CHECK_FALSE(covers(fastnorm::Grid<>(30, 21, 3e-4, 4e-4), steel));
  CHECK_FALSE(covers(fastnorm::Grid<>(20, 10, 3.1e-4, 4e-4), steel));
  CHECK_FALSE(covers(fastnorm::Grid<>(20, 10, 3e-4, 4.1e-4), steel));
  CHECK_FALSE(covers(fastnorm::Grid<>(20, 10, 3e-4, 4e-4), fastnorm::Material<>(2.1e11, 0.28)));
}

TEMPLATE_TEST_CASE("A solver for_grid shares the tables and answers as a new solver on that grid",
                   "[reduced][correlation]", fastnorm::EllipticBasis, fastnorm::PolynomialBasis,
                   fastnorm::PolynomialEdgeBasis) {
  const auto& grid = fastnorm::test::two_bumps_grid;
  const Eigen::VectorXd h = fastnorm::test::two_bumps(grid, 3e-5);
  const fastnorm::ReducedSolver<TestType> largest(
      fastnorm::Grid<>(grid.mx() + 9, grid.my() + 4, grid.dx(), grid.dy()), steel);
  const auto sibling = largest.for_grid(grid);
  const fastnorm::ReducedSolver<TestType> alone(grid, steel);
  CHECK(sibling.grid().mx() == grid.mx());
  CHECK(sibling.grid().x0() == grid.x0());
  // Its influence coefficients are the largest solver's, read in place (none computed).
  const auto centre = [](const auto& solver) { return solver.influence().table().data() + (solver.grid().mx() - 1); };
  CHECK(centre(sibling) == centre(largest));
  CHECK(centre(alone) != centre(largest));
  for (const auto& loading : {fastnorm::Loading<>::approach(), fastnorm::Loading<>::force(2e3)}) {
    const auto reference = alone.solve(h, loading);
    const auto solution = sibling.solve(h, loading);
    REQUIRE(reference.ok());
    CHECK(solution.iterations == reference.iterations);
    CHECK((solution.in_contact == reference.in_contact).all());
    CHECK((solution.pressure - reference.pressure).cwiseAbs().maxCoeff() == 0.0);  // the same tables' entries
  }
  CHECK(largest.table_bytes() > 0);  // built by the sibling's solves, in the shared tables
  CHECK(largest.table_bytes() == sibling.table_bytes());
  CHECK(largest.table_bytes() >= alone.table_bytes());

  // A grid beyond the extent, or of other element sizes, gets tables of its own.
  const auto beyond = largest.for_grid(fastnorm::Grid<>(grid.mx() + 10, grid.my(), grid.dx(), grid.dy()));
  const auto other_sizes = largest.for_grid(fastnorm::Grid<>(grid.mx(), grid.my(), grid.dx() * 1.5, grid.dy()));
  CHECK(beyond.table_bytes() == 0);
  CHECK(centre(beyond) != centre(largest));
  CHECK(other_sizes.table_bytes() == 0);
  const std::size_t shared = largest.table_bytes();
  REQUIRE(beyond.solve(Eigen::VectorXd::Constant(beyond.grid().size(), -1e-6), fastnorm::Loading<>::approach()).ok());
  CHECK(beyond.table_bytes() > 0);
  CHECK(largest.table_bytes() == shared);
}

TEST_CASE("Segment tables stay within their memory budget", "[reduced][correlation]") {
  const fastnorm::EllipticBasis basis;
  auto block_of = [&](Eigen::Index count) { return basis.block<double>(count); };
  const std::size_t one_table = sizeof(double) * (10 + 10 - 1) * 4;  // n_t = n_s = 10, q = 2
  const auto influence = std::make_shared<const fastnorm::InfluenceTable<>>(fastnorm::Grid<>(20, 4, 1e-3, 1e-3), steel);
  fastnorm::detail::SegmentTables<double> correlations(influence, one_table);
  CHECK(correlations.correlation(10, 10, block_of) != nullptr);
  CHECK(correlations.used_bytes() == one_table);
  CHECK(correlations.correlation(10, 10, block_of) == correlations.correlation(10, 10, block_of));  // built once
  CHECK(correlations.correlation(10, 9, block_of) == nullptr);  // no room left
  CHECK(correlations.used_bytes() == one_table);
  CHECK_FALSE(correlations.displacement(10, block_of, 20));  // one budget for both kinds

  fastnorm::detail::SegmentTables<double> none(influence, 0);
  CHECK(none.correlation(3, 3, block_of) == nullptr);
  CHECK(none.used_bytes() == 0);
}

TEMPLATE_TEST_CASE("Tables built ahead are every table a solve reads, with the answers of tables built on use",
                   "[reduced][correlation]", fastnorm::EllipticBasis, fastnorm::PolynomialEdgeBasis) {
  const auto& grid = fastnorm::test::two_bumps_grid;
  const Eigen::VectorXd h = fastnorm::test::two_bumps(grid, 3e-5);
  const fastnorm::ReducedSolver<TestType> largest(fastnorm::Grid<>(grid.mx() + 4, grid.my() + 4, grid.dx(), grid.dy()),
                                                  steel);
  REQUIRE(largest.build_tables());
  const std::size_t built = largest.table_bytes();
  CHECK(built > 0);
  const auto ahead = largest.for_grid(grid);
  const fastnorm::ReducedSolver<TestType> on_use(grid, steel);
  for (const auto& loading : {fastnorm::Loading<>::approach(), fastnorm::Loading<>::force(2e3)}) {
    const auto solution = ahead.solve(h, loading), reference = on_use.solve(h, loading);
    REQUIRE(reference.ok());
    CHECK((solution.pressure - reference.pressure).cwiseAbs().maxCoeff() == 0.0);
  }
  CHECK(largest.table_bytes() == built);  // the solves built nothing more
  CHECK(on_use.table_bytes() > 0);

  fastnorm::ReducedOptions<> small_budget;
  small_budget.table_budget_bytes = built / 2;
  const fastnorm::ReducedSolver<TestType> too_small(largest.grid(), steel, TestType(), small_budget);
  CHECK_FALSE(too_small.build_tables());  // not all fit: none built ahead
  CHECK(too_small.table_bytes() == 0);
}

TEMPLATE_TEST_CASE("Segment tables and direct products give the same solution",
                   "[reduced][correlation]", fastnorm::EllipticBasis, fastnorm::PolynomialBasis,
                   fastnorm::PolynomialEdgeBasis) {
  const auto& grid = fastnorm::test::two_bumps_grid;
  const Eigen::VectorXd h = fastnorm::test::two_bumps(grid, 3e-5);
  fastnorm::ReducedOptions<> direct_only;
  direct_only.table_budget_bytes = 0;
  const fastnorm::ReducedSolver<TestType> direct(grid, steel, TestType(), direct_only);
  const fastnorm::ReducedSolver<TestType> tabled(grid, steel);
  // A budget below the smallest displacement table (that of the longest segment): the
  // blocks come from correlation tables while they fit, then from direct products.
  fastnorm::ReducedOptions<> correlations_only;
  correlations_only.table_budget_bytes =
      sizeof(double) * static_cast<std::size_t>(grid.mx() * grid.my() * TestType().unknowns()) / 2;
  const fastnorm::ReducedSolver<TestType> correlated(grid, steel, TestType(), correlations_only);
  for (const auto& loading : {fastnorm::Loading<>::approach(), fastnorm::Loading<>::force(2e3)}) {
    const auto reference = direct.solve(h, loading);
    REQUIRE(reference.ok());
    for (const auto* solver : {&tabled, &correlated}) {
      const auto solution = solver->solve(h, loading);
      CHECK(solution.status == reference.status);
      CHECK(solution.iterations == reference.iterations);
      CHECK((solution.in_contact == reference.in_contact).all());
      CHECK((solution.pressure - reference.pressure).cwiseAbs().maxCoeff() <= 1e-11 * reference.pressure.maxCoeff());
    }
  }
  CHECK(direct.table_bytes() == 0);
  CHECK(tabled.table_bytes() > 0);
  CHECK(correlated.table_bytes() > 0);
  CHECK(correlated.table_bytes() <= correlations_only.table_budget_bytes);
}
