// SPDX-License-Identifier: MIT
// `pastemix validate ball-pour`: the thesis's multi-ball test (68 balls of 12.6 mm poured from the funnel,
// 15 cm fall into the paste; validation/fluid/ball_pour.h), over seeded runs: per-seed Z range, balls suspended,
// balls left in the funnel, and the presence-probability maps (PNG, scripts/plot_ball_pour.py).
#include <sys/wait.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "app/fluid_paste.h"
#include "base/error.h"
#include "base/staged_output.h"
#include "validation/fluid/ball_pour.h"

namespace pastemix::app {

namespace {

std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Runs the plotting script on the (staged) CSV; returns "" or why no PNG was written.
std::string plot(const std::filesystem::path& csv, const std::filesystem::path& maps,
                 const std::filesystem::path& hist) {
  const char* py = std::getenv("PASTEMIX_PYTHON");
  const std::string python = py && *py ? py : "/usr/bin/python3";
  const std::string script = PASTEMIX_SOURCE_DIR "/scripts/plot_ball_pour.py";
  if (!std::filesystem::exists(python)) return python + " not found";
  const std::string cmd = fmt::format("{} {} {} {} {} 2>&1", quote(python), quote(script), quote(csv.string()),
                                      quote(maps.string()), quote(hist.string()));
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return "popen failed";
  std::string out;
  std::array<char, 4096> buf{};
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) out.append(buf.data(), n);
  const int st = pclose(pipe);
  if (!(WIFEXITED(st) && WEXITSTATUS(st) == 0)) return fmt::format("{} failed: {}", script, out);
  return "";
}

struct PourOpts {
  int seeds = 15;
  int first_seed = 1;  // seeds first_seed .. first_seed + seeds - 1: a long study split over runs or machines
  double flow_cell = 0.0;  // m; > 0: the paste with dynamics = "flow" at this cell
  validation::PourFlow flow;
  std::string out = "out/fluid/ball_pour";
  validation::FunnelPour pour;
  PasteOpts paste;
};

// The set-up line and the lab's result, then the table's header.
void print_pour_header(const validation::FunnelPour& p, const Paste& paste) {
  const double tr = validation::rayleigh_time(p);
  fmt::print("{} balls of {} mm ({} kg/m3) in the funnel ({} cm top, {} cm exit, {} cm cone + {} cm tube) on a plate "
             "removed at {} s; fall {} cm to the paste (frame {} x {} cm, paste {} cm); steel e {:.4g}, mu {:.4g} "
             "({}); dt {:.3g} s = {} x Rayleigh time {:.3g} s\nlab: all balls suspended, Z = 8.5-13.5 cm (Z: ball "
             "centre above the frame bottom)\n",
             p.balls, 1e3 * p.ball_d, p.rho_ball, 100 * p.top_d, 100 * p.exit_d, 100 * p.cone_h, 100 * p.tube,
             p.release, 100 * p.fall, 100 * p.box_x, 100 * p.box_y, 100 * p.paste_depth, p.restitution, p.friction,
             paste.ball_from, p.dt_rayleigh * tr, p.dt_rayleigh, tr);
  if (p.flow) {
    const auto n = validation::pour_flow_cells(p, *p.flow);
    fmt::print("paste: dynamics = \"flow\", {} x {} x {} cells of {:.2f} x {:.2f} x {:.2f} mm up to {} cm of air above "
               "the rim, kernel width {}, coupling interval {} steps, m = {} s{}; at rest: |v| < {} m/s for {} s\n",
               n[0], n[1], n[2], 1e3 * p.box_x / n[0], 1e3 * p.box_y / n[1], 1e3 * (p.paste_depth + p.flow->air) / n[2],
               100 * p.flow->air, p.flow->kernel_width, p.flow->coupling_interval, p.flow->regularisation,
               p.flow->implicit_stick ? ", implicit stick" : "", p.flow->rest_speed, p.flow->rest_time);
  } else {
    fmt::print("paste: at rest (the at-rest field), at rest: v = 0\n");
  }
  fmt::print("{:>5} {:>9} {:>9} {:>10} {:>9} {:>9} {:>9} {:>8} {:>7} {:>7} {:>7}\n", "seed", "Z min cm", "Z max cm",
             "suspended", "in funnel", "1st out s", "last out", "t end s", "ids", "wall s", "cpu s");
}

// What the seeds add up to (Z in m), and the CSV rows of every ball.
struct PourTally {
  double lo = 1e300, hi = -1e300;
  long total = 0, suspended = 0, in_band = 0, stuck = 0, floor = 0;
  bool ids_ok = true;
  std::string rows = "seed,ball,x_m,y_m,z_m,in_funnel,below_surface\n";
};

// Seed k's run: its balls into the tally and the CSV, and its table row.
void pour_seed(const validation::FunnelPour& p, int k, PourTally& t) {
  // Wall time, and the process's CPU time (one thread: what the run costs on an idle core; the wall time
  // on a shared machine also counts the time other processes held the core).
  const auto t1 = std::chrono::steady_clock::now();
  const std::clock_t c1 = std::clock();
  const auto b = validation::ball_pour(p, static_cast<std::uint64_t>(k));
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  const double cpu = static_cast<double>(std::clock() - c1) / CLOCKS_PER_SEC;
  const double top = p.paste_depth + p.fall;
  for (std::size_t a = 0; a < b.z.size(); ++a) {
    const bool funnel = b.z[a] + 0.5 * p.ball_d > top;
    t.rows += fmt::format("{},{},{:.6f},{:.6f},{:.6f},{},{}\n", k, b.id[a], b.x[a], b.y[a], b.z[a], int(funnel),
                          int(!funnel && b.z[a] < p.paste_depth));
    t.in_band += !funnel && b.z[a] >= 0.085 && b.z[a] <= 0.135;
  }
  t.total += static_cast<long>(b.z.size());
  t.suspended += b.at_rest, t.stuck += b.in_funnel, t.floor += b.on_floor, t.ids_ok = t.ids_ok && b.ids_ok;
  if (b.in_funnel < p.balls) t.lo = std::min(t.lo, b.z_min), t.hi = std::max(t.hi, b.z_max);
  fmt::print("{:>5} {:>9.2f} {:>9.2f} {:>10} {:>9} {:>9.3f} {:>9.3f} {:>8.3f} {:>7} {:>7.1f} {:>7.1f}\n", k, 100 * b.z_min,
             100 * b.z_max, b.at_rest, b.in_funnel, b.first_out, b.last_out, b.t_end, b.ids_ok ? "ok" : "LOST",
             wall, cpu);
  if (p.flow)
    fmt::print("      flow: {} cycles, {} steps, {} pressure and {} viscous iterations, {:.1f} s in the flow solver; "
               "surface {:.2f} mm; fastest ball {:.3g} m/s\n",
               b.flow_cycles, b.flow_steps, b.pressure_iterations, b.viscous_iterations, b.flow_seconds,
               1e3 * b.surface, b.max_speed);
  std::fflush(stdout);
}

// ball_pour.csv and, if the plotting script succeeds, its two PNGs, all or none (StagedOutput).
void write_pour_outputs(const std::string& out, const std::string& rows) {
  namespace fs = std::filesystem;
  const fs::path dir = out;
  fs::create_directories(dir);
  StagedOutput staged;
  const fs::path csv = staged.path(dir / "ball_pour.csv");
  {
    std::FILE* f = std::fopen(csv.c_str(), "w");
    if (!f || std::fputs(rows.c_str(), f) < 0 || std::fclose(f) != 0)
      throw RuntimeFailure(fmt::format("cannot write {}", csv.string()));
  }
  // The PNGs are drawn under temporary names and staged only if the script succeeded.
  const fs::path tmaps = dir / ".ball_pour_maps.tmp.png", thist = dir / ".ball_pour_z.tmp.png";
  const std::string why = plot(csv, tmaps, thist);
  if (why.empty()) {
    fs::rename(tmaps, staged.path(dir / "ball_pour_maps.png"));
    fs::rename(thist, staged.path(dir / "ball_pour_z.png"));
  } else {
    std::error_code ec;
    fs::remove(tmaps, ec), fs::remove(thist, ec);
  }
  staged.commit();
  fmt::print("wrote {}\n", (dir / "ball_pour.csv").string());
  if (why.empty())
    fmt::print("wrote {} and {}\n", (dir / "ball_pour_maps.png").string(), (dir / "ball_pour_z.png").string());
  else
    fmt::print(stderr, "warning: no PNG maps written: {}\n", why);
}

void run_pour(const PourOpts& o) {
  if (o.seeds < 1) throw InputError("--seeds", 0, "seeds", "must be at least 1");
  if (o.first_seed < 1) throw InputError("--first-seed", 0, "first-seed", "must be at least 1");
  if (!(o.pour.dt_rayleigh > 0.0)) throw InputError("--dt-rayleigh", 0, "dt-rayleigh", "must be positive");
  const Paste paste = resolve_paste(o.paste);
  validation::FunnelPour p = o.pour;
  p.tau_y = paste.tau_y, p.rho_paste = paste.rho, p.eta_B = paste.eta, p.curve = paste.curve;
  p.restitution = paste.ball_restitution, p.friction = paste.ball_friction;
  if (o.flow_cell > 0.0) {
    p.flow = o.flow;
    p.flow->cell = o.flow_cell;
  }
  print_paste(paste);
  print_pour_header(p, paste);
  PourTally t;
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  for (int k = o.first_seed; k < o.first_seed + o.seeds; ++k) pour_seed(p, k, t);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  const double n = static_cast<double>(t.total);
  fmt::print("all {} seeds: Z = {:.2f}-{:.2f} cm (lab 8.5-13.5); suspended at rest {}/{} ({:.1f} %); inside "
             "8.5-13.5 cm {}/{} ({:.1f} %); on the floor {}; left in the funnel {}; ids {}; {:.1f} s wall, {:.1f} s CPU ({:.1f} s CPU per seed)\n",
             o.seeds, 100 * t.lo, 100 * t.hi, t.suspended, t.total, 100.0 * static_cast<double>(t.suspended) / n,
             t.in_band, t.total, 100.0 * static_cast<double>(t.in_band) / n, t.floor, t.stuck,
             t.ids_ok ? "conserved" : "NOT conserved", wall, cpu, cpu / o.seeds);
  write_pour_outputs(o.out, t.rows);
}

}  // namespace

void register_pour(CLI::App* val) {
  auto o = std::make_shared<PourOpts>();
  CLI::App* cmd = val->add_subcommand(
      "ball-pour", "68 balls of 12.6 mm poured from the funnel, 15 cm fall into the paste: Z range and maps");
  cmd->add_option("--seeds", o->seeds, "seeded runs 1..N (default 15, as the thesis)");
  cmd->add_option("--first-seed", o->first_seed,
                  "the first seed (default 1): --first-seed 4 --seeds 3 runs seeds 4-6, so that a study's seeds can be "
                  "split over runs (each seed is the same run whichever command runs it)");
  cmd->add_option("--balls", o->pour.balls, "balls (default 68)");
  cmd->add_option("--dt-rayleigh", o->pour.dt_rayleigh, "time step as a fraction of the Rayleigh time (default 0.5)");
  cmd->add_option("--end", o->pour.end_time, "simulated time limit (s), default 3 (runs stop when all balls rest)");
  cmd->add_option("--release", o->pour.release, "time the plate under the funnel is removed (s), default 0.25");
  cmd->add_option("--fall", o->pour.fall, "exit-tube bottom to paste surface (m), default 0.15");
  cmd->add_option("--exit-diameter", o->pour.exit_d, "funnel exit diameter (m), default 0.04");
  cmd->add_option("--out", o->out, "folder for ball_pour.csv, ball_pour_maps.png, ball_pour_z.png");
  cmd->add_option("--flow", o->flow_cell, "the paste with dynamics = \"flow\" at this cell size (m), e.g. 0.01")
      ->check(CLI::PositiveNumber);
  add_flow_options(cmd, o->flow.coupling_interval, o->flow.regularisation);
  cmd->add_flag("--implicit-stick", o->flow.implicit_stick, "with --flow: a yield-held ball moves with the paste in the flow step");
  add_paste_options(cmd, o->paste);
  cmd->callback([o] { run_pour(*o); });
}

}  // namespace pastemix::app
