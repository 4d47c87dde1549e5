#!/usr/bin/env python3
"""Issue 22: why a flow run misses the lab's unmixed cone, measured. A vertical profile of the final state in a
column of the block grid (default the centre column, blocks M_22k and M_32k: x 5-15 cm, y 5.5-11 cm):
per flow cell layer (1 cm), the rock's volume fraction (each sphere sliced exactly by the layer's planes, counted
where its centre lies in the column), the paste's share of the pore space (the flow's alpha, the paste share of
the fluid volume, averaged over the column's cells: the void filling the lab's S measures) and the paste's
volume fraction of the layer (that share times 1 - rock). A result without a flow field (at rest) gets the flat
surface instead: the pores below it full of paste, none above.

    /usr/bin/python3 scripts/flow_profile.py RESULT.h5 [--x 0.05 0.15] [--y 0.055 0.11] [--png OUT.png]
"""
import argparse
import math
import sys

import h5py
import numpy as np


def last_key(group):
    return sorted(k for k in group.keys() if k.isdigit())[-1]


def cap_volume(r, h):
    """Volume of a sphere cap of height h (0..2r) of a sphere of radius r."""
    h = min(max(h, 0.0), 2.0 * r)
    return math.pi * h * h * (3.0 * r - h) / 3.0


def rock_fraction(pos, rad, x, y, edges):
    """Rock volume per layer between edges (m3), spheres whose centres lie in the column, over the column's volume."""
    inside = (pos[:, 0] >= x[0]) & (pos[:, 0] < x[1]) & (pos[:, 1] >= y[0]) & (pos[:, 1] < y[1])
    vol = np.zeros(len(edges) - 1)
    for (cx, cy, cz), r in zip(pos[inside], rad[inside]):
        for k in range(len(edges) - 1):
            lo, hi = edges[k], edges[k + 1]
            if cz + r <= lo or cz - r >= hi:
                continue
            vol[k] += cap_volume(r, hi - (cz - r)) - cap_volume(r, lo - (cz - r))
    area = (x[1] - x[0]) * (y[1] - y[0])
    return vol / (area * np.diff(edges))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("result")
    ap.add_argument("--x", nargs=2, type=float, default=[0.05, 0.15])
    ap.add_argument("--y", nargs=2, type=float, default=[0.055, 0.11])
    ap.add_argument("--png")
    a = ap.parse_args()
    with h5py.File(a.result) as f:
        snap = f["snapshots"][last_key(f["snapshots"])]
        pos, rad, t = np.array(snap["position"]), np.array(snap["radius"]), float(snap.attrs["time_s"])
        flow = f["flow"] if "flow" in f else None
        if flow is not None:
            at = flow.attrs
            n = [int(at["nx"]), int(at["ny"]), int(at["nz"])]
            h = [float(at["hx"]), float(at["hy"]), float(at["hz"])]
            o = [float(at["origin_x"]), float(at["origin_y"]), float(at["origin_z"])]
            fs = flow["snapshots"][last_key(flow["snapshots"])]
            alpha = np.array(fs["paste_fraction"])  # (nz, ny, nx)
            edges = o[2] + h[2] * np.arange(n[2] + 1)
            xc = o[0] + h[0] * (np.arange(n[0]) + 0.5)
            yc = o[1] + h[1] * (np.arange(n[1]) + 0.5)
            ix = (xc >= a.x[0]) & (xc < a.x[1])
            iy = (yc >= a.y[0]) & (yc < a.y[1])
            paste = alpha[:, iy, :][:, :, ix].mean(axis=(1, 2))
            source = f"the flow field at t = {float(fs.attrs['time_s']):.3f} s"
        else:
            surface = float(f.attrs["fluid_surface_z"]) if "fluid_surface_z" in f.attrs else 0.10
            edges = np.arange(0.0, 0.2001, 0.01)
            paste = None
            source = f"at rest: paste below the flat surface z = {surface:.4f} m"
    rock = rock_fraction(pos, rad, a.x, a.y, edges)
    print(f"{a.result}: t = {t:.3f} s; column x {a.x[0]}-{a.x[1]} m, y {a.y[0]}-{a.y[1]} m; paste from {source}")
    print(f"{'z cm':>11} | {'rock vol':>8} | {'paste / pores':>13} | {'paste vol':>9}")
    rows = []
    for k in range(len(edges) - 2, -1, -1):
        lo, hi = edges[k], edges[k + 1]
        share = float(paste[k]) if paste is not None else float(np.clip((surface - lo) / (hi - lo), 0.0, 1.0))
        p = share * (1.0 - rock[k])
        if rock[k] < 1e-4 and p < 1e-4 and lo > 0.1:
            continue
        rows.append((lo, hi, rock[k], p, share))
        print(f"{100 * lo:5.1f}-{100 * hi:4.1f} | {rock[k]:8.3f} | {share:13.3f} | {p:9.3f}")
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        z = [100 * (r[0] + r[1]) / 2 for r in rows]
        fig, ax = plt.subplots(figsize=(4.5, 5))
        ax.plot([r[2] for r in rows], z, "o-", label="rock volume fraction")
        ax.plot([r[4] for r in rows], z, "s-", label="paste share of the pores")
        ax.set_xlabel("volume fraction")
        ax.set_ylabel("z (cm)")
        ax.set_title(f"centre column, t = {t:.2f} s")
        ax.legend()
        fig.tight_layout()
        fig.savefig(a.png, dpi=120)
        print("wrote", a.png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
