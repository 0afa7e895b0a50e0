// Counts the heap allocations of an executable, and the bytes they hold: the linker's --wrap
// sends the executable's own calls of malloc and free (Eigen's allocator) here, and this file
// replaces the global operator new and delete, which every part of the program calls,
// libstdc++'s compiled code too (a std::string built inside the shared library, e.g. from a
// long literal, is counted; a wrap of operator new would not see it). Include from one source
// file of an executable that CMake's fastnorm_count_allocations(target) links with the wrap
// (it then defines FASTNORM_COUNT_MALLOC); elsewhere allocation_count() and the byte counts
// are -1. (Allocations by malloc inside shared libraries are still not seen.)
#pragma once

#include <atomic>
#include <cstddef>
#if defined(FASTNORM_COUNT_MALLOC)
#include <malloc.h>  // malloc_usable_size (glibc)
#include <new>
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
extern "C" void __real_free(void* block);
extern "C" void __wrap_free(void* block) {
  fastnorm_example::count_freed(block);
  __real_free(block);
}

// The replaceable global allocation functions ([new.delete]), on the unwrapped malloc and
// free so that a block is counted once. The array and aligned forms keep their standard
// definitions: the array forms call these, and the aligned ones pair among themselves.
void* operator new(std::size_t size) {
  void* block = __real_malloc(size == 0 ? 1 : size);
  if (block == nullptr) throw std::bad_alloc();
  fastnorm_example::count_allocated(block);
  return block;
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  void* block = __real_malloc(size == 0 ? 1 : size);
  if (block != nullptr) fastnorm_example::count_allocated(block);
  return block;
}
void operator delete(void* block) noexcept {
  fastnorm_example::count_freed(block);
  __real_free(block);
}
void operator delete(void* block, std::size_t /*size*/) noexcept { operator delete(block); }
void operator delete(void* block, const std::nothrow_t&) noexcept { operator delete(block); }
#endif
