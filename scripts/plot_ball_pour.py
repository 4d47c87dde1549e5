#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# Presence-probability maps of the poured steel balls (`pastemix validate ball-pour --csv FILE`):
# per 1 cm cell, the fraction of the seeded runs in which at least one ball centre lies in the cell,
# seen from above (x-y) and from the side (x-z), with the lab's Z band (8.5-13.5 cm) on the side view.
# Usage: /usr/bin/python3 scripts/plot_ball_pour.py ball_pour.csv out.png
import csv
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

rows = list(csv.DictReader(open(sys.argv[1])))
seeds = sorted({int(r["seed"]) for r in rows})
x = np.array([float(r["x_m"]) for r in rows]) * 100
y = np.array([float(r["y_m"]) for r in rows]) * 100
z = np.array([float(r["z_m"]) for r in rows]) * 100
s = np.array([int(r["seed"]) for r in rows])
xe, ye, ze = np.arange(0, 20.01, 1.0), np.arange(0, 16.51, 1.0), np.arange(0, 15.01, 1.0)


def presence(a, b, ea, eb):
    p = np.zeros((len(ea) - 1, len(eb) - 1))
    for k in seeds:
        h, _, _ = np.histogram2d(a[s == k], b[s == k], bins=[ea, eb])
        p += h > 0
    return p / len(seeds)


fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
im = ax[0].pcolormesh(xe, ye, presence(x, y, xe, ye).T, vmin=0, vmax=1, cmap="viridis")
ax[0].set(xlabel="x (cm)", ylabel="y (cm)", title=f"from above: presence probability ({len(seeds)} runs)", aspect="equal")
ax[1].pcolormesh(xe, ze, presence(x, z, xe, ze).T, vmin=0, vmax=1, cmap="viridis")
ax[1].axhspan(8.5, 13.5, fill=False, ec="r", ls="--", label="lab: Z = 8.5-13.5 cm")
ax[1].set(xlabel="x (cm)", ylabel="Z (cm)", title=f"side: Z {z.min():.1f}-{z.max():.1f} cm", aspect="equal")
ax[1].legend(loc="lower right", fontsize=8)
fig.colorbar(im, ax=ax, shrink=0.8, label="fraction of runs with a ball in the 1 cm cell")
fig.savefig(sys.argv[2], dpi=110)
print(f"wrote {sys.argv[2]}: {len(seeds)} runs, {len(rows)} balls, Z = {z.min():.2f}-{z.max():.2f} cm")
