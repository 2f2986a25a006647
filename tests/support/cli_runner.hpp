// Runs the rbla program (RBLA_BINARY, set by tests/CMakeLists.txt) with a shell command line and
// captures what it prints, for the tests of the command-line interface.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace rbla::testing {

struct RunResult {
  int exit_code = -1;
  std::string output;  // standard output and standard error together
};

inline RunResult run_rbla(const std::string& arguments) {
  const std::string command = std::string(RBLA_BINARY) + " " + arguments + " 2>&1";
  RunResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace rbla::testing
