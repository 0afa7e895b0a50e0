// Counts the heap allocations of an executable's own code, and the bytes they hold: the
// linker's --wrap sends its calls of malloc (Eigen's allocator) and of operator
// new(std::size_t) (the containers'; mangled _Znwm on 64-bit Linux), and of free and
// operator delete, here. Include from one source file of an executable that CMake's
// fastnorm_count_allocations(target) links with the wrap (it then defines
// FASTNORM_COUNT_MALLOC); elsewhere allocation_count() and the byte counts are -1.
// (Allocations made inside the shared libstdc++ are not seen.)
#pragma once

#include <atomic>
#include <cstddef>
#if defined(FASTNORM_COUNT_MALLOC)
#include <malloc.h>  // malloc_usable_size (glibc)
#endif

namespace fastnorm_example {

inline std::atomic<long>& allocation_counter() {
  static std::atomic<long> count{0};
  return count;
}

/// Heap bytes held by the executable's own allocations now, and the most held since the
/// last reset_peak_bytes(): the usable sizes of the blocks, as the allocator reports them.
struct HeapBytes {
  std::atomic<long> held{0}, peak{0};
};
inline HeapBytes& heap_bytes() {
  static HeapBytes bytes;
  return bytes;
}

/// A counter's value, or -1 in a build without the wrap.
inline long counted(const std::atomic<long>& counter) {
#if defined(FASTNORM_COUNT_MALLOC)
  return counter.load(std::memory_order_relaxed);
#else
  (void)counter;
  return -1;
#endif
}

/// Allocations so far.
inline long allocation_count() { return counted(allocation_counter()); }
inline long held_bytes() { return counted(heap_bytes().held); }
inline long peak_bytes() { return counted(heap_bytes().peak); }
inline void reset_peak_bytes() { heap_bytes().peak.store(heap_bytes().held.load()); }

}  // namespace fastnorm_example

#if defined(FASTNORM_COUNT_MALLOC)
namespace fastnorm_example {
inline void count_allocated(void* block) {
  allocation_counter().fetch_add(1, std::memory_order_relaxed);
  if (block == nullptr) return;
  HeapBytes& bytes = heap_bytes();
  const auto size = static_cast<long>(malloc_usable_size(block));
  const long held = bytes.held.fetch_add(size) + size;
  long peak = bytes.peak.load();
  while (held > peak && !bytes.peak.compare_exchange_weak(peak, held)) {
  }
}
inline void count_freed(void* block) {
  if (block != nullptr) heap_bytes().held.fetch_sub(static_cast<long>(malloc_usable_size(block)));
}
}  // namespace fastnorm_example

extern "C" void* __real_malloc(std::size_t size);  // NOLINT: the linker's names
extern "C" void* __wrap_malloc(std::size_t size) {
  void* block = __real_malloc(size);
  fastnorm_example::count_allocated(block);
  return block;
}
extern "C" void* __real__Znwm(std::size_t size);
extern "C" void* __wrap__Znwm(std::size_t size) {
  void* block = __real__Znwm(size);
  fastnorm_example::count_allocated(block);
  return block;
}
extern "C" void __real_free(void* block);
extern "C" void __wrap_free(void* block) {
  fastnorm_example::count_freed(block);
  __real_free(block);
}
extern "C" void __real__ZdlPv(void* block);
extern "C" void __wrap__ZdlPv(void* block) {
  fastnorm_example::count_freed(block);
  __real__ZdlPv(block);
}
extern "C" void __real__ZdlPvm(void* block, std::size_t size);
extern "C" void __wrap__ZdlPvm(void* block, std::size_t size) {
  fastnorm_example::count_freed(block);
  __real__ZdlPvm(block, size);
}
#endif
