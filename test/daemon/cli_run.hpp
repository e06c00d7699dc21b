#pragma once
// Runs a command line from a test, as a user's shell would: what it printed and its exit code.
#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace rangefit::test {

struct CliRun {
  int exit_code = -1;
  std::string output;  // stdout (and stderr where the command line says 2>&1)
};

inline CliRun run_command(const std::string& command) {
  CliRun r;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return r;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, pipe)) > 0;) r.output.append(buf, n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

#ifdef RANGEFIT_CLI_PATH
// `rangefit ARGS`, stdout and stderr together.
inline CliRun run_cli(const std::string& args) {
  return run_command(std::string(RANGEFIT_CLI_PATH) + " " + args + " 2>&1");
}
#endif

}  // namespace rangefit::test
