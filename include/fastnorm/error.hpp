#pragma once
/// @file error.hpp
/// The two error channels of fastnorm (see CONTRIBUTING in README):
/// - `FASTNORM_CHECK` guards user input. It is always on and throws
///   `fastnorm::invalid_argument` with a message that names the argument.
/// - `FASTNORM_ASSERT` guards internal invariants and is compiled out under `NDEBUG`.

#include <cassert>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace fastnorm {

/// Thrown for bad input: non-positive sizes or moduli, NaN/Inf data, mismatched sizes.
class invalid_argument : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

namespace detail {

/// Builds "what (got value)" for error messages; full precision for floating values.
template <typename Value>
std::string describe(std::string_view what, const Value& value) {
  std::ostringstream out;
  out.precision(17);
  out << what << " (got " << value << ")";
  return out.str();
}

/// Throws fastnorm::invalid_argument("<what> must be positive (got <value>)") unless `value`
/// is finite and positive; `what` names the argument (and its unit). The names of the checks
/// are views, built into a string only when a check fails: a check that passes allocates
/// nothing (a time loop validates its options at every step).
template <typename Value>
void check_positive(const Value& value, std::string_view what) {
  if (!(std::isfinite(value) && value > 0)) {
    throw invalid_argument("fastnorm: " + describe(std::string(what) + " must be positive", value));
  }
}

/// A number as a person writes it in a message (six significant digits: "0.03", "1e-13").
template <typename Value>
std::string to_text(const Value& value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace detail

/// For code that checks its own input as fastnorm does (tools, bindings, a user's model):
/// `describe(what, value)` gives "what (got value)" with full precision, and
/// `check_positive(value, what)` throws fastnorm::invalid_argument unless the value is
/// finite and positive.
using detail::check_positive;
using detail::describe;

}  // namespace fastnorm

/// Throws fastnorm::invalid_argument("fastnorm: " + message) unless `condition` holds.
#define FASTNORM_CHECK(condition, message)                                         \
  do {                                                                             \
    if (!(condition)) throw ::fastnorm::invalid_argument("fastnorm: " + std::string(message)); \
  } while (false)

/// Internal invariant; compiled out under NDEBUG.
#define FASTNORM_ASSERT(condition) assert(condition)
