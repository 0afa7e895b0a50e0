#pragma once
/// @file detail/memory_check.hpp
/// Sizes checked against what the machine can hold before they are allocated: a grid of
/// 3·10⁹ × 3·10⁹ elements is a clear error naming the field, not std::bad_alloc.

#include <cstddef>
#include <limits>
#include <string>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#endif

#include "fastnorm/error.hpp"

namespace fastnorm {
namespace detail {

/// The machine's physical memory (bytes); the largest double where the system does not say.
inline double physical_memory() {
#if defined(_SC_PHYS_PAGES) && defined(_SC_PAGESIZE)
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  if (pages > 0 && page > 0) return static_cast<double>(pages) * static_cast<double>(page);
#endif
  return std::numeric_limits<double>::max();
}

/// @throws fastnorm::invalid_argument "<what>: <count> values need <bytes> bytes, more than
///         this machine's memory" when count · bytes_each exceeds it (`count` as a double:
///         a product of sizes may overflow any integer type)
inline void check_memory(double count, double bytes_each, const std::string& what) {
  const double bytes = count * bytes_each, memory = physical_memory();
  FASTNORM_CHECK(bytes <= memory, what + ": " + to_text(count) + " values need " + to_text(bytes) +
                                      " bytes, more than this machine's memory (" + to_text(memory) + " bytes)");
}

}  // namespace detail
}  // namespace fastnorm
