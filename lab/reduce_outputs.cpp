// SPDX-License-Identifier: MIT
#include "lab/reduce_outputs.h"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>

#include <fmt/format.h>

#include "base/staged_output.h"
#include "lab/lab_h5.h"
#include "lab/parameters_toml.h"

namespace pastemix::lab {

namespace {

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') out += "'\\''";
    else out += c;
  }
  return out + "'";
}

struct Exec {
  int status = -1;
  std::string output;
};

Exec run_capture(const std::string& cmd) {
  Exec r;
  FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
  const int st = pclose(pipe);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

std::string env_or(const char* name, std::string fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::string(v) : fallback;
}

// Runs the plotting script once on the staged lab.h5 and stages the PNGs it made. Returns warnings.
std::vector<Warning> stage_plots(StagedOutput& staged, const ReduceResult& r, const std::filesystem::path& h5,
                                 const std::filesystem::path& out_dir) {
  namespace fs = std::filesystem;
  std::vector<Warning> warnings;
  const std::string python = env_or("PASTEMIX_PYTHON", "/usr/bin/python3");
#ifdef PASTEMIX_SOURCE_DIR
  const std::string script = env_or("PASTEMIX_PLOT_SCRIPT", PASTEMIX_SOURCE_DIR "/scripts/plot_lab_grids.py");
#else
  const std::string script = env_or("PASTEMIX_PLOT_SCRIPT", "scripts/plot_lab_grids.py");
#endif
  if (!fs::exists(python)) {
    warnings.push_back({python, "not found: no PNG maps written (install python3 with matplotlib and h5py, see "
                                "scripts/install-deps.sh); parameters.toml and lab.h5 are complete"});
    return warnings;
  }
  const fs::path tmp = out_dir / fmt::format(".plots.partial-{}", static_cast<long>(::getpid()));
  fs::create_directories(tmp);
  const Exec e = run_capture(fmt::format("{} {} {} {}", shell_quote(python), shell_quote(script),
                                         shell_quote(h5.string()), shell_quote(tmp.string())));
  // What the helper prints (a traceback, matplotlib's chatter) goes to its own log beside the outputs,
  // never into a data file; the warning names the log and quotes its last line only.
  staged.write_text(out_dir / "plot_lab_grids.log", e.output.empty() ? "(the helper printed nothing)\n" : e.output);
  if (e.status != 0) {
    std::string last = e.output;
    while (!last.empty() && (last.back() == '\n' || last.back() == '\r')) last.pop_back();
    if (const auto nl = last.rfind('\n'); nl != std::string::npos) last = last.substr(nl + 1);
    if (last.size() > 200) last = last.substr(0, 200) + "...";
    warnings.push_back({script, fmt::format("{} (exit {}): no PNG maps written{}: {}{}", python, e.status,
                                            e.status == 3 ? " (matplotlib, h5py or numpy missing)" : "",
                                            last.empty() ? "no output" : last,
                                            e.output.empty() ? "" : " (full output in plot_lab_grids.log)")});
  } else {
    for (const auto& g : r.block_cut->cases) {
      const std::string name = fmt::format("mixing_case_{}.png", g.case_id);
      if (!fs::exists(tmp / name)) {
        warnings.push_back({script, fmt::format("did not write {}", name)});
        continue;
      }
      fs::rename(tmp / name, staged.path(out_dir / name));
    }
  }
  std::error_code ec;
  fs::remove_all(tmp, ec);
  return warnings;
}

}  // namespace

ReduceOutputs write_reduce_outputs(const ReduceResult& r, const std::filesystem::path& out_dir, RunInfo info) {
  ReduceOutputs out;
  StagedOutput staged;
  const auto h5 = staged.path(out_dir / "lab.h5");
  write_lab_h5(h5, r, info);
  if (r.block_cut) out.warnings = stage_plots(staged, r, h5, out_dir);
  ReduceResult with_output_warnings = r;
  for (const auto& w : out.warnings) with_output_warnings.warnings.push_back(w);
  staged.write_text(out_dir / "parameters.toml", parameters_toml(with_output_warnings, info));
  staged.commit();
  out.written = staged.final_paths();
  return out;
}

}  // namespace pastemix::lab
