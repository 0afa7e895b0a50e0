// Counts the heap allocations of an executable's own code: the linker's --wrap sends its
// calls of malloc (Eigen's allocator) and of operator new(std::size_t) (the containers';
// mangled _Znwm on 64-bit Linux) here. Include from one source file of an executable that
// CMake's fastnorm_count_allocations(target) links with the wrap (it then defines
// FASTNORM_COUNT_MALLOC); elsewhere allocation_count() is -1. (Allocations made inside the
// shared libstdc++ are not seen.)
#pragma once

#include <atomic>
#include <cstddef>

namespace fastnorm_example {

inline std::atomic<long>& allocation_counter() {
  static std::atomic<long> count{0};
  return count;
}

/// Allocations so far, or -1 in a build without the wrap.
inline long allocation_count() {
#if defined(FASTNORM_COUNT_MALLOC)
  return allocation_counter().load(std::memory_order_relaxed);
#else
  return -1;
#endif
}

}  // namespace fastnorm_example

#if defined(FASTNORM_COUNT_MALLOC)
extern "C" void* __real_malloc(std::size_t size);  // NOLINT: the linker's names
extern "C" void* __wrap_malloc(std::size_t size) {
  fastnorm_example::allocation_counter().fetch_add(1, std::memory_order_relaxed);
  return __real_malloc(size);
}
extern "C" void* __real__Znwm(std::size_t size);
extern "C" void* __wrap__Znwm(std::size_t size) {
  fastnorm_example::allocation_counter().fetch_add(1, std::memory_order_relaxed);
  return __real__Znwm(size);
}
#endif
