#!/usr/bin/python3
"""Tolerance comparison of two pastemix results of one scene that differ only in the order of their force
sums (the spatial sort of the particle store, [neighbor] sort_every): a granular flow is chaotic, so the two
diverge from round-off on; what must agree are settled statistics.

  compare_settled.py state A.h5 B.h5     final snapshot: pair contacts, kinetic energy, centre-of-mass height
                                          and the height profile (share of the spheres per 5 mm layer)
  compare_settled.py maps A_maps.h5 B_maps.h5 [FLOOR_maps.h5]   `pastemix maps` outputs: C and rock mass per
                                          block; FLOOR: a third run that differs from A at round-off only

Tolerances (why): contacts within 2 % and KE within 5 % (the bench pour's and bed's contact counts and
energies move by ~1-4 % between two codes with the same physics, bench/README.md, and far less between
round-off-different runs of one code); z_com within 0.1 % and each layer's share within 0.5 percentage
points (a settled pile's shape, which chaos does not change); the mixing map's C within 0.1 percentage
points per block (issue 19), or, given FLOOR, within 1.5 x the difference between A and FLOOR where that is
larger: measured (2026-12-02, case 3 fast, 200 g of rock) four runs differing at round-off only (unsorted,
sorted every 4th, 8th, 16th rebuild) differ pairwise by 0.41-0.86 pp in their largest block, so 0.1 pp is
below what chaos alone gives at that rock mass and cannot separate a wrong sort from a right one. Exit 0
when all hold, 1 otherwise; prints every figure.
"""
import sys

import h5py
import numpy as np


def last(f):
    keys = sorted(k for k in f["snapshots"].keys() if k != "time")
    return f["snapshots"][keys[-1]]


def state(a_path, b_path):
    a, b = h5py.File(a_path, "r"), h5py.File(b_path, "r")
    sa, sb = last(a), last(b)
    ok = True
    if not np.array_equal(sa["id"][:], sb["id"][:]):
        print("ids differ (not the same particles in the same order)")
        return False

    def check(name, va, vb, rel):
        nonlocal ok
        d = abs(va - vb) / max(abs(va), 1e-300)
        good = d <= rel
        ok &= good
        print("%-22s %14.6g %14.6g  rel diff %.3g (tolerance %.3g) %s" % (name, va, vb, d, rel, "ok" if good else "FAIL"))

    ta, tb = a["timeseries"], b["timeseries"]
    check("pair contacts", float(ta["pair_contacts"][-1]), float(tb["pair_contacts"][-1]), 0.02)
    check("kinetic energy J", float(ta["kinetic"][-1]), float(tb["kinetic"][-1]), 0.05)
    ra, rb = sa["radius"][:], sb["radius"][:]
    ma, mb = ra ** 3, rb ** 3  # mass weights (one density)
    za, zb = sa["position"][:, 2], sb["position"][:, 2]
    check("z_com m", float((ma * za).sum() / ma.sum()), float((mb * zb).sum() / mb.sum()), 0.001)
    top = max(za.max(), zb.max())
    edges = np.arange(0.0, top + 0.005, 0.005)
    ha = np.histogram(za, edges)[0] / za.size * 100
    hb = np.histogram(zb, edges)[0] / zb.size * 100
    worst = np.abs(ha - hb).max()
    good = worst <= 0.5
    ok &= good
    print("height profile: %d layers of 5 mm, largest share difference %.3f pp (tolerance 0.5) %s"
          % (len(ha), worst, "ok" if good else "FAIL"))
    dx = np.abs(sa["position"][:] - sb["position"][:]).max()
    print("largest position difference of one sphere %.3g m (informative: chaos)" % dx)
    return ok


def map_diff(a_path, b_path):
    a, b = h5py.File(a_path, "r"), h5py.File(b_path, "r")
    ca, cb = 100.0 * a["blocks/C"][:], 100.0 * b["blocks/C"][:]
    both = np.isfinite(ca) & np.isfinite(cb)
    return np.abs(ca[both] - cb[both]).max() if both.any() else 0.0


def maps(a_path, b_path, floor_path=None):
    a, b = h5py.File(a_path, "r"), h5py.File(b_path, "r")
    ca, cb = 100.0 * a["blocks/C"][:], 100.0 * b["blocks/C"][:]  # fractions -> percent
    both = np.isfinite(ca) & np.isfinite(cb)
    same_nan = np.array_equal(np.isfinite(ca), np.isfinite(cb))
    worst = np.abs(ca[both] - cb[both]).max() if both.any() else 0.0
    ma, mb = a["blocks/rock_mass_kg"][:], b["blocks/rock_mass_kg"][:]
    print("C per block (pp): A %s" % np.array2string(ca.ravel(), precision=3, max_line_width=200))
    print("                  B %s" % np.array2string(cb.ravel(), precision=3, max_line_width=200))
    print("rock mass per block, largest difference %.4g g of %.4g g in all" % (1e3 * np.abs(ma - mb).max(), 1e3 * ma.sum()))
    issue = worst <= 0.1
    print("C: %d blocks, largest difference %.4f pp; issue 19's 0.1 pp: %s; same empty blocks: %s"
          % (both.sum(), worst, "ok" if issue else "NOT MET", same_nan))
    if floor_path is None:
        return same_nan and issue
    # The chaos floor: A against a third run that differs from A only at round-off too (another sort interval).
    floor = map_diff(a_path, floor_path)
    good = same_nan and worst <= max(0.1, 1.5 * floor)
    print("round-off floor: A against %s differs by %.4f pp; tolerance max(0.1, 1.5 x floor) = %.4f pp -> %s"
          % (floor_path, floor, max(0.1, 1.5 * floor), "ok" if good else "FAIL"))
    return good


if __name__ == "__main__":
    if len(sys.argv) not in (4, 5) or sys.argv[1] not in ("state", "maps") or (sys.argv[1] == "state" and len(sys.argv) == 5):
        print(__doc__)
        sys.exit(2)
    sys.exit(0 if (state if sys.argv[1] == "state" else maps)(*sys.argv[2:]) else 1)
