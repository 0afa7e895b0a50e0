// The four tools share one command line (examples/support/arguments.hpp): --help with
// defaults, typed options with ranges, and one way of failing (status 2, the option named,
// the limits in the units the user typed).
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "support/run_command.hpp"

using Catch::Matchers::Contains;

namespace {

struct Tool {
  const char* name;
  const char* executable;
};

const Tool tools[] = {{"fastnorm-solve", FASTNORM_SOLVE_EXE},
                      {"fastnorm-wheelrail", FASTNORM_WHEELRAIL_EXE},
                      {"fastnorm-bench", FASTNORM_BENCH_EXE},
                      {"wheelrail_study", FASTNORM_STUDY_EXE}};

}  // namespace

TEST_CASE("every tool answers --help with its options and defaults", "[cli]") {
  for (const auto& tool : tools) {
    INFO(tool.name);
    const auto run = fastnorm::test::run_command(tool.executable, "--help");
    CHECK(run.status == 0);
    CHECK_THAT(run.output, Contains(std::string("usage: ") + tool.name));
    CHECK_THAT(run.output, Contains("(default "));
    CHECK_THAT(run.output, Contains("--help"));
  }
  const auto wheelrail = fastnorm::test::run_command(FASTNORM_WHEELRAIL_EXE, "--help");
  CHECK_THAT(wheelrail.output, Contains("--y MM"));
  CHECK_THAT(wheelrail.output, Contains("in (-30, 30) (default 0)"));
}

TEST_CASE("every tool refuses a bad value by name, with status 2", "[cli]") {
  struct Bad {
    const char* executable;
    std::string arguments, message;
  };
  const std::vector<Bad> cases{
      {FASTNORM_WHEELRAIL_EXE, "--y nan", "--y needs a number, not 'nan'"},
      {FASTNORM_WHEELRAIL_EXE, "--y 3mm", "--y needs a number, not '3mm'"},
      {FASTNORM_WHEELRAIL_EXE, "--y 40", "--y must be in (-30, 30), not 40"},  // mm, as typed
      {FASTNORM_WHEELRAIL_EXE, "--yaw 10", "--yaw must be in (-5.72958, 5.72958), not 10"},  // degrees
      {FASTNORM_WHEELRAIL_EXE, "--elements 2.5", "--elements needs a whole number"},
      {FASTNORM_WHEELRAIL_EXE, "--wheel middle --fz 1e5", "--wheel must be left|right, not 'middle'"},
      {FASTNORM_WHEELRAIL_EXE, "surplus", "unexpected argument 'surplus'"},
      {FASTNORM_BENCH_EXE, "--repeats 0", "--repeats must be >= 1, not 0"},
      {FASTNORM_BENCH_EXE, "--growth --sizes 12,x", "--sizes needs a number, not 'x'"},
      {FASTNORM_BENCH_EXE, "--solvers magic", "unknown solver 'magic'"},
      {FASTNORM_STUDY_EXE, "--elements 3", "--elements must be in [4, 2000], not 3"},
      {FASTNORM_STUDY_EXE, "--out", "option --out needs a value"},
  };
  for (const auto& c : cases) {
    const auto run = fastnorm::test::run_command(c.executable, c.arguments);
    INFO(c.arguments << "\n" << run.output);
    CHECK(run.status == 2);
    CHECK_THAT(run.output, Contains(c.message));
  }
}
