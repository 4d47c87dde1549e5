#!/usr/bin/python3
"""Convert the settled LIGGGHTS dump (in.settle's write_dump) into the bed initial state for both codes.

Velocities are set to zero (the bed is released at rest; contact history starts empty in both codes),
so the state is fully described by id, diameter and position.

Each sphere's radius is reduced by just enough that no two spheres and no sphere and wall overlap:
s_i = max(largest pair overlap of i / 2, its wall overlap) + GAP. The settled bed has Hertz overlaps of up
to ~10 um (0.4 % of d_min), and pastemix's scene reader (rightly, for hand-written scenes) rejects explicit
particles that overlap. Both codes start from this same state: every former contact is open by a few um
at most, so the bed re-closes within a few tens of steps and is the same dense bed.
Usage: dump_to_state.py DUMP OUT_STEM "comment"
"""
import sys
import numpy as np
from scipy.spatial import cKDTree

GAP = 0.5e-6  # m, extra radius reduction so that former contacts are open by at least 2 GAP

sys.path.insert(0, __file__.rsplit("/", 1)[0])
import make_pour  # noqa: E402  (writers and box size)


def read_dump(path):
    with open(path) as f:
        lines = f.read().splitlines()
    start = next(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
    cols = lines[start].split()[2:]
    rows = np.array([[float(v) for v in l.split()] for l in lines[start + 1:] if l.strip()])
    return {c: rows[:, k] for k, c in enumerate(cols)}


def wall_gaps(r, pos):
    return np.min([pos[:, 0] - r, make_pour.BOX_X - pos[:, 0] - r, pos[:, 1] - r,
                   make_pour.BOX_Y - pos[:, 1] - r, pos[:, 2] - r], axis=0)


def pair_gaps(r, pos):
    pairs = cKDTree(pos).query_pairs(2 * r.max(), output_type="ndarray")
    gap = np.linalg.norm(pos[pairs[:, 0]] - pos[pairs[:, 1]], axis=1) - r[pairs[:, 0]] - r[pairs[:, 1]]
    return pairs, gap


def shrink(d, pos):
    r = d / 2
    pairs, gap = pair_gaps(r, pos)
    s = np.maximum(0.0, -wall_gaps(r, pos))
    half = np.maximum(0.0, -gap) / 2
    np.maximum.at(s, pairs[:, 0], half)
    np.maximum.at(s, pairs[:, 1], half)
    print("settled bed: %d pair contacts (max overlap %.3g m), %d wall contacts (max %.3g m); "
          "radii reduced by up to %.3g m" % ((gap < 0).sum(), -gap.min(), (wall_gaps(r, pos) < 0).sum(),
                                             -wall_gaps(r, pos).min(), s.max() + GAP))
    return 2 * (r - s - GAP)


def check_no_overlap(d, pos):
    r = d / 2
    _, gap = pair_gaps(r, pos)
    wall = wall_gaps(r, pos)
    if gap.min() <= 0 or wall.min() <= 0:
        sys.exit("dump_to_state: overlap left after shrinking: pair gap %.3g m, wall gap %.3g m"
                 % (gap.min(), wall.min()))
    print("after: closest pair gap %.2g m (%d pairs open by < 10 um), closest wall gap %.2g m"
          % (gap.min(), (gap < 1e-5).sum(), wall.min()))


def main():
    dump, stem, comment = sys.argv[1:4]
    a = read_dump(dump)
    order = np.argsort(a["id"])
    d = a["diameter"][order]
    pos = np.column_stack([a["x"][order], a["y"][order], a["z"][order]])
    vel = np.zeros_like(pos)
    d = shrink(d, pos)
    check_no_overlap(d, pos)
    make_pour.write(stem, d, pos, vel, comment)
    print("%s: %d spheres, bed top z = %.4f m" % (stem, d.size, (pos[:, 2] + d / 2).max()))


if __name__ == "__main__":
    main()
