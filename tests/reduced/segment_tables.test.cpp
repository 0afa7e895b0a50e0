#include <catch2/catch.hpp>
#include <fastnorm/bases.hpp>
#include <fastnorm/influence.hpp>
#include <fastnorm/reduced_solver.hpp>
#include <fastnorm/detail/segment_tables.hpp>

#include <functional>

#include "support/surfaces.hpp"

namespace {

const fastnorm::Material<> steel(2.1e11, 0.3);

/// Element numbers of `count` consecutive elements of strip j from i = first.
std::vector<Eigen::Index> run_of(const fastnorm::Grid<>& grid, Eigen::Index first, Eigen::Index count,
                                 Eigen::Index strip) {
  std::vector<Eigen::Index> elements;
  for (Eigen::Index i = first; i < first + count; ++i) elements.push_back(grid.index(i, strip));
  return elements;
}

/// Checks the segment tables of `basis` on a small grid against dense products.
template <typename Basis>
struct TableCheck {
  explicit TableCheck(const Basis& b) : basis(b) {}
  Basis basis;
  Eigen::Index q = basis.unknowns();
  fastnorm::Grid<> grid{23, 9, 3e-4, 4e-4};
  fastnorm::InfluenceTable<> influence{grid, steel};
  fastnorm::detail::SegmentTables<double> tables{grid.mx(), std::size_t(1) << 24};
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

  /// Eq. (M3): u at every element of a strip due to p = A α on a source segment, from the
  /// displacement table, against the dense block of the influence table times p.
  void displacements() {
    const Eigen::VectorXd alpha = Eigen::VectorXd::LinSpaced(q, 1.0, -0.5);
    for (Eigen::Index n_s : {q + 1, Eigen::Index(11), grid.mx()}) {
      const auto table = tables.displacement(n_s, block_of, influence);
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

TEST_CASE("Displacement tables give the displacement of a segment's basis functions", "[reduced][correlation]") {
  TableCheck<fastnorm::EllipticBasis>(fastnorm::EllipticBasis()).displacements();
  TableCheck<fastnorm::PolynomialBasis>(fastnorm::PolynomialBasis(4)).displacements();
  TableCheck<fastnorm::PolynomialEdgeBasis>(fastnorm::PolynomialEdgeBasis(fastnorm::PolynomialBasis(2), 2))
      .displacements();
}

TEST_CASE("Segment tables stay within their memory budget", "[reduced][correlation]") {
  const fastnorm::EllipticBasis basis;
  auto block_of = [&](Eigen::Index count) { return basis.block<double>(count); };
  const std::size_t one_table = sizeof(double) * (10 + 10 - 1) * 4;  // n_t = n_s = 10, q = 2
  fastnorm::detail::SegmentTables<double> correlations(20, one_table);
  CHECK(correlations.correlation(10, 10, block_of) != nullptr);
  CHECK(correlations.used_bytes() == one_table);
  CHECK(correlations.correlation(10, 10, block_of) == correlations.correlation(10, 10, block_of));  // built once
  CHECK(correlations.correlation(10, 9, block_of) == nullptr);  // no room left
  CHECK(correlations.used_bytes() == one_table);
  const fastnorm::InfluenceTable<> influence(fastnorm::Grid<>(20, 4, 1e-3, 1e-3), steel);
  CHECK_FALSE(correlations.displacement(10, block_of, influence));  // one budget for both kinds

  fastnorm::detail::SegmentTables<double> none(20, 0);
  CHECK(none.correlation(3, 3, block_of) == nullptr);
  CHECK(none.used_bytes() == 0);
}

TEMPLATE_TEST_CASE("Segment tables and direct products give the same solution",
                   "[reduced][correlation]", fastnorm::EllipticBasis, fastnorm::PolynomialBasis,
                   fastnorm::PolynomialEdgeBasis) {
  const auto grid = fastnorm::test::two_bumps_grid();
  const Eigen::VectorXd h = fastnorm::test::two_bumps(grid, 3e-5);
  fastnorm::ReducedOptions<> direct_only;
  direct_only.table_budget_bytes = 0;
  const fastnorm::ReducedSolver<TestType> direct(grid, steel, TestType(), direct_only);
  const fastnorm::ReducedSolver<TestType> tabled(grid, steel);
  for (const auto& loading : {fastnorm::Loading<>::approach(), fastnorm::Loading<>::force(2e3)}) {
    const auto reference = direct.solve(h, loading);
    const auto solution = tabled.solve(h, loading);
    REQUIRE(reference.ok());
    CHECK(solution.status == reference.status);
    CHECK(solution.iterations == reference.iterations);
    CHECK((solution.in_contact == reference.in_contact).all());
    CHECK((solution.pressure - reference.pressure).cwiseAbs().maxCoeff() <= 1e-11 * reference.pressure.maxCoeff());
  }
  CHECK(direct.table_bytes() == 0);
  CHECK(tabled.table_bytes() > 0);
}
