#!/usr/bin/python3
"""Trends across the chapter-3 mixing cases: lab vs model, from `pastemix score` outputs (score.toml).

Usage: /usr/bin/python3 scripts/mixing_trends.py CASE=SCORE_TOML [CASE=SCORE_TOML ...] [--program CSV]

The headline columns (per-layer rock, matched layers Y/n, deep share, cone) come first; the trend measure is the deep share: rock in layers 2-3 over rock in all 36 blocks (the lab's "penetration").
Table 3.1's factors per case (solids content, rock size, falling height) come from the program CSV, so the
reader sees which factor each pair of cases varies. Prints a Markdown table; nothing is fitted or tuned.
"""
import csv
import sys
import tomllib


def main(argv):
    program = "datasets/thesis/mixing_tests_program.csv"
    pairs = []
    args = iter(argv)
    for a in args:
        if a == "--program":
            program = next(args)
        elif "=" in a:
            case, path = a.split("=", 1)
            pairs.append((int(case), path))
        else:
            sys.exit(f"mixing_trends: expected CASE=SCORE_TOML, got {a!r}")
    if not pairs:
        sys.exit(__doc__)
    with open(program, newline="") as f:
        prog = {int(r["case"]): r for r in csv.DictReader(f)}
    print("| case | solids % | rock mm | H_f cm | N | layer 1 / 2 / 3 rock kg lab | model | matched "
          "| lab deep share % | model deep share % | cone lab / model | MAE C pp | end s | moving g |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for case, path in sorted(pairs):
        with open(path, "rb") as f:
            s = tomllib.load(f)
        if s["case"] != case:
            sys.exit(f"mixing_trends: {path} scores case {s['case']}, not {case}")
        p = prog[case]
        h = s["headline"]
        n = s["realizations"]
        sd = f" +- {100 * h['model_deep_share_sd']:.1f}" if n > 1 else ""
        lab = " / ".join(f"{x:.3f}" for x in h["lab_layer_rock_kg"])
        if n > 1:
            model = " / ".join(f"{m:.3f}+-{d:.3f}" for m, d in zip(h["model_layer_rock_kg"], h["model_layer_rock_sd_kg"]))
        else:
            model = " / ".join(f"{m:.3f}" for m in h["model_layer_rock_kg"])
        ok = "".join("Y" if m else "n" for m in h["layer_matched"])
        reals = s.get("realization", [])
        ends = [r["time_s"] for r in reals]
        moving = [1e3 * r.get("moving_mass_kg", float("nan")) for r in reals]
        end = f"{min(ends):.2f}-{max(ends):.2f}" if len(ends) > 1 else f"{ends[0]:.2f}"
        mov = f"<= {max(moving):.2f}" if len(moving) > 1 else f"{moving[0]:.2f}"
        state = "" if h["state"] == "at rest" else " (NOT AT REST)"
        print(f"| {case}{state} | {p['paste_solids_content_percent']} | {p['d_wr_min_mm']}-{p['d_wr_max_mm']} "
              f"| {p['falling_height_cm']} | {n} | {lab} | {model} | {ok} "
              f"| {100 * h['lab_deep_share']:.1f} | {100 * h['model_deep_share']:.1f}{sd} "
              f"| {'yes' if h['cone_lab'] else 'no'} / {'yes' if h['cone_model'] else 'no'} "
              f"| {s['score']['C_mean_abs_error_pp']:.2f} | {end} | {mov} |")

if __name__ == "__main__":
    main(sys.argv[1:])
