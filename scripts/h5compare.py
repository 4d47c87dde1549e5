#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# Compares two pastemix result files bit for bit (what h5diff would do, without hdf5-tools): every dataset and
# every attribute of every group, byte for byte. Wall-clock entries (the /profile group's seconds, rates and
# thread count, the run's wall time) are listed apart and do not count. Exit 0 if equal, 1 otherwise.
#   /usr/bin/python3 scripts/h5compare.py A.h5 B.h5
import sys

import h5py
import numpy as np

WALL = ("wall", "seconds", "per_second", "threads", "steps_per_s", "_s_per_", "created", "utc", "time_of_run")


def is_wall(path, name=""):
    p = (path + "/" + name).lower()
    return p.startswith("/profile") or any(w in name.lower() for w in WALL)


def same_value(a, b):
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape or a.dtype != b.dtype:
        return False
    if a.dtype.kind in "fiub":
        return a.tobytes() == b.tobytes()
    return a.tolist() == b.tolist()


def walk(f, out, path="/"):
    node = f[path]
    for k, v in node.attrs.items():
        out[("attr", path, k)] = v
    if isinstance(node, h5py.Group):
        for k in node.keys():
            walk(f, out, (path.rstrip("/") + "/" + k))
    else:
        out[("data", path, "")] = node[()]


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: h5compare.py A.h5 B.h5")
    ea, eb = {}, {}
    with h5py.File(sys.argv[1], "r") as a, h5py.File(sys.argv[2], "r") as b:
        walk(a, ea)
        walk(b, eb)
    diff, wall, n = [], [], 0
    for key in sorted(set(ea) | set(eb)):
        kind, path, name = key
        if key not in ea or key not in eb:
            diff.append(f"{kind} {path} {name}: only in {'B' if key not in ea else 'A'}")
            continue
        n += 1
        if not same_value(ea[key], eb[key]):
            (wall if is_wall(path, name) else diff).append(f"{kind} {path} {name}")
    print(f"{n} entries compared; {len(diff)} differ; {len(wall)} wall-clock entries differ (not counted)")
    for d in diff[:40]:
        print("  DIFFERS:", d)
    for w in wall:
        print("  wall-clock:", w)
    sys.exit(1 if diff else 0)


if __name__ == "__main__":
    main()
