#!/usr/bin/env bash
# Builds pastemix and runs every test (doctest suites registered with CTest).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
# Threads sleep at barriers instead of spinning: on a shared or loaded machine spinning OpenMP threads
# starve each other (the determinism tests run 2 threads). Tests make no speed claims.
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
ctest --test-dir build --output-on-failure -j "$(nproc)"
