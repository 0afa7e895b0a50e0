#include <unistd.h>

#include <catch2/catch.hpp>
#include <fastnorm/case_file.hpp>
#include <filesystem>
#include <sstream>

using Catch::Matchers::Contains;

namespace {

const char* const valid_case = R"(# a comment before the magic line
fastnorm-case 1
name small test case
source hand-written   # trailing comment

grid mx 3 my 2 dx 1e-4 dy 2e-4 x0 -1e-4 y0 0
material E 2.1e11 nu 0.3
control force 1500
h
 1e-6 -2e-6 3e-6
-4e-6 5e-6 -6e-6
result ncontact 3 fn 1500 approach 1e-6 unknown_field 7 iterations 2 solve_s 0.01
p
0 1e8 0
1e8 0 5e7
)";

fastnorm::Case<> read_text(const std::string& text) {
  std::istringstream in(text);
  return fastnorm::read_case(in, "test.case");
}

// Replaces the first occurrence of `from` in the valid case by `to`.
std::string edited(const std::string& from, const std::string& to) {
  std::string text = valid_case;
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

int error_line(const std::string& text) {
  try {
    read_text(text);
  } catch (const fastnorm::case_format_error& error) {
    return error.line();
  }
  return -1;
}

}  // namespace

TEST_CASE("Case reader reads every part", "[case]") {
  const auto problem = read_text(valid_case);
  CHECK(problem.name == "small test case");
  CHECK(problem.source == "hand-written");
  CHECK(problem.grid.mx() == 3);
  CHECK(problem.grid.my() == 2);
  CHECK(problem.grid.dy() == 2e-4);
  CHECK(problem.grid.x0() == -1e-4);
  CHECK(problem.material.young_modulus() == 2.1e11);
  CHECK(problem.loading.control == fastnorm::Control::force);
  CHECK(problem.loading.normal_force == 1500);
  CHECK(problem.undeformed_distance(problem.grid.index(2, 1)) == -6e-6);
  REQUIRE(problem.result.has_value());
  CHECK(problem.result->contact_count == 3);
  CHECK(problem.result->iterations == 2);
  CHECK(problem.result->pressure(problem.grid.index(2, 1)) == 5e7);
}

TEST_CASE("Case writer and reader round-trip exactly", "[case]") {
  auto problem = read_text(valid_case);
  problem.undeformed_distance(0) = 1.0 / 3.0 * 1e-5;  // needs all 17 digits
  std::ostringstream out;
  fastnorm::write_case(out, problem);
  const auto again = read_text(out.str());
  CHECK(again.name == problem.name);
  CHECK(again.undeformed_distance == problem.undeformed_distance);
  CHECK(again.result->pressure == problem.result->pressure);
  CHECK(again.grid.dx() == problem.grid.dx());

  auto approach_case = read_text(edited("control force 1500", "control approach 2.5e-5"));
  approach_case.result.reset();
  std::ostringstream approach_out;
  fastnorm::write_case(approach_out, approach_case);
  const auto approach_again = read_text(approach_out.str());
  CHECK(approach_again.loading.control == fastnorm::Control::approach);
  CHECK(approach_again.stated_approach == 2.5e-5);
  CHECK_FALSE(approach_again.result.has_value());
}

TEST_CASE("A case's tangential line poses steady rolling and round-trips", "[case]") {
  const auto rolling = read_text(
      edited("control force 1500\n",
             "control force 1500\ntangential friction 0.3 xi 1e-3 eta -5e-4 phi 0.5 xc 1e-4 yc -2e-4 rolling -x\n"));
  REQUIRE(rolling.rolling.has_value());
  CHECK(rolling.rolling->friction == 0.3);
  CHECK(rolling.rolling->creepage.longitudinal == 1e-3);
  CHECK(rolling.rolling->creepage.lateral == -5e-4);
  CHECK(rolling.rolling->creepage.spin == 0.5);
  CHECK(rolling.rolling->creepage.spin_centre_x == 1e-4);
  CHECK(rolling.rolling->creepage.spin_centre_y == -2e-4);
  CHECK(rolling.rolling->direction == fastnorm::RollingDirection::negative_x);
  CHECK(rolling.undeformed_distance == read_text(valid_case).undeformed_distance);
  CHECK_FALSE(read_text(valid_case).rolling.has_value());

  auto changed = rolling;
  changed.rolling->creepage.lateral = 1.0 / 3.0 * 1e-3;  // needs all 17 digits
  changed.rolling->direction = fastnorm::RollingDirection::positive_x;
  std::ostringstream out;
  fastnorm::write_case(out, changed);
  const auto again = read_text(out.str());
  REQUIRE(again.rolling.has_value());
  CHECK(again.rolling->creepage.lateral == changed.rolling->creepage.lateral);
  CHECK(again.rolling->creepage.spin_centre_y == changed.rolling->creepage.spin_centre_y);
  CHECK(again.rolling->direction == fastnorm::RollingDirection::positive_x);

  // Line 9 is the tangential line: a friction that is not positive, an unknown direction,
  // keys out of order; and it must come before h.
  const auto with = [](const std::string& line) { return edited("control force 1500\n", "control force 1500\n" + line + "\n"); };
  CHECK(error_line(with("tangential friction 0 xi 0 eta 0 phi 0 xc 0 yc 0 rolling +x")) == 9);
  CHECK(error_line(with("tangential friction 0.3 xi 0 eta 0 phi 0 xc 0 yc 0 rolling +y")) == 9);
  CHECK(error_line(with("tangential friction 0.3 eta 0 xi 0 phi 0 xc 0 yc 0 rolling +x")) == 9);
  CHECK(error_line(with("tangential friction 0.3 xi nan eta 0 phi 0 xc 0 yc 0 rolling +x")) == 9);
  CHECK(error_line(with("rolling friction 0.3")) == 9);
  CHECK_THROWS_WITH(read_text(with("tangential friction 0.3 xi 0 eta 0 phi 0 xc 0 yc 0 rolling +y")),
                    Contains("rolling must be +x or -x"));
}

TEST_CASE("Case files are written whole and read back, and what the format cannot hold is refused", "[case]") {
  namespace fs = std::filesystem;
  const fs::path path = fs::temp_directory_path() / ("fastnorm_case_" + std::to_string(getpid()) + ".case");
  auto problem = read_text(valid_case);
  fastnorm::write_case_file(path.string(), problem);
  const auto again = fastnorm::read_case_file(path.string());
  fs::remove(path);
  CHECK(again.undeformed_distance == problem.undeformed_distance);
  CHECK(again.result->pressure == problem.result->pressure);

  CHECK_THROWS_WITH(fastnorm::write_case_file("/nonexistent/fastnorm.case", problem),
                    Contains("path: cannot open '/nonexistent/fastnorm.case'"));
  problem.material = fastnorm::Material<>(2.1e11, 0.3, 2.0e11, 0.3);
  CHECK_THROWS_WITH(fastnorm::write_case_file(path.string(), problem), Contains("material: a .case file holds one"));
  CHECK_FALSE(fs::exists(path));  // refused before the file is opened
}

TEST_CASE("Case reader rejects malformed files with the line number", "[case]") {
  // Line numbers of the valid case: 2 magic, 3 name, 4 source, 6 grid, 7 material,
  // 8 control, 9 h, 10–11 numbers, 12 result, 13 p, 14–15 numbers.
  CHECK(error_line(edited("fastnorm-case 1", "fastnorm-case 2")) == 2);
  CHECK(error_line(edited("source hand-written", "origin hand-written")) == 4);
  CHECK(error_line(edited("grid mx 3 my 2", "grid mx 3 ny 2")) == 6);
  CHECK(error_line(edited("dx 1e-4", "dx 0")) == 6);
  CHECK(error_line(edited("dy 2e-4", "dy -2e-4")) == 6);
  CHECK(error_line(edited("mx 3", "mx three")) == 6);
  CHECK(error_line(edited("material E 2.1e11", "material E -2.1e11")) == 7);
  CHECK(error_line(edited("control force 1500", "control torque 1500")) == 8);
  CHECK(error_line(edited("control force 1500", "control force 0")) == 8);
  CHECK(error_line(edited("-4e-6 5e-6 -6e-6", "-4e-6 5e-6")) == 12);          // fewer numbers
  CHECK(error_line(edited("-4e-6 5e-6 -6e-6", "-4e-6 5e-6 -6e-6 7e-6")) == 11);  // more numbers
  CHECK(error_line(edited("-4e-6 5e-6 -6e-6", "-4e-6 nan -6e-6")) == 11);
  CHECK(error_line(edited("-4e-6 5e-6 -6e-6", "-4e-6 inf -6e-6")) == 11);
  CHECK(error_line(edited("-4e-6 5e-6 -6e-6", "-4e-6 5e-6x -6e-6")) == 11);
  CHECK(error_line(edited("1e8 0 5e7", "1e8 0")) == 15);                       // p block short at EOF
  CHECK(error_line(edited(" fn 1500", " force 1500")) == 12);                  // result lacks fn
  CHECK(error_line(edited("p\n", "q\n")) == 13);
  CHECK(error_line("fastnorm-case 1\nname x\n") == 2);                          // truncated
  CHECK_THROWS_WITH(read_text(edited("dx 1e-4", "dx 0")), Contains("test.case:6"));
  CHECK_THROWS_AS(fastnorm::read_case_file("/nonexistent/x.case"), fastnorm::invalid_argument);
}

TEST_CASE("Case reader refuses sizes beyond memory and numbers that are not plain decimals", "[case]") {
  // Issue #15: a 30-byte edit to mx, my made std::bad_alloc escape; 1e400 was caught after
  // reading, without file:line; 0x10 was read as 16.
  CHECK(error_line(edited("grid mx 3 my 2", "grid mx 3000000000 my 3000000000")) == 6);
  CHECK_THROWS_WITH(read_text(edited("grid mx 3 my 2", "grid mx 3000000000 my 3000000000")),
                    Contains("test.case:6: grid mx x my") && Contains("more than this machine's memory"));
  CHECK(error_line(edited("control force 1500", "control force 1e400")) == 8);
  CHECK_THROWS_WITH(read_text(edited("control force 1500", "control force 1e400")), Contains("out of range"));
  CHECK(error_line(edited("-4e-6 5e-6 -6e-6", "-4e-6 1e400 -6e-6")) == 11);
  CHECK_THROWS_WITH(read_text(edited("control force 1500", "control force 0x10")),
                    Contains("test.case:8") && Contains("decimal numbers only"));
  CHECK(error_line(edited("-4e-6 5e-6 -6e-6", "-4e-6 0x5p-3 -6e-6")) == 11);
  CHECK(error_line(edited("-4e-6 5e-6 -6e-6", "-4e-6 infinity -6e-6")) == 11);
  CHECK(error_line(edited("-4e-6 5e-6 -6e-6", "-4e-6 1e -6e-6")) == 11);
  CHECK(error_line(edited("-4e-6 5e-6 -6e-6", "-4e-6 . -6e-6")) == 11);
  CHECK(error_line(edited("grid mx 3 my 2", "grid mx 99999999999999999999 my 2")) == 6);
  CHECK(error_line(edited("grid mx 3 my 2", "grid mx 3+ my 2")) == 6);
  // What the format writes still reads: signs, no leading digit, capital exponent.
  CHECK_NOTHROW(read_text(edited("-4e-6 5e-6 -6e-6", "-4E-6 +.5e-5 -6.0e-06")));
}
