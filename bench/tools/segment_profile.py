#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""The stage profile of a resumed pastemix run's own segment: the run's profile (its log) minus the one
stored in the checkpoint it resumed (model/checkpoint.cpp world_state: tag, t, t_at_rebuild, steps,
started, escaped mass, then Profile: 8 stage seconds, rebuilds, sorts).
Usage: segment_profile.py CHECKPOINT.h5 RUN.log SEGMENT_SECONDS LABEL"""
import re
import struct
import sys

import h5py

NAMES = "kick_drift neighbor contact_forces walls kick fluid wait output".split()


def stored_profile(path):
    b = bytes(h5py.File(path, "r")["/checkpoint/state"][()])
    n = struct.unpack_from("<Q", b, 0)[0]
    o = 8 + n + 24 + 1 + 8  # tag, t, t_at_rebuild, steps, started, escaped mass
    return dict(zip(NAMES, struct.unpack_from("<8d", b, o)))


def main():
    ck, log, length, label = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4]
    text = open(log).read()
    total = {m.group(1): float(m.group(2)) for m in re.finditer(r"^\s+(\w+)\s+([\d.]+) s\s", text, re.M)}
    missing = [k for k in NAMES if k not in total]
    if missing:
        sys.exit(f"segment_profile: {log} has no stage profile line for {', '.join(missing)}")
    base = stored_profile(ck)
    seg = {k: total[k] - base[k] for k in NAMES}
    loop = sum(seg.values()) - seg["output"]
    print(f"{label}: loop {loop:.1f} s over {length:g} simulated s = {loop / length:.1f} s per simulated s")
    print("  " + "  ".join(f"{k} {v:.1f} s ({100 * v / loop:.0f} %)" for k, v in seg.items() if k != "output"))


if __name__ == "__main__":
    main()
