#!/usr/bin/python3
"""Parse the benchmark logs of one harness run and print the ratio table.

Logs are named <code>_<scene>_t<threads>_r<repeat>.log in WORK (code: liggghts or pastemix).
For each (code, scene, threads) the best (shortest) loop time over the repeats is kept: on a shared,
noisy machine other processes can only add time, so the minimum is the best estimate of the cost.
particle-steps/s = particles x steps / loop time, where loop time is the wall-clock of the time-step
loop only (LIGGGHTS: its "Loop time" line; pastemix: its own loop timer), setup and I/O excluded.
Usage: report.py WORK CSV_OUT
"""
import glob
import os
import re
import socket
import sys
import time

LIGGGHTS_LOOP = re.compile(
    r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms")
LIGGGHTS_STAGE = re.compile(r"^(Pair|Neigh|Comm|Outpt|Modfy|Other) +time \(%\) = ([0-9.eE+-]+) \(([0-9.eE+-]+)\)")
LOGNAME = re.compile(r"(liggghts|pastemix)_(\w+?)_t(\d+)_r(\d+)\.log$")


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
    return dict(loop_s=float(m.group(1)), steps=int(m.group(3)), particles=int(m.group(4)),
                stages=stages, line=m.group(0))


# pastemix prints (model/world, on stderr at the end of `pastemix run`):
#   loop: <steps> steps, <particles> particles, <seconds> s
#   stage <name>: <seconds> s (<percent> %)
PASTEMIX_LOOP = re.compile(r"loop: (\d+) steps, (\d+) particles, ([0-9.eE+-]+) s")
PASTEMIX_STAGE = re.compile(r"^stage ([\w/-]+): ([0-9.eE+-]+) s", re.M)


def parse_pastemix(text):
    m = PASTEMIX_LOOP.search(text)
    if not m:
        return None
    stages = {s.group(1): float(s.group(2)) for s in PASTEMIX_STAGE.finditer(text)}
    return dict(loop_s=float(m.group(3)), steps=int(m.group(1)), particles=int(m.group(2)),
                stages=stages, line=m.group(0))


def collect(work):
    best = {}
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
        key = (code, scene, threads)
        r["runs"] = best.get(key, {}).get("runs", 0) + 1
        r["log"] = os.path.basename(path)
        if key not in best or r["loop_s"] < best[key]["loop_s"]:
            best[key] = r
        else:
            best[key]["runs"] = r["runs"]
    return best


def mps(r):
    return r["particles"] * r["steps"] / r["loop_s"] / 1e6


def stage_text(r):
    total = r["loop_s"]
    return " ".join("%s %.0f%%" % (k, 100 * v / total) for k, v in r["stages"].items())


def main():
    work, csv_out = sys.argv[1:3]
    best = collect(work)
    scenes = sorted({k[1] for k in best}, key=lambda s: ["pour", "bed"].index(s) if s in ("pour", "bed") else 9)
    threads = sorted({k[2] for k in best})
    stamp = time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())
    load = os.getloadavg()
    print("\nparticle-steps per second (millions), best of repeats; machine %s, %d cores, load avg %.1f"
          % (socket.gethostname(), os.cpu_count(), load[0]))
    print("%-6s %7s %16s %16s %8s" % ("scene", "threads", "pastemix Mps/s", "LIGGGHTS Mps/s", "ratio"))
    rows = []
    for s in scenes:
        for t in threads:
            p, l = best.get(("pastemix", s, t)), best.get(("liggghts", s, t))
            pm = mps(p) if p else None
            lm = mps(l) if l else None
            ratio = pm / lm if (pm and lm) else None
            print("%-6s %7d %16s %16s %8s" % (
                s, t, "%.3f" % pm if pm else "-", "%.3f" % lm if lm else "-",
                "%.2f" % ratio if ratio else "-"))
            for code, r in (("pastemix", p), ("liggghts", l)):
                if r:
                    rows.append([stamp, s, t, code, r["particles"], r["steps"], "%.6g" % r["loop_s"],
                                 r["runs"], "%.6g" % mps(r), "%.4g" % ratio if ratio else "",
                                 stage_text(r), r["log"]])
    print("\nwhere the time goes (share of the loop time, best run):")
    for (code, s, t), r in sorted(best.items(), key=lambda kv: (kv[0][1], kv[0][2], kv[0][0])):
        print("  %-8s %-5s t%d: %s" % (code, s, t, stage_text(r)))
        print("           %s" % r["line"])
    with open(csv_out, "w") as f:
        f.write("date_utc,scene,threads,code,particles,steps,loop_s,runs,mps,ratio_pastemix_over_liggghts,"
                "stages,log\n")
        for row in rows:
            f.write(",".join('"%s"' % c if isinstance(c, str) and " " in c else str(c) for c in row) + "\n")
    print("\nwrote %s" % csv_out)


if __name__ == "__main__":
    main()
