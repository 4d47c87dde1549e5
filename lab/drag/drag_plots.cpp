// SPDX-License-Identifier: MIT
#include "lab/drag/drag_plots.h"

#include <unistd.h>

#include <cstdlib>
#include <fstream>

#include <fmt/format.h>

#include "base/drag_curves.h"

namespace pastemix::lab::drag {

namespace {

// argv: spheres.csv curves.csv chosen_column cd_png parity_png
constexpr const char* kScript = R"PY(# Drag-fit figures (written and run by `pastemix lab drag-fit`).
import csv, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

spheres_csv, curves_csv, chosen, cd_png, parity_png = sys.argv[1:6]
rows = list(csv.DictReader(open(spheres_csv)))
curves = list(csv.DictReader(open(curves_csv)))
re = [float(c["Re_prime"]) for c in curves]

fig, ax = plt.subplots(figsize=(7.5, 5.5))
for s in sorted({r["suspension"] for r in rows}, key=int):
    sel = [r for r in rows if r["suspension"] == s]
    ax.scatter([float(r["Re_prime"]) for r in sel], [float(r["Cd"]) for r in sel], s=18, label=f"suspension {s}")
ax.plot(re, [float(c["stokes"]) for c in curves], "k:", lw=1, label="Stokes 24/Re'")
ax.plot(re, [float(c["published_4_19"]) for c in curves], "k--", lw=1.2, label="published (4.19)")
ax.plot(re, [float(c[chosen]) for c in curves], "r-", lw=2, label=f"fit: {chosen}")
ax.set_xscale("log"); ax.set_yscale("log")
ax.set_xlim(0.1, 5e3); ax.set_ylim(0.2, 300)
ax.set_xlabel("Re' = rho_f v^2 / (tau_y + eta_B v / d)"); ax.set_ylabel("Cd (eq. 4.17)")
ax.set_title("Valentik & Whitmore (1965) spheres in Bingham clay suspensions")
ax.grid(True, which="both", alpha=0.3); ax.legend(fontsize=8)
fig.tight_layout(); fig.savefig(cd_png, format="png", dpi=130)

fig, ax = plt.subplots(figsize=(6.5, 6.5))
vm = [float(r["v_measured_m_s"]) for r in rows]
def col(name):
    return [float(r[name]) if r[name] else None for r in rows]
series = [("v_published_m_s", "(a) published 4.19", "s", "tab:gray"),
          ("v_fit_loso_m_s", "(c) fit, held out (LOSO)", "o", "tab:red"),
          ("v_thesis_model_m_s", "(d) thesis model (A.1)", "^", "tab:blue")]
for name, label, marker, color in series:
    pts = [(m, p) for m, p in zip(vm, col(name)) if p is not None]
    ax.scatter([m for m, _ in pts], [p for _, p in pts], s=20, marker=marker, color=color, alpha=0.75,
               label=label, facecolors="none" if marker != "o" else color)
top = 3.2
ax.plot([0, top], [0, top], "k-", lw=1, label="1:1")
ax.plot([0, top], [0, 1.2 * top], "k--", lw=0.8, label="+-20 %")
ax.plot([0, top], [0, 0.8 * top], "k--", lw=0.8)
ax.set_xlim(0, top); ax.set_ylim(0, top)
ax.set_xlabel("measured terminal velocity (m/s)"); ax.set_ylabel("predicted terminal velocity (m/s)")
ax.set_title("Terminal velocity: predicted vs measured"); ax.grid(True, alpha=0.3); ax.legend(fontsize=8)
fig.tight_layout(); fig.savefig(parity_png, format="png", dpi=130)
)PY";

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char ch : s) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return out + "'";
}

}  // namespace

std::string make_drag_plots(StagedOutput& out, const DragFitResult& r, const std::filesystem::path& spheres_csv,
                            const std::filesystem::path& curves_csv, const std::filesystem::path& out_dir) {
  const std::string python = "/usr/bin/python3";
  if (::access(python.c_str(), X_OK) != 0) return "no /usr/bin/python3: plots skipped";
  // Draw into a private folder first; only complete PNGs are moved into the staged set.
  const auto work = out_dir / fmt::format(".drag-plots-{}", static_cast<long>(::getpid()));
  std::filesystem::create_directories(work);
  const auto script = work / "drag_plots.py", cd_png = work / "cd_re.png", parity_png = work / "velocity_parity.png";
  {
    std::ofstream f(script);
    f << kScript;
  }
  const std::string cmd = fmt::format("{} {} {} {} {} {} {} > {} 2>&1", python, shell_quote(script.string()),
                                      shell_quote(spheres_csv.string()), shell_quote(curves_csv.string()),
                                      shell_quote(r.best().name()), shell_quote(cd_png.string()),
                                      shell_quote(parity_png.string()), shell_quote((work / "log.txt").string()));
  const int rc = std::system(cmd.c_str());
  std::string message;
  if (rc != 0 || !std::filesystem::exists(cd_png) || !std::filesystem::exists(parity_png)) {
    std::ifstream log(work / "log.txt");
    std::string tail((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
    if (tail.size() > 400) tail = tail.substr(tail.size() - 400);
    message = fmt::format("plot script failed (exit {}): {}", rc, tail);
  } else {
    std::filesystem::rename(cd_png, out.path(out_dir / "cd_re.png"));
    std::filesystem::rename(parity_png, out.path(out_dir / "velocity_parity.png"));
    std::filesystem::rename(script, out.path(out_dir / "drag_plots.py"));
  }
  std::error_code ec;
  std::filesystem::remove_all(work, ec);
  return message;
}

}  // namespace pastemix::lab::drag
