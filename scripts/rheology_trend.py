#!/usr/bin/env python3
"""The issue-15 trend table across the mixing cases (docs/rheology_protocol.md step 7), from the band ledger.

Reads docs/studies/rheology_band.csv (rows of `pastemix predict rheology`), keeps the finished rows of the band
(the engine named in --engine; rows of the 5 s limit are told apart by their key, so give --keys-from to a
band.csv/runs.csv if needed), and prints per case and shape value: solids content, rock size, fall height (from
the scene files), seeds, per-layer rock (g), deep share (%), mixed/unmixed (g), MAE (pp), mean +- sd over seeds.
Cases 6 and 7 have no lab grid (blind validation): their rows have no score and the MAE column says so.
Usage: scripts/rheology_trend.py [LEDGER] [--scenes datasets/scenes] [--skip KEY,KEY]
"""
import csv
import re
import statistics
import sys
from pathlib import Path

NAMES = ["layer1_kg", "layer2_kg", "layer3_kg", "deep_share", "mixed_kg", "unmixed_kg", "score_layers", "mae_pp"]


def scene_facts(scenes, case):
    """Solids fraction, rock d range (mm) and the fall height line of a case's scene header."""
    text = (scenes / f"mixing_case{case}.toml").read_text()
    cw = re.search(r"^solids_fraction\s*=\s*([0-9.]+)", text, re.M)
    dmin = re.findall(r"^d_min\s*=\s*([0-9.e-]+)", text, re.M)
    dmax = re.findall(r"^d_max\s*=\s*([0-9.e-]+)", text, re.M)
    fall = re.search(r"H_f = (\d+(?:\.\d+)?) cm", text)
    d = f"{1e3 * min(map(float, dmin)):g}-{1e3 * max(map(float, dmax)):g}" if dmin and dmax else "?"
    return (float(cw.group(1)) * 100 if cw else float("nan"), d, fall.group(1) if fall else "?")


def main(argv):
    ledger = Path(argv[0]) if argv and not argv[0].startswith("--") else Path("docs/studies/rheology_band.csv")
    scenes = Path("datasets/scenes")
    skip = set()
    for i, a in enumerate(argv):
        if a == "--scenes":
            scenes = Path(argv[i + 1])
        if a == "--skip":
            skip = set(argv[i + 1].split(","))
    groups = {}
    with ledger.open() as f:
        for row in csv.DictReader(f):
            m = re.match(r"case (\d+) (\w+) = ([0-9.]+) seed (\d+)", row["task"])
            if not m or row["status"] != "done" or row["key"] in skip:
                continue
            q = [float(x) for x in row["qoi"].split()]
            # Cases without a lab grid (6, 7: reserved for blind validation) carry no score: 6 values, not 8.
            if len(q) not in (len(NAMES) - 2, len(NAMES)):
                raise SystemExit(f"{ledger}: task {row['task']}: {len(q)} values, not {len(NAMES)} (or {len(NAMES) - 2} without a lab grid)")
            key = (int(m.group(1)), float(m.group(3)))
            groups.setdefault(key, {})[int(m.group(4))] = q  # a seed's last row wins (a rerun of the same run)
    print("case | C_w % | rock mm | H_f cm | b | seeds | layer 1 g | layer 2 g | layer 3 g | deep % | mixed g | unmixed g | MAE pp")
    for (case, b), seeds in sorted(groups.items()):
        cw, d, fall = scene_facts(scenes, case)
        cols = list(zip(*seeds.values()))

        def ms(i, scale):
            v = [x * scale for x in cols[i]]
            sd = statistics.stdev(v) if len(v) > 1 else float("nan")
            return f"{statistics.mean(v):.1f} +- {sd:.1f}"

        print(f"{case} | {cw:.1f} | {d} | {fall} | {b:.5g} | {len(seeds)} | {ms(0, 1e3)} | {ms(1, 1e3)} | {ms(2, 1e3)} | "
              f"{ms(3, 100)} | {ms(4, 1e3)} | {ms(5, 1e3)} | {ms(7, 1) if len(cols) == len(NAMES) else 'blind (no lab grid)'}")


if __name__ == "__main__":
    main(sys.argv[1:])
