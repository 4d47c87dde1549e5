#!/usr/bin/python3
"""Parse the benchmark logs of one harness run and print the ratio table.

Logs are named <code>_<scene>_t<threads>_r<repeat>.log in WORK (code: liggghts or pastemix).
For each (code, scene, threads) the best (shortest) loop time over the repeats is kept: on a shared,
noisy machine other processes can only add time, so the minimum is the best estimate of the cost.
particle-steps/s = particles x steps / loop time, where loop time is the wall-clock of the time-step
loop only (LIGGGHTS: its "Loop time" line; pastemix: its own loop timer), setup and I/O excluded.
Usage: report.py WORK CSV_OUT
"""
import csv
import glob
import os
import re
import socket
import sys
import time

LIGGGHTS_LOOP = re.compile(
    r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms")
LIGGGHTS_STAGE = re.compile(r"^(Pair|Neigh|Comm|Outpt|Modfy|Other) +time \(%\) = ([0-9.eE+-]+) \(([0-9.eE+-]+)\)")
LIGGGHTS_BUILDS = re.compile(r"Neighbor list builds = (\d+)")
LOGNAME = re.compile(r"(liggghts|pastemix|baseline)_(\w+?)_t(\d+)_r(\d+)\.log$")


def parse_liggghts(text):
    """Returns dict(loop_s, steps, particles, stages{name: seconds}, line) for the last run in the log."""
    loops = list(LIGGGHTS_LOOP.finditer(text))
    if not loops:
        return None
    m = loops[-1]
    stages = {}
    for line in text[m.end():].splitlines():
        s = LIGGGHTS_STAGE.match(line)
        if s:
            stages[s.group(1)] = float(s.group(2))
        elif line.startswith("Nlocal"):
            break
    b = LIGGGHTS_BUILDS.search(text, m.end())
    return dict(loop_s=float(m.group(1)), steps=int(m.group(3)), particles=int(m.group(4)),
                stages=stages, line=m.group(0), rebuilds=int(b.group(1)) if b else None,
                final=liggghts_final_state(text[:m.start()]))


def liggghts_final_state(text):
    """The last thermo row before the loop-time line: (KE, rotational KE, z_com, pair contacts)."""
    rows = [l.split() for l in text.splitlines()]
    head = max((k for k, r in enumerate(rows) if r[:2] == ["Step", "Atoms"]), default=None)
    if head is None:
        return None
    data = [r for r in rows[head + 1:] if len(r) == 6 and r[0].isdigit()]
    if not data:
        return None
    _, _, ke, rke, zcom, npair = data[-1]
    return dict(ke=float(ke), rke=float(rke), zcom=float(zcom), npair=int(float(npair)))


# pastemix prints at the end of `pastemix run` (model/run.cpp, format_profile):
#   stage profile (2000 steps, 12960 particles, 95 neighbour rebuilds):
#     neighbor            0.412 s   12.3 %
#     ...
#     output              0.020 s    0.6 %
#     total wall          3.350 s  (597 steps/s, 7.74e+06 particle-steps/s)
# "total wall" covers the whole step loop including the HDF5 snapshots at t = 0 and at the end; the loop
# time used here is total wall minus the output stage (LIGGGHTS writes no snapshots in its loop).
PASTEMIX_HEAD = re.compile(r"stage profile \((\d+) steps, (\d+) particles, (\d+) neighbour rebuilds[^)]*\)")
PASTEMIX_STAGE = re.compile(r"^ +([a-z_]+) +([0-9.eE+-]+) s +([0-9.]+) %", re.M)
PASTEMIX_TOTAL = re.compile(r"^ +total wall +([0-9.eE+-]+) s", re.M)


def parse_pastemix(text):
    h, t = PASTEMIX_HEAD.search(text), PASTEMIX_TOTAL.search(text)
    if not (h and t):
        return None
    stages = {s.group(1): float(s.group(2)) for s in PASTEMIX_STAGE.finditer(text[h.end():])}
    loop = float(t.group(1)) - stages.get("output", 0.0)
    line = "%s; total wall %s s, output %.3g s" % (h.group(0), t.group(1), stages.get("output", 0.0))
    stages.pop("output", None)
    stages["other"] = max(0.0, loop - sum(stages.values()))  # diagnostics, loop overhead
    return dict(loop_s=loop, steps=int(h.group(1)), particles=int(h.group(2)), stages=stages, line=line,
                rebuilds=int(h.group(3)), final=None)


def pastemix_final_state(h5path):
    """(KE, rotational KE, z_com, pair contacts) at the end of a pastemix run, from its HDF5 output."""
    try:
        import h5py
        import numpy as np
        with h5py.File(h5path, "r") as f:
            t = f["timeseries"]
            last = sorted(k for k in f["snapshots"] if k != "time")[-1]
            snap = f["snapshots"][last]
            r, z = snap["radius"][:], snap["position"][:, 2]
            return dict(ke=float(t["kinetic"][-1]), rke=float(t["rotational"][-1]),
                        zcom=float((r**3 * z).sum() / (r**3).sum()), npair=int(t["pair_contacts"][-1]))
    except Exception as e:  # the cross-check is informative; a missing file must not hide the timings
        print("report: no final state from %s (%s)" % (h5path, e), file=sys.stderr)
        return None


def read_cpu(path):
    try:
        with open(path) as f:
            return float(f.readline().split()[1])
    except (OSError, IndexError, ValueError):
        return None


def read_maxrss_kb(path):
    """Peak RSS (kB) of the largest process of a run (tools/cputime.py), or None for an older .cpu file."""
    try:
        with open(path) as f:
            for line in f:
                k, v = line.split()
                if k == "maxrss_kB":
                    return int(v)
    except (OSError, ValueError):
        pass
    return None


def collect(work, finals):
    """Best (shortest-loop) run per (code, scene, threads); also the least loop CPU time over the repeats
    (CPU of the run minus CPU of the 1-step setup run: see tools/cputime.py)."""
    best = {}
    cpu_best = {}
    for path in sorted(glob.glob(os.path.join(work, "*.log"))):
        n = LOGNAME.search(os.path.basename(path))
        if not n:
            continue
        code, scene, threads = n.group(1), n.group(2), int(n.group(3))
        with open(path, errors="replace") as f:
            text = f.read()
        r = (parse_liggghts if code == "liggghts" else parse_pastemix)(text)
        if r is None:
            print("report: no loop time in %s" % path, file=sys.stderr)
            continue
        if code != "liggghts":
            h5 = glob.glob(os.path.join(work, "out_%s_%s_t%d_r%s" % (code, scene, threads, n.group(4)), "*.h5"))
            r["final"] = pastemix_final_state(h5[0]) if h5 else None
        key = (code, scene, threads)
        cpu, setup = read_cpu(path + ".cpu"), read_cpu(
            os.path.join(work, "%s_%s_t%d_setup.log.cpu" % (code, scene, threads)))
        if cpu is not None and setup is not None:
            cpu_best[key] = min(cpu_best.get(key, float("inf")), cpu - setup)
        if r["final"] is not None:
            finals.setdefault(key, r["final"])  # the first repeat that has one
        r["maxrss_kB"] = read_maxrss_kb(path + ".cpu")
        r["runs"] = best.get(key, {}).get("runs", 0) + 1
        r["log"] = os.path.basename(path)
        if key not in best or r["loop_s"] < best[key]["loop_s"]:
            best[key] = r
        else:
            best[key]["runs"] = r["runs"]
    for key, c in cpu_best.items():
        best[key]["cpu_s"] = c
    return best


def mps(r):
    return r["particles"] * r["steps"] / r["loop_s"] / 1e6


def cpu_mps(r):
    c = r.get("cpu_s")
    return r["particles"] * r["steps"] / c / 1e6 if c and c > 0 else None


def stage_text(r):
    total = r["loop_s"]
    return " ".join("%s %.0f%%" % (k, 100 * v / total) for k, v in r["stages"].items())


def main():
    work, csv_out = sys.argv[1:3]
    finals = {}
    best = collect(work, finals)
    scenes = sorted({k[1] for k in best}, key=lambda s: ["pour", "bed"].index(s) if s in ("pour", "bed") else 9)
    threads = sorted({k[2] for k in best})
    stamp = time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())
    load = os.getloadavg()
    print("\nparticle-steps per second (millions), best of repeats; machine %s, %d cores, load avg %.1f"
          % (socket.gethostname(), os.cpu_count(), load[0]))
    print("%-6s %7s %16s %16s %8s   %s" % ("scene", "threads", "pastemix Mps/s", "LIGGGHTS Mps/s", "ratio",
                                        "(per CPU-second: pastemix, LIGGGHTS, ratio)"))
    rows = []
    for s in scenes:
        for t in threads:
            p, l = best.get(("pastemix", s, t)), best.get(("liggghts", s, t))
            pm = mps(p) if p else None
            lm = mps(l) if l else None
            ratio = pm / lm if (pm and lm) else None
            pc, lc = (cpu_mps(p) if p else None), (cpu_mps(l) if l else None)
            print("%-6s %7d %16s %16s %8s   (%s, %s, %s)" % (
                s, t, "%.3f" % pm if pm else "-", "%.3f" % lm if lm else "-",
                "%.2f" % ratio if ratio else "-", "%.3f" % pc if pc else "-", "%.3f" % lc if lc else "-",
                "%.2f" % (pc / lc) if (pc and lc) else "-"))
            for code, r in (("pastemix", p), ("liggghts", l)):
                if r:
                    rows.append([stamp, s, t, code, r["particles"], r["steps"], "%.6g" % r["loop_s"],
                                 r["runs"], "%.6g" % mps(r), "%.4g" % ratio if ratio else "",
                                 "%.6g" % r["cpu_s"] if r.get("cpu_s") else "",
                                 "%.6g" % cpu_mps(r) if cpu_mps(r) else "", stage_text(r), r["log"],
                                 r.get("maxrss_kB") or ""])
    if any(k[0] == "baseline" for k in best):
        print("\nthis build against the baseline build (PASTEMIX_BASELINE), interleaved in the same run:")
        print("%-6s %7s %16s %16s %12s %22s" % ("scene", "threads", "pastemix Mps/s", "baseline Mps/s",
                                               "pm/baseline", "baseline/LIGGGHTS"))
        for s in scenes:
            for t in threads:
                p, b, l = (best.get((c, s, t)) for c in ("pastemix", "baseline", "liggghts"))
                print("%-6s %7d %16s %16s %12s %22s" % (
                    s, t, "%.3f" % mps(p) if p else "-", "%.3f" % mps(b) if b else "-",
                    "%.3f" % (mps(p) / mps(b)) if (p and b) else "-",
                    "%.2f" % (mps(b) / mps(l)) if (b and l) else "-"))
                if b:
                    rows.append([stamp, s, t, "baseline", b["particles"], b["steps"], "%.6g" % b["loop_s"],
                                 b["runs"], "%.6g" % mps(b), "%.4g" % (mps(b) / mps(l)) if l else "",
                                 "%.6g" % b["cpu_s"] if b.get("cpu_s") else "",
                                 "%.6g" % cpu_mps(b) if cpu_mps(b) else "", stage_text(b), b["log"],
                                 b.get("maxrss_kB") or ""])
    if len(threads) > 1:
        lo, hi = threads[0], threads[-1]
        print("\nspeed-up from %d to %d thread(s)/rank(s) (best runs, wall clock):" % (lo, hi))
        print("%-6s %10s %10s" % ("scene", "pastemix", "LIGGGHTS"))
        for s in scenes:
            ups = []
            for code in ("pastemix", "liggghts"):
                a, b = best.get((code, s, lo)), best.get((code, s, hi))
                ups.append("%.2fx" % (mps(b) / mps(a)) if (a and b) else "-")
            print("%-6s %10s %10s" % (s, *ups))
    print("\npeak memory per particle (peak RSS of the largest process / N; includes the binary, its libraries "
          "and input parsing; at 2+ ranks one LIGGGHTS rank holds about 1/ranks of the particles):")
    print("%-6s %7s %16s %16s" % ("scene", "threads", "pastemix B", "LIGGGHTS B"))
    for s in scenes:
        for t in threads:
            cells = []
            for code in ("pastemix", "liggghts"):
                r = best.get((code, s, t))
                kb = r.get("maxrss_kB") if r else None
                cells.append("%.0f (%.0f MB)" % (kb * 1024 / r["particles"], kb / 1024) if kb else "-")
            print("%-6s %7d %16s %16s" % (s, t, *cells))
    print("\nwhere the time goes (share of the loop time, best run):")
    for (code, s, t), r in sorted(best.items(), key=lambda kv: (kv[0][1], kv[0][2], kv[0][0])):
        print("  %-8s %-5s t%d: %s" % (code, s, t, stage_text(r)))
        print("           %s" % r["line"])
    print("\nsame scene? state at the end of the segment (first repeat), and neighbour-list rebuilds:")
    print("  %-8s %-5s %3s %12s %12s %10s %8s %9s" % ("code", "scene", "thr", "KE J", "rot KE J", "z_com m",
                                                   "contacts", "rebuilds"))
    for (code, s, t), r in sorted(best.items(), key=lambda kv: (kv[0][1], kv[0][2], kv[0][0])):
        fin = finals.get((code, s, t))
        print("  %-8s %-5s %3d %12s %12s %10s %8s %9s" % (
            code, s, t, "%.5g" % fin["ke"] if fin else "-", "%.4g" % fin["rke"] if fin else "-",
            "%.6f" % fin["zcom"] if fin else "-", fin["npair"] if fin else "-", r.get("rebuilds")))
    with open(csv_out, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["date_utc", "scene", "threads", "code", "particles", "steps", "loop_s", "runs", "mps",
                    "ratio_pastemix_over_liggghts", "loop_cpu_s", "mps_per_cpu_s", "stages", "log", "maxrss_kB", "load_avg_1min", "settings"])
        for row in rows:
            w.writerow(row + ["%.1f" % load[0], os.environ.get("BENCH_SETTINGS", "")])
    print("\nwrote %s" % csv_out)


if __name__ == "__main__":
    main()
