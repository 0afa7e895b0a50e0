// The CONTACT set-up of a `wr_*` peer case, read from its comment lines (mm and rad as
// CONTACT prints them): wheel, wheelset position, contact reference point.
#pragma once

#include <catch2/catch.hpp>
#include <fastnorm/wheelrail.hpp>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/peer_cases.hpp"

namespace fastnorm::test {

struct WheelRailCase {
  wheelrail::Side side = wheelrail::Side::right;
  double y_mm = 0, z_mm = 0, roll = 0, yaw = 0;     // wheelset position
  double xcp = 0, ycp = 0, zcp = 0, deltcp = 0;     // contact reference point (mm, rad)
};

// A wheelset contact model's options on a coarse patch grid, for tests that need many steps.
inline wheelrail::WheelsetContactOptions coarse_contact(const char* solver = "norm", int elements = 30) {
  wheelrail::WheelsetContactOptions options;
  options.solver = SolverSpec<double>::parse(solver);
  options.grid.elements = elements;
  return options;
}

// The wr_* peer cases; none, with a warning, when ../shared/peer-cases is absent.
inline std::vector<std::string> wheelrail_peer_cases() {
  auto files = peer_case_files("wr_");
  if (files.empty()) reference_data_missing("no wr_* peer cases found");
  return files;
}

inline WheelRailCase read_wheelrail_case(const std::string& path) {
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto after = [&](const std::string& key) {
    const auto at = text.find(key);
    if (at == std::string::npos) throw std::runtime_error(path + ": no '" + key + "'");
    return std::stod(text.substr(at + key.size()));
  };
  WheelRailCase c;
  c.side = text.find("right wheel (C1=1)") != std::string::npos ? wheelrail::Side::right : wheelrail::Side::left;
  c.xcp = after("XCP="), c.ycp = after("YCP="), c.zcp = after("ZCP="), c.deltcp = after("DELTCP=");
  const auto at = text.find("S,Y,Z,ROLL,YAW,PITCH [");
  if (at == std::string::npos) throw std::runtime_error(path + ": no wheelset position");
  double s = 0;
  if (std::sscanf(text.c_str() + at + 22, "%lf, %lf, %lf, %lf, %lf", &s, &c.y_mm, &c.z_mm, &c.roll, &c.yaw) != 5) {
    throw std::runtime_error(path + ": unreadable wheelset position");
  }
  return c;
}

}  // namespace fastnorm::test
