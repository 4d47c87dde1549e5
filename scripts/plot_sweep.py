#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# Plot of a `pastemix sweep` CSV: relative QoI error against wall-clock cost, chosen point marked.
# Usage: plot_sweep.py sweep.csv sweep.png QOI_NAME
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

src, dst, qoi = sys.argv[1], sys.argv[2], sys.argv[3]
with open(src) as f:
    rows = list(csv.DictReader(f))
var = list(rows[0].keys())[0]
cost = [float(r["particle_steps"]) for r in rows]
err = [max(float(r["rel_error"]), 1e-16) for r in rows]
fig, ax = plt.subplots(figsize=(6, 4.2))
ax.loglog(cost, err, "o-", color="tab:blue", label=f"{qoi} error vs reference")
for r, c, e in zip(rows, cost, err):
    ax.annotate(f"{var}={float(r[var]):.3g}", (c, e), textcoords="offset points", xytext=(4, 4), fontsize=7)
    if r["chosen"] == "1":
        ax.plot([c], [e], "*", ms=16, color="tab:red", label="chosen (cheapest within tol)")
ax.set_xlabel("cost of one run (particle-steps)")
ax.set_ylabel(f"|{qoi} - ref| / |ref|")
ax.set_title(f"sweep {var}: reference = {rows[0]['reference_method']}", fontsize=8)
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(dst, dpi=120)
