# Warning flags for fastnorm's own tests, examples and tools (never put on the
# INTERFACE target: users choose their own). CI adds -DCMAKE_COMPILE_WARNING_AS_ERROR=ON.
function(fastnorm_add_warnings target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE
      -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wold-style-cast -Wdouble-promotion)
  endif()
endfunction()
