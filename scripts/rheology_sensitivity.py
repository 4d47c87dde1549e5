#!/usr/bin/env python3
"""The issue-15 sensitivity table (docs/rheology_protocol.md step 8): case 2 at the calibrated shape b with eta_B
x F, from docs/studies/rheology_sensitivity.csv (rows of `pastemix calibrate rheology --refine 0 --eta-factor F`).

Per factor: per-layer rock (g, mean +- sd over seeds), the objective J = (1/3) sum ((M_k - L_k)/L_k)^2 of the
seed means, the deep share, and the headline score: layers matched under analysis/score's tolerance
max(15 % of the lab layer, 2 model sd, 10 g). The lab targets are case 2's layers (sum of M_wr per layer, lab.h5).
Usage: scripts/rheology_sensitivity.py [LEDGER] [--lab 703.80,182.80,77.50]
"""
import csv
import re
import statistics
import sys
from pathlib import Path


def main(argv):
    ledger = Path(argv[0]) if argv and not argv[0].startswith("--") else Path("docs/studies/rheology_sensitivity.csv")
    lab = [703.80, 182.80, 77.50]  # g, case 2 (docs/studies/rheology_case2/table.txt, from lab.h5)
    if "--lab" in argv:
        lab = [float(x) for x in argv[argv.index("--lab") + 1].split(",")]
    groups = {}
    with ledger.open() as f:
        for row in csv.DictReader(f):
            m = re.match(r"shape ([0-9.]+)(?: eta x ([0-9.]+))? seed (\d+)", row["task"])
            if not m or row["status"] != "done":
                continue
            q = [1e3 * float(x) for x in row["qoi"].split()]
            groups.setdefault(float(m.group(2) or 1), {})[int(m.group(3))] = q
    lab_deep = 100 * (lab[1] + lab[2]) / sum(lab)
    print(f"case 2, lab layers {lab[0]:.1f} / {lab[1]:.1f} / {lab[2]:.1f} g, lab deep share {lab_deep:.1f} %")
    print("eta_B x | seeds | layer 1 g | layer 2 g | layer 3 g | J | deep % | layers matched | change of score vs x1")
    base = None
    for fac, seeds in sorted(groups.items(), key=lambda kv: (kv[0] != 1, kv[0])):
        cols = list(zip(*seeds.values()))
        mean = [statistics.mean(c) for c in cols]
        sd = [statistics.stdev(c) if len(c) > 1 else 0.0 for c in cols]
        j = sum(((m - l) / l) ** 2 for m, l in zip(mean, lab)) / 3
        deep = statistics.mean(100 * (s[1] + s[2]) / sum(s) for s in seeds.values())
        ok = sum(abs(m - l) <= max(0.15 * l, 2 * s, 10.0) for m, s, l in zip(mean, sd, lab))
        if base is None:
            base = (ok, j, deep)
        cells = " | ".join(f"{m:.1f} +- {s:.1f}" for m, s in zip(mean, sd))
        print(f"{fac:g} | {len(seeds)} | {cells} | {j:.4f} | {deep:.1f} | {ok}/3 | "
              f"{ok - base[0]:+d} layers, J {j - base[1]:+.4f}, deep {deep - base[2]:+.1f} pp")


if __name__ == "__main__":
    main(sys.argv[1:])
