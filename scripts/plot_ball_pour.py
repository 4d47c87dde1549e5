#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# Figures of `pastemix validate ball-pour` (it runs this script on its ball_pour.csv):
#   MAPS: presence probability per 1 cm cell (fraction of the seeded runs with at least one ball centre in
#         the cell) seen from above (x-y, the 20 x 16.5 cm frame) and from the side (x-Z), with the lab's
#         Z band (8.5-13.5 cm);
#   HIST: histogram of the final Z of every ball over all runs, with the lab band.
# Balls left in the funnel (in_funnel = 1) are not drawn; their count is in the titles.
# Usage: /usr/bin/python3 scripts/plot_ball_pour.py ball_pour.csv MAPS.png HIST.png
import csv
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

rows = list(csv.DictReader(open(sys.argv[1])))
stuck = sum(int(r["in_funnel"]) for r in rows)
rows = [r for r in rows if r["in_funnel"] == "0"]
seeds = sorted({int(r["seed"]) for r in rows})
x = np.array([float(r["x_m"]) for r in rows]) * 100
y = np.array([float(r["y_m"]) for r in rows]) * 100
z = np.array([float(r["z_m"]) for r in rows]) * 100
s = np.array([int(r["seed"]) for r in rows])
xe, ye, ze = np.arange(0, 20.01, 1.0), np.arange(0, 16.51, 1.0), np.arange(0, 15.01, 1.0)
n_runs = len(seeds)


def presence(a, b, ea, eb):
    p = np.zeros((len(ea) - 1, len(eb) - 1))
    for k in seeds:
        h, _, _ = np.histogram2d(a[s == k], b[s == k], bins=[ea, eb])
        p += h > 0
    return p / max(n_runs, 1)


fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
im = ax[0].pcolormesh(xe, ye, presence(x, y, xe, ye).T, vmin=0, vmax=1, cmap="viridis")
ax[0].set(xlabel="x (cm)", ylabel="y (cm)", title=f"from above: presence probability ({n_runs} runs)", aspect="equal")
ax[1].pcolormesh(xe, ze, presence(x, z, xe, ze).T, vmin=0, vmax=1, cmap="viridis")
ax[1].axhspan(8.5, 13.5, fill=False, ec="r", ls="--", label="lab: Z = 8.5-13.5 cm")
ax[1].set(xlabel="x (cm)", ylabel="Z (cm)", title=f"side: Z {z.min():.1f}-{z.max():.1f} cm", aspect="equal")
ax[1].legend(loc="lower right", fontsize=8)
fig.colorbar(im, ax=ax, shrink=0.8, label="fraction of runs with a ball in the 1 cm cell")
fig.suptitle(f"{len(rows)} balls out of the funnel, {stuck} left in it")
fig.savefig(sys.argv[2], dpi=110)

fig, ax = plt.subplots(figsize=(6, 4))
ax.hist(z, bins=np.arange(np.floor(z.min()) - 0.5, np.ceil(z.max()) + 1.0, 0.25), color="C0")
ax.axvspan(8.5, 13.5, color="r", alpha=0.12, label="lab: 8.5-13.5 cm")
ax.set(xlabel="final Z of the ball centre (cm, above the frame bottom)", ylabel="balls (all runs)",
       title=f"{n_runs} runs, {len(rows)} balls: Z {z.min():.2f}-{z.max():.2f} cm")
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(sys.argv[3], dpi=110)
print(f"wrote {sys.argv[2]} and {sys.argv[3]}: {n_runs} runs, {len(rows)} balls, Z = {z.min():.2f}-{z.max():.2f} cm")
