#!/usr/bin/python3
"""The scaling series of bench/run.sh --scaling: cost per particle-step against N, for both codes (and the
baseline build, PASTEMIX_BASELINE, when the harness ran one).

Logs in WORK are <code>_pours<K>_t1_r<repeat>.log (the pour K times wider and longer: K^2 x 12,960 spheres,
same 12 layers, so every column of the pile sees the same physics and only N changes). For each (code, K) the
shortest loop time over the repeats is kept (report.py's parsers). It prints, per code: N, ns per
particle-step, its growth from the smallest to the largest N, the exponent b of loop time per step ~ N^b
(least squares on the logs; 1 = linear), and the peak RSS per particle with the marginal memory per added
particle (the slope of peak RSS against N, which leaves out the binary and libraries).
Usage: scaling.py WORK CSV_OUT
"""
import csv
import glob
import math
import os
import re
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report  # noqa: E402  (the log parsers)

LOGNAME = re.compile(r"(liggghts|pastemix|baseline)_pours(\d+)_t1_r(\d+)\.log$")


def slope(xs, ys):
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else float("nan")


def collect(work):
    best = {}
    for path in sorted(glob.glob(os.path.join(work, "*.log"))):
        m = LOGNAME.search(os.path.basename(path))
        if not m:
            continue
        code, k = m.group(1), int(m.group(2))
        with open(path, errors="replace") as f:
            text = f.read()
        r = (report.parse_liggghts if code == "liggghts" else report.parse_pastemix)(text)
        if r is None:
            print("scaling: no loop time in %s" % path, file=sys.stderr)
            continue
        r["maxrss_kB"] = report.read_maxrss_kb(path + ".cpu")
        key = (code, k)
        if key not in best or r["loop_s"] < best[key]["loop_s"]:
            best[key] = r
    return best


def main():
    work, csv_out = sys.argv[1:3]
    best = collect(work)
    stamp = time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())
    rows = []
    print("%-8s %4s %9s %14s %12s %14s" % ("code", "K", "N", "ns/particle-step", "Mps/s", "peak RSS B/N"))
    summary = []
    for code in ("pastemix", "baseline", "liggghts"):
        ks = sorted(k for c, k in best if c == code)
        if not ks:
            continue
        ns, cost, rss = [], [], []
        for k in ks:
            r = best[(code, k)]
            n = r["particles"]
            ns_per = r["loop_s"] / (n * r["steps"]) * 1e9
            kb = r.get("maxrss_kB")
            ns.append(n)
            cost.append(r["loop_s"] / r["steps"])
            rss.append(kb * 1024.0 if kb else None)
            print("%-8s %4d %9d %14.1f %12.3f %14s" % (code, k, n, ns_per, n * r["steps"] / r["loop_s"] / 1e6,
                                                       "%.0f" % (kb * 1024.0 / n) if kb else "-"))
            rows.append([stamp, code, k, n, r["steps"], "%.6g" % r["loop_s"], "%.4g" % ns_per, kb or "",
                         "%.1f" % os.getloadavg()[0], os.environ.get("BENCH_SETTINGS", "")])
        if len(ns) > 1:
            per = [c / n for c, n in zip(cost, ns)]
            growth = 100.0 * (per[-1] / per[0] - 1.0)
            b = slope([math.log(n) for n in ns], [math.log(c) for c in cost])
            marginal = slope(ns, rss) if all(v is not None for v in rss) else float("nan")
            summary.append("%s: cost per particle-step %+.1f %% from N = %d to %d; loop time per step ~ N^%.3f; "
                           "marginal memory %.0f B per added particle" % (code, growth, ns[0], ns[-1], b, marginal))
    for line in summary:
        print(line)
    with open(csv_out, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["date_utc", "code", "scale", "particles", "steps", "loop_s", "ns_per_particle_step",
                    "maxrss_kB", "load_avg_1min", "settings"])
        w.writerows(rows)
    print("wrote %s" % csv_out)


if __name__ == "__main__":
    main()
