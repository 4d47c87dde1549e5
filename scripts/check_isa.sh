#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Compiles the engine's vector code for the instruction-set levels this build did not choose, so that a
# change which breaks a form this CPU cannot run still fails a test here (issue 19: the CI machine is an
# AVX2-only Zen 3, so the AVX-512 lanes of pair_filter.h, kick_block.h, wall_batch.h, field.h, neighbor.cpp and
# collective.cpp are never compiled by its build, and an AVX-512 build would never compile the AVX2 ones).
#   scripts/check_isa.sh [BUILD_DIR] [JOBS]
# For each translation unit below it takes the build's own compile command (BUILD_DIR/compile_commands.json),
# replaces the engine's -march with x86-64-v4, x86-64-v3 and the compiler's default (no -march) in turn, skips
# the level the build used, and compiles to a scratch object (nothing in BUILD_DIR is written). Prints one
# line per level and exits non-zero with the compiler's messages if any compile fails or warns.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-$ROOT/build}
JOBS=${2:-$(nproc)}
DB="$BUILD/compile_commands.json"
[[ -f "$DB" ]] || { echo "check_isa: $DB not found (configure the build first)" >&2; exit 2; }
# The translation units whose code has an AVX-512, an AVX2 and a scalar form (by #if on __AVX512F__ /
# PASTEMIX_AVX2_LANES), directly or through the inline kernels of the headers they include.
UNITS=(model/contacts.cpp model/contacts_partition.cpp model/neighbor.cpp model/wall_contacts.cpp model/world.cpp
       model/fluid/collective.cpp model/fluid/field.cpp
       tests/model/pair_filter_test.cpp tests/model/kick_block_test.cpp tests/model/wall_batch_test.cpp
       tests/model/fluid/asin_poly_test.cpp tests/model/fluid/field_kick8_test.cpp)
SCRATCH=$(mktemp -d)
trap 'rm -rf "$SCRATCH"' EXIT
# One shell command per (unit, level): the build's command with its -march, output and dependency flags
# replaced. Python's json module reads the database (the commands hold quoted defines).
/usr/bin/env python3 - "$DB" "$ROOT" "$SCRATCH" "${UNITS[@]}" <<'EOF'
import json, os, re, shlex, sys
db, root, scratch, units = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
entries = {os.path.realpath(e["file"]): e for e in json.load(open(db))}
levels = ["x86-64-v4", "x86-64-v3", ""]
jobs = []
for u in units:
    e = entries.get(os.path.realpath(os.path.join(root, u)))
    if e is None:
        sys.exit(f"check_isa: {u} is not in {db}")
    args = shlex.split(e["command"]) if "command" in e else e["arguments"]
    used = [a for a in args if a.startswith("-march=")]
    if not used:
        sys.exit(f"check_isa: {u} is built without the engine's -march (is PASTEMIX_MODEL_ARCH empty?)")
    base, skip = [], False
    for a in args:
        if skip:
            skip = False
            continue
        if a in ("-o", "-MF", "-MT"):
            skip = True
            continue
        if a.startswith("-march=") or a in ("-MD", "-MMD"):
            continue
        base.append(a)
    for lv in levels:
        if "-march=" + lv in used:
            continue
        tag = (lv or "default") + "_" + re.sub(r"[^A-Za-z0-9]", "_", u)
        cmd = base[:1] + ([f"-march={lv}"] if lv else []) + base[1:] + ["-Werror", "-o", os.path.join(scratch, tag + ".o")]
        jobs.append(f"cd {shlex.quote(e['directory'])} && {shlex.join(cmd)} > {shlex.quote(os.path.join(scratch, tag + '.log'))} 2>&1 || echo {shlex.quote(tag)} >> {shlex.quote(os.path.join(scratch, 'failed'))}")
with open(os.path.join(scratch, "jobs"), "w") as f:
    f.write("\0".join(jobs) + "\0")
print(f"check_isa: {len(jobs)} compiles ({len(units)} units at the levels the build did not use)")
EOF
xargs -0 -P "$JOBS" -I{} bash -c '{}' < "$SCRATCH/jobs"
if [[ -f "$SCRATCH/failed" ]]; then
  while read -r tag; do echo "check_isa: FAILED $tag"; sed -n 1,40p "$SCRATCH/$tag.log"; done < "$SCRATCH/failed"
  exit 1
fi
for lv in x86-64-v4 x86-64-v3 default; do
  n=$(ls "$SCRATCH" | grep -c "^${lv}_.*\.o$" || true)
  [[ $n -gt 0 ]] && echo "check_isa: $lv: $n units compiled without error or warning"
done
exit 0
