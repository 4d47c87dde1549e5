#!/usr/bin/env python3
"""Issue 18: the dense stream (datasets/scenes/flow_stream_small.toml) at several coupling intervals, side by side.

For each run's .h5: the final state's rock depth below the initial paste surface (mean, and the mass shares
below 0.5 / 1 / 2 cm), the kinetic energy's peak and end, the paste volume drift, and whether any value is NaN.
Usage: /usr/bin/python3 scripts/stream_compare.py LABEL=RUN.h5 ... [--surface 0.06]
"""
import sys

import h5py
import numpy as np


def main(argv):
    surface = 0.06  # m, the scene's paste surface (flow_drop.toml: 6 cm of paste)
    if "--surface" in argv:
        surface = float(argv[argv.index("--surface") + 1])
    print("interval | t_end s | rock mean depth mm | mass below 0.5 / 1 / 2 cm % | K peak mJ | K end uJ | paste volume drift | NaN")
    for arg in argv:
        if "=" not in arg:
            continue
        label, path = arg.split("=", 1)
        f = h5py.File(path, "r")
        snaps = sorted(k for k in f["snapshots"].keys() if k != "time")
        s = f["snapshots"][snaps[-1]]
        z = s["position"][:, 2]
        r = s["radius"][:]
        m = r ** 3  # one material: mass share by volume
        depth = surface - z
        share = [100 * m[depth > d].sum() / m.sum() for d in (0.005, 0.01, 0.02)]
        K = f["timeseries"]["kinetic"][:]
        pv = f["flow"]["timeseries"]["paste_volume"][:]
        nan = not (np.isfinite(s["position"][:]).all() and np.isfinite(K).all())
        t = f["snapshots"]["time"][-1]
        print(f"{label} | {t:.3f} | {1e3 * np.average(depth, weights=m):.2f} | "
              f"{share[0]:.1f} / {share[1]:.1f} / {share[2]:.1f} | {1e3 * K.max():.3f} | {1e6 * K[-1]:.3f} | "
              f"{(pv[-1] - pv[0]) / pv[0]:+.2e} | {'yes' if nan else 'no'}")


if __name__ == "__main__":
    main(sys.argv[1:])
