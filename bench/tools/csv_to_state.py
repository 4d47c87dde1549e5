#!/usr/bin/python3
"""Unpack a committed initial state (CSV, optionally gzipped) into <stem>.csv + <stem>.data (LIGGGHTS).
Usage: csv_to_state.py STATE.csv[.gz] OUT_STEM
"""
import gzip
import sys

import numpy as np

sys.path.insert(0, __file__.rsplit("/", 1)[0])
import make_pour  # noqa: E402


def main():
    src, stem = sys.argv[1:3]
    opener = gzip.open if src.endswith(".gz") else open
    with opener(src, "rt") as f:
        header = f.readline().strip().split(",")
        a = np.loadtxt(f, delimiter=",", ndmin=2)
    col = {c: a[:, k] for k, c in enumerate(header)}
    d = col["diameter"]
    pos = np.column_stack([col["x"], col["y"], col["z"]])
    vel = np.column_stack([col["vx"], col["vy"], col["vz"]])
    make_pour.write(stem, d, pos, vel, "unpacked from %s" % src.rsplit("/", 1)[-1])
    print("%s: %d spheres from %s" % (stem, d.size, src))


if __name__ == "__main__":
    main()
