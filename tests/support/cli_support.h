// Running the polyfloe program from a test: its exit code and everything it printed.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace polyfloe::tsupport {

struct CommandResult {
  int code = -1;       // exit code; -1 if it did not exit normally
  std::string output;  // stdout and stderr
};

// Runs `POLYFLOE_BINARY args` through the shell (args are shell words).
// `env` (e.g. "PATH=/nowhere") sets variables for the command alone.
inline CommandResult run_polyfloe(const std::string& args, const std::string& env = "") {
  const std::string cmd =
      (env.empty() ? std::string() : "env " + env + " ") + std::string(POLYFLOE_BINARY) + " " + args + " 2>&1";
  CommandResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  while (const std::size_t n = std::fread(buf, 1, sizeof buf, p)) r.output.append(buf, n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace polyfloe::tsupport
