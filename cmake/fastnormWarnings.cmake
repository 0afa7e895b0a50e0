# Build helpers for fastnorm's own tests, examples and tools. Warning flags (never put on the
# INTERFACE target: users choose their own). CI adds -DCMAKE_COMPILE_WARNING_AS_ERROR=ON.
function(fastnorm_add_warnings target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE
      -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wold-style-cast -Wdouble-promotion)
  endif()
endfunction()

# Counts the executable's calls of malloc (through the linker's --wrap) and every call of the
# global operator new (replaced), and the bytes they hold until free and operator delete:
# examples/support/allocation_counter.hpp.
# Not under ThreadSanitizer, whose runtime defines operator new itself (the link would fail).
function(fastnorm_count_allocations target)
  if(CMAKE_SYSTEM_NAME STREQUAL "Linux" AND CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang" AND CMAKE_SIZEOF_VOID_P EQUAL 8
     AND NOT CMAKE_CXX_FLAGS MATCHES "-fsanitize=thread")
    target_link_options(${target} PRIVATE "LINKER:--wrap=malloc" "LINKER:--wrap=free")
    target_compile_definitions(${target} PRIVATE FASTNORM_COUNT_MALLOC)
  endif()
endfunction()
