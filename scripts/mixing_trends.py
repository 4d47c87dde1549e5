#!/usr/bin/python3
"""Trends across the chapter-3 mixing cases: lab vs model, from `pastemix score` outputs (score.toml).

Usage: /usr/bin/python3 scripts/mixing_trends.py CASE=SCORE_TOML [CASE=SCORE_TOML ...] [--program CSV]

The trend measure is the deep share: rock in layers 2-3 over rock in all 36 blocks (the lab's "penetration").
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
    print("| case | solids % | rock mm | H_f cm | N | MAE C pp | lab deep share % | model deep share % "
          "| model unmixed kg | cone lab / model |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for case, path in sorted(pairs):
        with open(path, "rb") as f:
            s = tomllib.load(f)
        if s["case"] != case:
            sys.exit(f"mixing_trends: {path} scores case {s['case']}, not {case}")
        p = prog[case]
        r = s["rock_mass_kg"]
        n = s["realizations"]
        sd = f" +- {100 * r['model_deep_share_sd']:.1f}" if n > 1 else ""
        usd = f" +- {r['unmixed_sd']:.3f}" if n > 1 else ""
        cone = s["unmixed_cone"]
        print(f"| {case} | {p['paste_solids_content_percent']} | {p['d_wr_min_mm']}-{p['d_wr_max_mm']} "
              f"| {p['falling_height_cm']} | {n} | {s['score']['C_mean_abs_error_pp']:.2f} "
              f"| {100 * r['lab_deep_share']:.1f} | {100 * r['model_deep_share']:.1f}{sd} "
              f"| {r['unmixed']:.3f}{usd} | {'yes' if cone['lab_has_cone'] else 'no'} / "
              f"{'yes' if cone['model_has_cone'] else 'no'} |")


if __name__ == "__main__":
    main(sys.argv[1:])
