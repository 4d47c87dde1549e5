// SPDX-License-Identifier: MIT
#include "analysis/plot.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>

#include <fmt/format.h>

namespace pastemix::analysis {

namespace {

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') out += "'\\''";
    else out.push_back(c);
  }
  return out + "'";
}

std::string env_or(const char* name, std::string fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::string(v) : fallback;
}

}  // namespace

PlotResult run_plot_script(const std::vector<std::string>& args) {
  const std::string python = env_or("PASTEMIX_PYTHON", "/usr/bin/python3");
  const std::string script =
      env_or("PASTEMIX_ANALYSIS_PLOT_SCRIPT", PASTEMIX_SOURCE_DIR "/scripts/plot_mixing_maps.py");
  if (!std::filesystem::exists(python))
    return {false, fmt::format("{} not found: no PNGs written (install python3 with matplotlib, numpy and h5py)", python)};
  std::string cmd = shell_quote(python) + " " + shell_quote(script);
  for (const auto& a : args) {
    cmd.push_back(' ');
    cmd += shell_quote(a);
  }
  FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
  if (!pipe) return {false, "cannot start the plotting script"};
  std::string output;
  std::array<char, 4096> buf{};
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) output.append(buf.data(), n);
  const int st = pclose(pipe);
  const int code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  if (code == 0) return {true, ""};
  while (!output.empty() && output.back() == '\n') output.pop_back();
  return {false, fmt::format("{} {} (exit {}): no PNGs written{}: {}", python, script, code,
                             code == 3 ? " (matplotlib, h5py or numpy missing)" : "", output)};
}

}  // namespace pastemix::analysis
