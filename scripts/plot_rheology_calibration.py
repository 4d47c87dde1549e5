#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# Objective against the shape parameter for `pastemix calibrate rheology` (app/study/calibrate_rheology.h):
# J of the seed-mean layers with its jackknife se, each seed's J_s, the quadratic surrogate, the result +- sd
# and the prior range.  Usage: plot_rheology_calibration.py points.csv out.png --name b --prior LO HI
#                              --fit c0 c1 c2 p_ref vertex sd ok
import argparse
import csv
import sys

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit(3)

ap = argparse.ArgumentParser()
ap.add_argument("csv")
ap.add_argument("png")
ap.add_argument("--name", default="shape")
ap.add_argument("--prior", nargs=2, type=float)
ap.add_argument("--fit", nargs=7, type=float)
a = ap.parse_args()

rows = [r for r in csv.DictReader(open(a.csv)) if r["failed"] == "0"]
p = [float(r["shape"]) for r in rows]
J = [float(r["J"]) for r in rows]
se = [float(r["J_se"]) for r in rows]
Js = [float(r["J_seed_mean"]) for r in rows]
Jsd = [float(r["J_seed_sd"]) for r in rows]
fig, ax = plt.subplots(figsize=(7, 4.5))
ax.axvspan(a.prior[0], a.prior[1], color="0.93", label="prior range")
ax.errorbar(p, J, yerr=se, fmt="o", color="C0", capsize=3, label="J of the seed-mean layers (jackknife se)")
ax.errorbar(p, Js, yerr=Jsd, fmt="x", color="C1", capsize=3, alpha=0.7, label="per-seed J: mean (sd)")
c0, c1, c2, pref, vertex, sd, ok = a.fit
if c2 > 0:
    lo, hi = min(p), max(p)
    xs = [lo + (hi - lo) * i / 200 for i in range(201)]
    ax.plot(xs, [c0 + c1 * (x - pref) + c2 * (x - pref) ** 2 for x in xs], "-", color="C0", lw=1, label="surrogate")
if ok > 0.5:
    ax.axvline(vertex, color="C3", lw=1.5, label=f"result {vertex:.4g} +- {sd:.2g}")
    ax.axvspan(vertex - sd, vertex + sd, color="C3", alpha=0.15)
ax.set_xlabel(f"shape parameter {a.name}")
ax.set_ylabel("J = mean squared relative error of the layer rock masses")
ax.set_ylim(bottom=0)
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(a.png, dpi=120)
