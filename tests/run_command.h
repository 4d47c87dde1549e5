// SPDX-License-Identifier: MIT
// Runs the built `pastemix` command in a test and captures its exit code and output (stdout + stderr).
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace pastemix::test {

struct CommandResult {
  int exit_code = -1;
  std::string output;
};

// `args` is appended to the binary path as shell words (quote them yourself if needed); `prefix` goes
// before it (environment variables, `ulimit ...;`), run by sh.
inline CommandResult run_pastemix(const std::string& args, const std::string& prefix = "") {
  std::string cmd = prefix + " '" + PASTEMIX_BINARY + "' " + args + " 2>&1";
  CommandResult r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
  int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline std::string source_path(const std::string& rel) { return std::string(PASTEMIX_SOURCE_DIR) + "/" + rel; }

}  // namespace pastemix::test
