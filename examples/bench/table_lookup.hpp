// fastnorm-bench --table: ContactTable::lookup (contact_table.hpp, docs/tables.md §4) on a
// table of the size issue 30 names: 85 lateral shifts (−10…10 mm, finer towards the flange) ×
// 21 yaws (0…24 mrad) × 5 loads (50…150 kN), 10 outputs, one pair, every case solved with one
// topology (smooth synthetic outputs: the lookup's cost does not depend on the numbers).
// 20 000 random queries inside the table; each repeat times all of them by multilinear
// interpolation, then by PCHIP (interleaved); medians over the repeats, one thread:
//
//   table shifts=85 yaws=21 loads=5 outputs=10 multilinear_ns=<median per lookup>
//     pchip_ns=<median> pchip_over_multilinear=<x> spread_multilinear=<max/min> spread_pchip=<max/min>
#pragma once

#include <fastnorm/contact_table.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace fastnorm_bench {

inline fastnorm::ContactTable synthetic_table() {
  fastnorm::TableAxes axes;
  for (int i = 0; i < 85; ++i) {
    const double s = i / 84.0;  // finer towards +10 mm, where the flange comes in
    axes.lateral_shift_m.push_back(-10e-3 + 20e-3 * (1.6 * s - 0.6 * s * s));
  }
  for (int j = 0; j < 21; ++j) axes.yaw_rad.push_back(24e-3 * j / 20);
  for (int k = 0; k < 5; ++k) axes.load_n.push_back(5e4 + 2.5e4 * k);
  constexpr int outputs = 10;
  std::vector<std::string> names, units;
  for (int o = 0; o < outputs; ++o) {
    names.push_back("output" + std::to_string(o));
    units.push_back("1");
  }
  std::vector<double> values;
  for (double load : axes.load_n)
    for (double yaw : axes.yaw_rad)
      for (double y : axes.lateral_shift_m)
        for (int o = 0; o < outputs; ++o) values.push_back(std::sin(300 * y + o) * load + yaw * o);
  const std::vector<std::int32_t> topology(axes.lateral_shift_m.size() * axes.yaw_rad.size() * axes.load_n.size(), 1);
  return fastnorm::ContactTable(axes, {"synthetic"}, names, units, values, topology);
}

inline void bench_table_lookup(int repeats) {
  using Clock = std::chrono::steady_clock;
  const fastnorm::ContactTable table = synthetic_table();
  const auto& axes = table.axes();
  std::mt19937 generator(1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  constexpr int queries = 20000;
  std::vector<std::array<double, 3>> points(queries);
  for (auto& point : points)
    point = {axes.lateral_shift_m.front() + unit(generator) * (axes.lateral_shift_m.back() - axes.lateral_shift_m.front()),
             axes.yaw_rad.back() * unit(generator),
             axes.load_n.front() + unit(generator) * (axes.load_n.back() - axes.load_n.front())};
  std::vector<double> out(table.outputs());
  double checksum = 0;
  auto time_all = [&](fastnorm::TableInterpolation how) {
    const auto start = Clock::now();
    for (const auto& point : points) {
      if (table.lookup(0, point[0], point[1], point[2], how, out.data()) != fastnorm::TableLookupStatus::ok) {
        throw std::logic_error("fastnorm-bench --table: a lookup inside the table failed");
      }
      checksum += out[0];
    }
    return std::chrono::duration<double, std::nano>(Clock::now() - start).count() / queries;
  };
  std::vector<double> multilinear, pchip, ratio;
  for (int r = 0; r < repeats; ++r) {
    multilinear.push_back(time_all(fastnorm::TableInterpolation::multilinear));
    pchip.push_back(time_all(fastnorm::TableInterpolation::pchip));
    ratio.push_back(pchip.back() / multilinear.back());
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  };
  auto spread = [](const std::vector<double>& v) {
    return *std::max_element(v.begin(), v.end()) / *std::min_element(v.begin(), v.end());
  };
  std::cout << "table shifts=" << axes.lateral_shift_m.size() << " yaws=" << axes.yaw_rad.size()
            << " loads=" << axes.load_n.size() << " outputs=" << table.outputs()
            << " multilinear_ns=" << median(multilinear) << " pchip_ns=" << median(pchip)
            << " pchip_over_multilinear=" << median(ratio) << " spread_multilinear=" << spread(multilinear)
            << " spread_pchip=" << spread(pchip) << (std::isfinite(checksum) ? "" : " (checksum not finite)")
            << std::endl;
}

}  // namespace fastnorm_bench
