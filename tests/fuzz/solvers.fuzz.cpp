// libFuzzer target: every solver on small problems decoded from the bytes (at most 16 x 16
// elements), in both controls. Most inputs are physical: a random ellipsoid with waviness
// on a random grid and material. Some take every number raw from the bytes (NaN, inf,
// negative, huge) to reach the argument checks. Properties: bad arguments throw
// fastnorm::invalid_argument and nothing else escapes; an answer the status calls usable
// has finite, non-negative pressures whose sum is the force, meets a prescribed force, and
// for NORM satisfies the Signorini conditions on every element (checked here with the
// influence coefficients, independently of the solver).

#include <fuzzer/FuzzedDataProvider.h>

#include <fastnorm/any_solver.hpp>
#include <fastnorm/influence.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

#include "fuzz_check.hpp"
#include "support/signorini.hpp"

namespace {

using fastnorm::fuzz::require;
constexpr double pi = 3.14159265358979323846;

const char* const solver_names[] = {"norm", "cg", "elliptic", "polynomial:2", "polynomial:4", "elliptic-edge:1",
                                    "polynomial-edge:3:1"};

double raw_double(FuzzedDataProvider& data) {
  const auto bytes = data.ConsumeBytes<std::uint8_t>(sizeof(double));
  double value = 0;  // 0 once the input is used up
  if (!bytes.empty()) std::memcpy(&value, bytes.data(), bytes.size());
  return value;
}

// The problem's numbers: physical ranges, or raw bits.
struct Numbers {
  FuzzedDataProvider& data;
  bool raw;
  double in(double low, double high) { return raw ? raw_double(data) : data.ConsumeFloatingPointInRange(low, high); }
};

// NORM's answer against g = h − δ + C p ≥ 0, p ≥ 0, g·p = 0 (docs/design.md §1) to
// round-off: 1e-9 of the largest |h − δ| (NORM's join test allows 2e-13 of max |h|).
void check_signorini(const fastnorm::Grid<>& grid, const fastnorm::Material<>& material, const Eigen::VectorXd& h,
                     const fastnorm::Solution<>& solution) {
  const double depth = solution.approach - h.minCoeff();
  const double scale = (h.array() - solution.approach).abs().maxCoeff();
  const double error = fastnorm::test::complementarity_error(fastnorm::InfluenceTable<>(grid, material), h, solution);
  require(error * depth <= 1e-9 * scale, "NORM satisfies the Signorini conditions");
}

void check_answer(const fastnorm::Grid<>& grid, const fastnorm::Material<>& material, const Eigen::VectorXd& h,
                  const fastnorm::Loading<>& loading, const std::string& solver, const fastnorm::Solution<>& solution) {
  require(solution.status != fastnorm::Status::not_solved, "a solve fills its answer");
  require(solution.pressure.size() == grid.size() && solution.in_contact.size() == grid.size(),
          "an answer has a value per element");
  if (!solution.ok()) return;  // iteration limit or numerical issue: said, nothing to check
  require(solution.pressure.allFinite() && (solution.pressure.array() >= 0).all(), "pressures finite, >= 0");
  require(std::isfinite(solution.normal_force) && std::isfinite(solution.approach), "force and approach finite");
  const double sum = grid.element_area() * solution.pressure.sum();
  require(std::abs(solution.normal_force - sum) <= 1e-7 * sum, "the force is the sum of the pressures");
  if (loading.control == fastnorm::Control::force) {
    require(std::abs(solution.normal_force - loading.normal_force) <= 1e-7 * loading.normal_force,
            "a prescribed force is met");
  }
  if (solver == "norm" && solution.status == fastnorm::Status::converged) check_signorini(grid, material, h, solution);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
  FuzzedDataProvider data(bytes, size);
  const std::string solver = solver_names[data.ConsumeIntegralInRange<std::size_t>(0, std::size(solver_names) - 1)];
  const bool force_control = data.ConsumeBool();
  Numbers number{data, data.ConsumeIntegralInRange(0, 7) == 0};
  const auto mx = data.ConsumeIntegralInRange<Eigen::Index>(1, 16), my = data.ConsumeIntegralInRange<Eigen::Index>(1, 16);
  const double dx = number.in(2e-5, 2e-3), dy = number.in(2e-5, 2e-3);
  const double young = number.in(1e8, 1e13), poisson = number.in(0.0, 0.49);
  // h = x²/(2 Rx) + y²/(2 Ry) + waviness − approach, centred on a random point of the grid.
  const double radius_x = number.in(2e-3, 10.0), radius_y = number.in(2e-3, 10.0);
  const double centre_x = number.in(-1.0, 1.0), centre_y = number.in(-1.0, 1.0);
  const double wave_amplitude = number.in(0.0, 2e-5), wave_length = number.in(2.0, 30.0);
  const double approach = number.in(-1e-5, 2e-4), force = number.in(1.0, 1e6);
  try {
    const fastnorm::Grid<> grid(mx, my, dx, dy, -0.5 * (double(mx) - 1) * dx, -0.5 * (double(my) - 1) * dy);
    const fastnorm::Material<> material(young, poisson);
    Eigen::VectorXd h(grid.size());
    for (Eigen::Index j = 0; j < my; ++j) {
      for (Eigen::Index i = 0; i < mx; ++i) {
        const double x = grid.x(i) - centre_x * 0.5 * double(mx) * dx, y = grid.y(j) - centre_y * 0.5 * double(my) * dy;
        const double waviness = std::sin(2 * pi * x / (wave_length * dx)) * std::cos(2 * pi * y / (wave_length * dy));
        h(grid.index(i, j)) = x * x / (2 * radius_x) + y * y / (2 * radius_y) + wave_amplitude * waviness -
                              (force_control ? 0.0 : approach);
      }
    }
    const auto loading = force_control ? fastnorm::Loading<>::force(force) : fastnorm::Loading<>::approach();
    const fastnorm::AnySolver<> any(solver, grid, material);
    check_answer(grid, material, h, loading, solver, any.solve(h, loading));
  } catch (const fastnorm::invalid_argument&) {
  }
  return 0;
}
