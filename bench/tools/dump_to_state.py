#!/usr/bin/python3
"""Convert the settled LIGGGHTS dump (in.settle's write_dump) into the bed initial state for both codes.

Velocities are set to zero (the bed is released at rest; contact history starts empty in both codes),
so the state is fully described by id, diameter and position.
Usage: dump_to_state.py DUMP OUT_STEM "comment"
"""
import sys
import numpy as np

sys.path.insert(0, __file__.rsplit("/", 1)[0])
import make_pour  # noqa: E402  (writers and box size)


def read_dump(path):
    with open(path) as f:
        lines = f.read().splitlines()
    start = next(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
    cols = lines[start].split()[2:]
    rows = np.array([[float(v) for v in l.split()] for l in lines[start + 1:] if l.strip()])
    return {c: rows[:, k] for k, c in enumerate(cols)}


def main():
    dump, stem, comment = sys.argv[1:4]
    a = read_dump(dump)
    order = np.argsort(a["id"])
    d = a["diameter"][order]
    pos = np.column_stack([a["x"][order], a["y"][order], a["z"][order]])
    vel = np.zeros_like(pos)
    make_pour.write(stem, d, pos, vel, comment)
    print("%s: %d spheres, bed top z = %.4f m" % (stem, d.size, (pos[:, 2] + d / 2).max()))


if __name__ == "__main__":
    main()
