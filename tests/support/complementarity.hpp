#pragma once
// Checks the Signorini conditions on a returned solution: p ≥ 0, g = h − δ + C p ≥ 0 to
// round-off, and g·p = 0 relative to the scales of the problem.

#include <catch2/catch.hpp>
#include <fastnorm/influence.hpp>
#include <fastnorm/solution.hpp>

namespace fastnorm::test {

/// Largest violations, each relative to its scale.
struct Complementarity {
  double negative_pressure;  ///< max(−p) / max p
  double negative_gap;       ///< max(−g) / max|h|
  double gap_times_pressure; ///< max |g·p| / (max|h| · max p)
};

inline Complementarity complementarity(const fastnorm::InfluenceTable<>& table, const Eigen::VectorXd& h,
                                       const fastnorm::Solution<>& solution) {
  const Eigen::VectorXd gap =
      (h.array() - solution.approach).matrix() + table.displacement(solution.pressure);
  const double pressure_scale = std::max(solution.pressure.maxCoeff(), 1e-300);
  const double gap_scale = h.cwiseAbs().maxCoeff();
  return {std::max(0.0, -solution.pressure.minCoeff()) / pressure_scale,
          std::max(0.0, -gap.minCoeff()) / gap_scale,
          (gap.array() * solution.pressure.array()).abs().maxCoeff() / (gap_scale * pressure_scale)};
}

/// REQUIREs the Signorini conditions to round-off (1e-9 of the scales).
inline void require_complementarity(const fastnorm::InfluenceTable<>& table, const Eigen::VectorXd& h,
                                    const fastnorm::Solution<>& solution) {
  const auto violation = complementarity(table, h, solution);
  INFO("negative pressure " << violation.negative_pressure << ", negative gap "
                            << violation.negative_gap << ", |g p| " << violation.gap_times_pressure);
  CHECK(violation.negative_pressure == 0);
  CHECK(violation.negative_gap <= 1e-9);
  CHECK(violation.gap_times_pressure <= 1e-9);
}

}  // namespace fastnorm::test
