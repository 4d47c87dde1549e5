#!/usr/bin/python3
"""Bitwise comparison of two pastemix result files (model/output.h schema).

Every dataset and every attribute must have the same dtype, shape and bytes, except what measures the
machine rather than the physics: the /profile group (wall seconds per stage) and the root attributes
wall_seconds, steps_per_second and threads. Exit 0 when identical, 1 with the first differences listed.
Usage: compare_states.py A.h5 B.h5
"""
import sys

import h5py
import numpy as np

SKIP_GROUPS = ("profile",)
SKIP_ATTRS = {"wall_seconds", "steps_per_second", "threads"}


def same(a, b):
    a, b = np.asarray(a), np.asarray(b)
    if a.dtype.kind in "OSU" or b.dtype.kind in "OSU":
        return a.shape == b.shape and a.tolist() == b.tolist()
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def describe(a, b):
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape or a.dtype.kind not in "fiu":
        return "shape %s vs %s" % (a.shape, b.shape)
    diff = np.abs(a.astype(float) - b.astype(float))
    return "%d of %d values differ, max |diff| %.3g" % (np.count_nonzero(a != b), a.size, np.nanmax(diff))


def walk(f):
    items = {}
    f.visititems(lambda name, obj: items.__setitem__(name, obj))
    return items


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    problems = []
    with h5py.File(sys.argv[1], "r") as fa, h5py.File(sys.argv[2], "r") as fb:
        for key in sorted(set(fa.attrs) | set(fb.attrs)):
            if key in SKIP_ATTRS:
                continue
            if key not in fa.attrs or key not in fb.attrs:
                problems.append("attribute /%s only in one file" % key)
            elif not same(fa.attrs[key], fb.attrs[key]):
                problems.append("attribute /%s differs" % key)
        ia, ib = walk(fa), walk(fb)
        for name in sorted(set(ia) | set(ib)):
            if name.split("/")[0] in SKIP_GROUPS:
                continue
            if name not in ia or name not in ib:
                problems.append("/%s only in one file" % name)
                continue
            if isinstance(ia[name], h5py.Dataset):
                a, b = ia[name][()], ib[name][()]
                if not same(a, b):
                    problems.append("/%s: %s" % (name, describe(a, b)))
        n = len([k for k in ia if isinstance(ia[k], h5py.Dataset) and k.split("/")[0] not in SKIP_GROUPS])
    if problems:
        print("DIFFER: " + "; ".join(problems[:8]) + (" ..." if len(problems) > 8 else ""))
        sys.exit(1)
    print("identical (%d datasets)" % n)


if __name__ == "__main__":
    main()
