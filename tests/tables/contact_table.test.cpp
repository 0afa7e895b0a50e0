// ContactTable (docs/tables.md §4): multilinear and PCHIP lookups against closed forms, the
// topology guard, and the export file.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <fastnorm/contact_table.hpp>
#include <fastnorm/contact_table_file.hpp>

using Catch::Matchers::Contains;
using fastnorm::ContactTable;
using fastnorm::TableAxes;
using fastnorm::TableInterpolation;
using fastnorm::TableLookupStatus;

namespace {

using Field = std::function<double(double y, double yaw, double load)>;

/// Nodes from `first` to `last` whose spacing grows by `growth` per interval (non-uniform).
std::vector<double> graded_axis(double first, double last, int count, double growth) {
  std::vector<double> nodes(static_cast<std::size_t>(count));
  double total = 0, width = 1;
  for (int i = 1; i < count; ++i, width *= growth) total += width;
  nodes[0] = first;
  width = 1;
  for (int i = 1; i < count; ++i, width *= growth) nodes[std::size_t(i)] = nodes[std::size_t(i) - 1] + (last - first) * width / total;
  nodes.back() = last;
  return nodes;
}

/// Topology code of a case by its y index i and yaw index j.
using Code = std::function<std::int32_t(std::size_t i, std::size_t j)>;

/// One pair; outputs field(y, yaw, load) and 2·field + 1; every case of topology `code(i, j)`;
/// with `derivative`, its values at the nodes as the measured ∂/∂y of both outputs.
ContactTable table_of(const TableAxes& axes, const Field& field,
                      const Code& code = [](std::size_t, std::size_t) { return 0; }, const Field& derivative = {}) {
  std::vector<double> values, measured;
  std::vector<std::int32_t> topology;
  for (double load : axes.load_n)
    for (std::size_t j = 0; j < axes.yaw_rad.size(); ++j)
      for (std::size_t i = 0; i < axes.lateral_shift_m.size(); ++i) {
        const double y = axes.lateral_shift_m[i], yaw = axes.yaw_rad[j];
        const double f = field(y, yaw, load);
        values.push_back(f);
        values.push_back(2 * f + 1);
        topology.push_back(code(i, j));
        if (derivative) {
          measured.push_back(derivative(y, yaw, load));
          measured.push_back(2 * derivative(y, yaw, load));
        }
      }
  return ContactTable(axes, {"S1002/UIC60"}, {"fn", "twice"}, {"N", "N"}, values, topology, measured);
}

TableAxes example_axes() {
  return {graded_axis(-6e-3, 6e-3, 13, 0.9), graded_axis(0.0, 0.02, 6, 1.2), graded_axis(5e4, 1.5e5, 4, 1.0)};
}

std::array<double, 2> lookup(const ContactTable& table, double y, double yaw, double load, TableInterpolation how,
                             TableLookupStatus expected = TableLookupStatus::ok) {
  std::array<double, 2> out{-1.0, -1.0};
  REQUIRE(table.lookup(0, y, yaw, load, how, out.data()) == expected);
  return out;
}

/// Random points inside the axes' ranges.
std::vector<std::array<double, 3>> inner_points(const TableAxes& axes, int count) {
  std::mt19937 generator(7);
  auto within = [&](const std::vector<double>& axis) {
    return std::uniform_real_distribution<double>(axis.front(), axis.back())(generator);
  };
  std::vector<std::array<double, 3>> points;
  for (int n = 0; n < count; ++n) points.push_back({within(axes.lateral_shift_m), within(axes.yaw_rad), within(axes.load_n)});
  return points;
}

/// The largest interpolation error at the midpoints of the y intervals, yaw and load fixed at nodes.
double midpoint_error(int shifts, TableInterpolation how) {
  const Field smooth = [](double y, double, double) { return std::exp(200 * y); };
  const TableAxes axes{graded_axis(-6e-3, 6e-3, shifts, 1.0), {0.0}, {1e5}};
  const ContactTable table = table_of(axes, smooth);
  double worst = 0;
  for (std::size_t i = 0; i + 1 < axes.lateral_shift_m.size(); ++i) {
    const double y = 0.5 * (axes.lateral_shift_m[i] + axes.lateral_shift_m[i + 1]);
    worst = std::max(worst, std::abs(lookup(table, y, 0.0, 1e5, how)[0] - smooth(y, 0, 0)));
  }
  return worst;
}

}  // namespace

TEST_CASE("Both interpolations reproduce multilinear data exactly and the nodes bit for bit", "[table]") {
  const Field trilinear = [](double y, double yaw, double load) {
    return 3e4 + 2e6 * y - 4e5 * yaw + 0.3 * load + 7e7 * y * yaw - 5 * y * load + 2 * yaw * load + 300 * y * yaw * load;
  };
  const TableAxes axes = example_axes();
  const ContactTable table = table_of(axes, trilinear);
  for (TableInterpolation how : {TableInterpolation::multilinear, TableInterpolation::pchip}) {
    for (const auto& point : inner_points(axes, 400)) {
      const double exact = trilinear(point[0], point[1], point[2]);
      const auto got = lookup(table, point[0], point[1], point[2], how);
      CHECK(got[0] == Approx(exact).epsilon(1e-12));
      CHECK(got[1] == Approx(2 * exact + 1).epsilon(1e-12));
    }
    for (double y : axes.lateral_shift_m)
      for (double yaw : axes.yaw_rad) {
        const auto got = lookup(table, y, yaw, axes.load_n[2], how);
        CHECK(got[0] == trilinear(y, yaw, axes.load_n[2]));
      }
  }
}

TEST_CASE("PCHIP converges at third order on smooth data, multilinear at second", "[table]") {
  const double linear_ratio = midpoint_error(25, TableInterpolation::multilinear) /
                              midpoint_error(49, TableInterpolation::multilinear);
  const double pchip_ratio =
      midpoint_error(25, TableInterpolation::pchip) / midpoint_error(49, TableInterpolation::pchip);
  CHECK(linear_ratio == Approx(4).epsilon(0.1));
  CHECK(pchip_ratio > 6.5);  // h³: 8 in the limit
  CHECK(midpoint_error(25, TableInterpolation::pchip) < 0.05 * midpoint_error(25, TableInterpolation::multilinear));
}

TEST_CASE("PCHIP keeps monotone data monotone and is C1 across nodes", "[table]") {
  // A smoothed step (flange contact's onset has this shape): cubic splines overshoot it.
  const Field step = [](double y, double, double) { return y < 1e-3 ? 1.0 : (y < 2e-3 ? 1.0 + 9 * (y - 1e-3) / 1e-3 : 10.0); };
  const TableAxes axes{graded_axis(-6e-3, 6e-3, 13, 1.0), {0.0}, {1e5}};
  const ContactTable table = table_of(axes, step);
  double previous = -std::numeric_limits<double>::infinity();
  for (int n = 0; n <= 2000; ++n) {
    const double y = -6e-3 + 12e-3 * n / 2000;
    const double value = lookup(table, y, 0.0, 1e5, TableInterpolation::pchip)[0];
    CHECK(value >= previous);
    CHECK(value >= 1.0);
    CHECK(value <= 10.0);
    previous = value;
  }
  // The one-sided slopes at an inner node agree (to the differences' truncation).
  const Field smooth = [](double y, double, double) { return std::sin(300 * y); };
  const ContactTable smooth_table = table_of(axes, smooth);
  const double node = axes.lateral_shift_m[5], step_size = 1e-9;
  auto at = [&](double y) { return lookup(smooth_table, y, 0.0, 1e5, TableInterpolation::pchip)[0]; };
  const double left = (at(node) - at(node - step_size)) / step_size;
  const double right = (at(node + step_size) - at(node)) / step_size;
  CHECK(left == Approx(right).epsilon(1e-4));
}

TEST_CASE("Measured derivatives along y: exact for cubics in y, NaN falls back to PCHIP, monotone kept", "[table]") {
  // Cubic in y, linear in yaw and load (which PCHIP reproduces), increasing in y.
  const Field cubic = [](double y, double yaw, double load) { return 1 + 100 * y + 1e6 * y * y * y + 3 * yaw + 1e-5 * load; };
  const Field slope = [](double y, double, double) { return 100 + 3e6 * y * y; };
  const TableAxes axes = example_axes();
  const auto always = [](std::size_t, std::size_t) { return std::int32_t(0); };
  const ContactTable measured = table_of(axes, cubic, always, slope);
  const ContactTable estimated = table_of(axes, cubic);
  double estimated_error = 0;
  for (const auto& point : inner_points(axes, 300)) {
    const double exact = cubic(point[0], point[1], point[2]);
    const auto got = lookup(measured, point[0], point[1], point[2], TableInterpolation::pchip);
    CHECK(got[0] == Approx(exact).epsilon(1e-12));
    CHECK(got[1] == Approx(2 * exact + 1).epsilon(1e-12));
    estimated_error = std::max(
        estimated_error, std::abs(lookup(estimated, point[0], point[1], point[2], TableInterpolation::pchip)[0] - exact));
  }
  CHECK(estimated_error > 1e-6);  // PCHIP's own slopes are not exact for the cubic
  // NaN: nothing measured there, PCHIP's estimate, bit for bit; the file keeps the measured ones.
  const ContactTable unmeasured = table_of(axes, cubic, always, [](double, double, double) { return std::nan(""); });
  const std::string path = "contact_table_measured_test.fntable";
  fastnorm::write_contact_table(measured, path);
  const ContactTable read = fastnorm::read_contact_table(path);
  std::remove(path.c_str());
  for (const auto& point : inner_points(axes, 50)) {
    CHECK(lookup(unmeasured, point[0], point[1], point[2], TableInterpolation::pchip)[0] ==
          lookup(estimated, point[0], point[1], point[2], TableInterpolation::pchip)[0]);
    CHECK(lookup(read, point[0], point[1], point[2], TableInterpolation::pchip)[0] ==
          lookup(measured, point[0], point[1], point[2], TableInterpolation::pchip)[0]);
  }
  // Wrong-signed or far too steep measurements are limited: the smoothed step stays within its
  // cells' values and monotone.
  const Field step = [](double y, double, double) { return y < 1e-3 ? 1.0 : (y < 2e-3 ? 1.0 + 9 * (y - 1e-3) / 1e-3 : 10.0); };
  const TableAxes line{graded_axis(-6e-3, 6e-3, 13, 1.0), {0.0}, {1e5}};
  for (const double wild : {-5e3, 5e5}) {
    const ContactTable limited = table_of(line, step, always, [wild](double, double, double) { return wild; });
    double previous = -std::numeric_limits<double>::infinity();
    for (int n = 0; n <= 2000; ++n) {
      const double value = lookup(limited, -6e-3 + 12e-3 * n / 2000, 0.0, 1e5, TableInterpolation::pchip)[0];
      CHECK(value >= previous);
      CHECK(value >= 1.0);
      CHECK(value <= 10.0);
      previous = value;
    }
  }
  // Sizes and values it refuses.
  const std::vector<double> values{1, 2, 3, 4};
  const std::vector<std::int32_t> codes{0, 0};
  const TableAxes two{{0.0, 1e-3}, {0.0}, {1e5}};
  auto make = [&](std::vector<double> derivatives) {
    return ContactTable(two, {"p"}, {"fn", "pmax"}, {"N", "Pa"}, values, codes, std::move(derivatives));
  };
  CHECK_NOTHROW(make({}));
  CHECK_NOTHROW(make({1, std::nan(""), 3, 4}));
  CHECK_THROWS_WITH(make({1, 2, 3}), Contains("measured_shift_derivatives must be empty or hold one number per value"));
  CHECK_THROWS_WITH(make({1, 2, std::numeric_limits<double>::infinity(), 4}), Contains("measured_shift_derivatives[2]"));
}

TEST_CASE("The topology guard: no blend across a change of patch count", "[table]") {
  const Field field = [](double y, double yaw, double load) { return 1e4 + 1e6 * y * y + 1e3 * yaw + 0.1 * load; };
  const TableAxes axes = example_axes();
  const std::size_t change = 8;  // cases from y index 9 on have another code (say, a flange patch)
  auto code = [&](std::size_t i, std::size_t) { return std::int32_t(i <= change ? 1 : 2); };
  // Beyond the change the values jump: a blend would show.
  const Field jumped = [&](double y, double yaw, double load) {
    return y > axes.lateral_shift_m[change] ? 1e9 : field(y, yaw, load);
  };
  const ContactTable table = table_of(axes, jumped, code);
  TableAxes before = axes;
  before.lateral_shift_m.resize(change + 1);
  const ContactTable truncated = table_of(before, field, code);

  const double yaw = 0.013, load = 9e4;
  const double across = 0.5 * (axes.lateral_shift_m[change] + axes.lateral_shift_m[change + 1]);
  for (TableInterpolation how : {TableInterpolation::multilinear, TableInterpolation::pchip}) {
    lookup(table, across, yaw, load, how, TableLookupStatus::topology_change);
    // In the cells before the change, PCHIP's stencil stops at the change: the same numbers as
    // a table that ends there, bit for bit.
    for (std::size_t cell = change - 2; cell < change; ++cell) {
      const double y = 0.3 * axes.lateral_shift_m[cell] + 0.7 * axes.lateral_shift_m[cell + 1];
      CHECK(lookup(table, y, yaw, load, how)[0] == lookup(truncated, y, yaw, load, how)[0]);
    }
    // A node belongs to the cell above it: at the last node before the change that cell's
    // corners differ.
    lookup(table, axes.lateral_shift_m[change], yaw, load, how, TableLookupStatus::topology_change);
  }
}

TEST_CASE("The guard along y is per line: a change in one yaw line leaves its neighbours' derivatives two-sided",
          "[table]") {
  // Line yaw index 2 changes code from y index 8 on; the other lines do not. Nothing beyond the
  // change may enter a lookup: the answer cannot depend on the values held there.
  const Field field = [](double y, double yaw, double load) { return 1e4 + 1e6 * y * y + 1e3 * yaw + 0.1 * load; };
  const TableAxes axes = example_axes();
  const std::size_t changed_line = 2, change = 8;
  const Code code = [&](std::size_t i, std::size_t j) { return std::int32_t(j == changed_line && i >= change ? 2 : 1); };
  auto table_with = [&](double beyond) {
    const Field held = [&](double y, double yaw, double load) {
      const bool across = yaw == axes.yaw_rad[changed_line] && y >= axes.lateral_shift_m[change];
      return across ? beyond : field(y, yaw, load);
    };
    return table_of(axes, held, code);
  };
  const ContactTable high = table_with(1e9), low = table_with(-5e8);
  const double load = 9e4;
  // Cells whose y stencil reaches the change on the changed line: that line a corner line of
  // the yaw cell (its derivative one-sided along y), or an outer line (its yaw layer dropped).
  for (std::size_t yaw_cell : {changed_line - 2, changed_line - 1, changed_line, changed_line + 1}) {
    const double yaw = 0.4 * axes.yaw_rad[yaw_cell] + 0.6 * axes.yaw_rad[yaw_cell + 1];
    for (std::size_t cell = change - 3; cell + 1 < change; ++cell) {
      const double y = 0.6 * axes.lateral_shift_m[cell] + 0.4 * axes.lateral_shift_m[cell + 1];
      const auto a = lookup(high, y, yaw, load, TableInterpolation::pchip);
      CHECK(a[0] == lookup(low, y, yaw, load, TableInterpolation::pchip)[0]);
      CHECK(std::abs(a[0] - field(y, yaw, load)) < 1e-3 * field(y, yaw, load));
    }
  }
}

TEST_CASE("Failed cases are never interpolated", "[table]") {
  const Field field = [](double y, double, double) { return 1 + y; };
  const TableAxes axes = example_axes();
  const ContactTable table = table_of(axes, field, [](std::size_t i, std::size_t) { return std::int32_t(i >= 11 ? -1 : 0); });
  const auto& y = axes.lateral_shift_m;
  lookup(table, 0.5 * (y[10] + y[11]), 0.01, 1e5, TableInterpolation::pchip, TableLookupStatus::topology_change);
  lookup(table, 0.5 * (y[11] + y[12]), 0.01, 1e5, TableInterpolation::multilinear, TableLookupStatus::failed_case);
  const auto untouched = lookup(table, 0.5 * (y[11] + y[12]), 0.01, 1e5, TableInterpolation::pchip,
                                TableLookupStatus::failed_case);
  CHECK(untouched[0] == -1.0);  // the outputs are not written
}

TEST_CASE("Queries outside the axes, or NaN, are out of range; a one-node axis takes its value only", "[table]") {
  const Field field = [](double y, double yaw, double) { return y + yaw; };
  const TableAxes axes{graded_axis(-6e-3, 6e-3, 7, 1.0), graded_axis(0, 0.02, 3, 1.0), {1e5}};
  const ContactTable table = table_of(axes, field);
  for (TableInterpolation how : {TableInterpolation::multilinear, TableInterpolation::pchip}) {
    CHECK(lookup(table, 6e-3, 0.02, 1e5, how)[0] == Approx(0.026).epsilon(1e-14));  // the upper corner
    lookup(table, -6.001e-3, 0.0, 1e5, how, TableLookupStatus::out_of_range);
    lookup(table, 0.0, 0.0201, 1e5, how, TableLookupStatus::out_of_range);
    lookup(table, std::nan(""), 0.0, 1e5, how, TableLookupStatus::out_of_range);
    lookup(table, 0.0, 0.0, 1.0001e5, how, TableLookupStatus::out_of_range);
    CHECK(lookup(table, 1e-3, 0.01, 1e5, how)[0] == Approx(0.011).epsilon(1e-13));
  }
  std::array<double, 2> out{};
  CHECK_THROWS_WITH(table.lookup(1, 0, 0, 1e5, TableInterpolation::pchip, out.data()), Contains("pair"));
  CHECK(table.output_index("twice") == 1);
  CHECK_THROWS_WITH(table.output_index("pmax"), Contains("pmax"));
}

TEST_CASE("A table refuses bad arrays, naming them", "[table]") {
  const TableAxes axes{{0.0, 1e-3}, {0.0}, {1e5}};
  const std::vector<double> values{1, 2, 3, 4};
  const std::vector<std::int32_t> topology{0, 0};
  auto make = [&](TableAxes a, std::vector<std::string> units, std::vector<double> v, std::vector<std::int32_t> t) {
    return ContactTable(std::move(a), {"pair"}, {"fn", "pmax"}, std::move(units), std::move(v), std::move(t));
  };
  CHECK_NOTHROW(make(axes, {"N", "Pa"}, values, topology));
  CHECK_THROWS_WITH(make({{1e-3, 0.0}, {0.0}, {1e5}}, {"N", "Pa"}, values, topology),
                    Contains("axes.lateral_shift_m must increase strictly"));
  CHECK_THROWS_WITH(make({{0.0, 1e-3}, {}, {1e5}}, {"N", "Pa"}, values, topology), Contains("axes.yaw_rad"));
  CHECK_THROWS_WITH(make({{0.0, 1e-3}, {0.0}, {std::nan("")}}, {"N", "Pa"}, values, topology),
                    Contains("axes.load_n[0] must be finite"));
  CHECK_THROWS_WITH(make(axes, {"N"}, values, topology), Contains("output_units"));
  CHECK_THROWS_WITH(make(axes, {"N", "Pa"}, {1, 2, 3}, topology), Contains("values must hold"));
  CHECK_THROWS_WITH(make(axes, {"N", "Pa"}, values, {0}), Contains("topology must hold"));
  CHECK_THROWS_WITH(make(axes, {"N", "Pa"}, {1, 2, std::nan(""), 4}, topology), Contains("output 'fn' of solved case 1"));
  CHECK_NOTHROW(make(axes, {"N", "Pa"}, {1, 2, std::nan(""), 4}, {0, -3}));  // a failed case may hold NaN
}

TEST_CASE("The export file round-trips bit for bit and refuses what it is not", "[table]") {
  const Field field = [](double y, double yaw, double load) { return std::cos(100 * y) + yaw * load; };
  const TableAxes axes = example_axes();
  const ContactTable table = table_of(axes, field, [](std::size_t i, std::size_t) { return std::int32_t(i % 3 == 0 ? -1 : 2); });
  const std::string path = "contact_table_test.fntable";
  fastnorm::write_contact_table(table, path);
  const ContactTable read = fastnorm::read_contact_table(path);
  CHECK(read.axes().lateral_shift_m == axes.lateral_shift_m);
  CHECK(read.axes().yaw_rad == axes.yaw_rad);
  CHECK(read.axes().load_n == axes.load_n);
  CHECK(read.pair_names() == table.pair_names());
  CHECK(read.output_names() == table.output_names());
  CHECK(read.output_units() == table.output_units());
  CHECK(read.topology() == table.topology());
  REQUIRE(read.values().size() == table.values().size());
  for (std::size_t n = 0; n < table.values().size(); ++n)
    if (table.topology()[n / 2] >= 0) CHECK(read.values()[n] == table.values()[n]);

  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  auto write_bytes = [&](const std::string& content) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << content;
  };
  write_bytes(bytes.substr(0, bytes.size() - 5));
  CHECK_THROWS_WITH(fastnorm::read_contact_table(path), Contains("ends before its topology"));
  write_bytes(bytes + "x");
  CHECK_THROWS_WITH(fastnorm::read_contact_table(path), Contains("bytes after its last part"));
  write_bytes("NOTATABLE" + bytes.substr(9));
  CHECK_THROWS_WITH(fastnorm::read_contact_table(path), Contains("not a fastnorm contact table"));
  std::string other_version = bytes;
  other_version[8] = 3;
  write_bytes(other_version);
  CHECK_THROWS_WITH(fastnorm::read_contact_table(path), Contains("format version"));
  std::string bad_flag = bytes;
  bad_flag[bytes.size() - 4] = 2;  // no measured derivatives: the flag is the last 4 bytes
  write_bytes(bad_flag);
  CHECK_THROWS_WITH(fastnorm::read_contact_table(path), Contains("measured-derivatives flag"));
  // Version 1, the same without the flag, is still read.
  std::string version_one = bytes.substr(0, bytes.size() - 4);
  version_one[8] = 1;
  write_bytes(version_one);
  const ContactTable old = fastnorm::read_contact_table(path);
  CHECK(old.topology() == table.topology());
  CHECK(old.measured_shift_derivatives().empty());
  std::remove(path.c_str());
  CHECK_THROWS_WITH(fastnorm::read_contact_table(path), Contains("cannot open"));
}
