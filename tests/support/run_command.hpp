// Running a command-line tool as a user does, and reading its `name=value` fields.
#pragma once

#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <string>

namespace fastnorm::test {

struct Outcome {
  int status;
  std::string output;  // stdout and stderr
};

inline Outcome run_command(const std::string& executable, const std::string& arguments) {
  const std::string command = executable + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::string output;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int raw = pclose(pipe);
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, output};
}

// The value of `name=value` where name starts a word of the output.
inline double field(const std::string& output, const std::string& name) {
  const std::string key = name + "=";
  for (auto at = output.find(key); at != std::string::npos; at = output.find(key, at + 1)) {
    if (at == 0 || output[at - 1] == ' ' || output[at - 1] == '\n') {
      return std::stod(output.substr(at + key.size()));
    }
  }
  FAIL("no field '" << name << "' in the output");
  return 0;
}

}  // namespace fastnorm::test
