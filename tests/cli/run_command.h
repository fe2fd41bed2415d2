#pragma once
// Runs the built coinroll binary with arguments, as a script would, capturing its output.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace coinroll::testing {

struct RunResult {
  int exitCode = -1;
  std::string output;  // stdout and stderr together
};

// `environment` is prefixed to the command line (e.g. "LP_NUM_THREADS=1" or "cd DIR &&").
inline RunResult runCoinroll(const std::string& arguments, const std::string& environment = "") {
  const std::string command = environment + " " + std::string(COINROLL_BINARY_DIR) + "/coinroll " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  RunResult result;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) result.output += buffer.data();
  const int status = pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace coinroll::testing
