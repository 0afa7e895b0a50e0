# Build helpers for fastnorm's own tests, examples and tools. Warning flags (never put on the
# INTERFACE target: users choose their own). CI adds -DCMAKE_COMPILE_WARNING_AS_ERROR=ON.
function(fastnorm_add_warnings target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE
      -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wold-style-cast -Wdouble-promotion)
  endif()
endfunction()

# Counts the executable's calls of malloc and operator new(std::size_t) (mangled _Znwm on
# 64-bit Linux), and the bytes they hold until free and operator delete (_ZdlPv, _ZdlPvm),
# through the linker's --wrap: examples/support/allocation_counter.hpp.
function(fastnorm_count_allocations target)
  if(CMAKE_SYSTEM_NAME STREQUAL "Linux" AND CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang" AND CMAKE_SIZEOF_VOID_P EQUAL 8)
    target_link_options(${target} PRIVATE "LINKER:--wrap=malloc" "LINKER:--wrap=_Znwm" "LINKER:--wrap=free"
                        "LINKER:--wrap=_ZdlPv" "LINKER:--wrap=_ZdlPvm")
    target_compile_definitions(${target} PRIVATE FASTNORM_COUNT_MALLOC)
  endif()
endfunction()
