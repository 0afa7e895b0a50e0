// libFuzzer target: the .case reader (case_file.hpp) on arbitrary bytes.
// Properties: the reader either throws fastnorm::invalid_argument or returns a whole,
// finite case; a case read is written and read again unchanged (write_case keeps full
// precision); reading as float refuses what float cannot hold instead of making it inf.

#include <fastnorm/case_file.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <sstream>
#include <string>

#include "fuzz_check.hpp"

namespace {

using fastnorm::fuzz::require;

template <typename Scalar>
bool whole_and_finite(const fastnorm::Case<Scalar>& problem) {
  if (problem.undeformed_distance.size() != problem.grid.size() || !problem.undeformed_distance.allFinite()) {
    return false;
  }
  if (!problem.result) return true;
  return problem.result->pressure.size() == problem.grid.size() && problem.result->pressure.allFinite();
}

template <typename Scalar>
void read_and_check(const std::string& text) {
  std::istringstream in(text);
  std::optional<fastnorm::Case<Scalar>> read;
  try {
    read.emplace(fastnorm::read_case<Scalar>(in, "fuzz"));
  } catch (const fastnorm::invalid_argument&) {
    return;  // refused with a message: the expected outcome for most inputs
  }
  const auto& problem = *read;
  require(whole_and_finite(problem), "a case read is whole and finite");
  std::ostringstream out;
  fastnorm::write_case(out, problem);
  std::istringstream written(out.str());
  const auto reread = fastnorm::read_case<Scalar>(written, "rewritten");  // throws: a finding
  require(reread.grid.mx() == problem.grid.mx() && reread.grid.my() == problem.grid.my() &&
              reread.grid.dx() == problem.grid.dx() && reread.grid.dy() == problem.grid.dy() &&
              reread.grid.x0() == problem.grid.x0() && reread.grid.y0() == problem.grid.y0(),
          "the grid survives write and read");
  require(reread.loading.control == problem.loading.control &&
              reread.loading.normal_force == problem.loading.normal_force &&
              reread.stated_approach == problem.stated_approach,
          "the control survives write and read");
  require(reread.undeformed_distance == problem.undeformed_distance, "h survives write and read");
  require(reread.result.has_value() == problem.result.has_value() &&
              (!problem.result || reread.result->pressure == problem.result->pressure),
          "the stored result survives write and read");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  read_and_check<double>(text);
  read_and_check<float>(text);
  return 0;
}
