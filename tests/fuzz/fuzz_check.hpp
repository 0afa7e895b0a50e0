#pragma once
// What a fuzz target does when a property fails: say which and abort, so that libFuzzer
// keeps the input as a crash (docs/contributing.md, Fuzzing).

#include <cstdio>
#include <cstdlib>

namespace fastnorm::fuzz {

inline void require(bool holds, const char* property) {
  if (holds) return;
  std::fprintf(stderr, "fastnorm fuzz: property violated: %s\n", property);
  std::abort();
}

}  // namespace fastnorm::fuzz
