#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# Plot of a `pastemix sweep` CSV. Left: the QoI (mean, with the seed sd as error bars) against the cost of a
# run, the reference as a line and the tolerance as a band. Right: the relative error against the cost.
# The chosen point (cheapest within the tolerance) is a red star in both.
# Usage: plot_sweep.py sweep.csv sweep.png QOI_NAME [TOL]
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

src, dst, qoi = sys.argv[1], sys.argv[2], sys.argv[3]
tol = float(sys.argv[4]) if len(sys.argv) > 4 else None
with open(src) as f:
    rows = list(csv.DictReader(f))
var = list(rows[0].keys())[0]
cost = [float(r["particle_steps"]) for r in rows]
q = [float(r["qoi_mean"]) for r in rows]
sd = [float(r["qoi_sd"]) for r in rows]
err = [max(float(r["rel_error"]), 1e-16) for r in rows]
ref = float(rows[0]["reference"])
fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4.2))
a1.errorbar(cost, q, yerr=sd, fmt="o-", color="tab:blue", capsize=3, label=f"{qoi} (mean +- seed sd)")
a1.axhline(ref, color="k", lw=0.8, label="reference")
if tol:
    a1.axhspan(ref * (1 - tol), ref * (1 + tol), color="0.85", label=f"tolerance {tol:g}")
a1.set_xscale("log")
a2.loglog(cost, err, "o-", color="tab:blue", label=f"{qoi} error vs reference")
for r, c, v, e in zip(rows, cost, q, err):
    for ax, y in ((a1, v), (a2, e)):
        ax.annotate(f"{var}={float(r[var]):.3g}", (c, y), textcoords="offset points", xytext=(4, 4), fontsize=7)
        if r["chosen"] == "1":
            ax.plot([c], [y], "*", ms=16, color="tab:red", label="chosen (cheapest within tol)")
a1.set_xlabel("cost of one run (particle-steps)")
a1.set_ylabel(qoi)
a2.set_xlabel("cost of one run (particle-steps)")
a2.set_ylabel(f"|{qoi} - ref| / |ref|")
fig.suptitle(f"sweep {var}: reference = {rows[0]['reference_method']}", fontsize=8)
for ax in (a1, a2):
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(dst, dpi=120)
