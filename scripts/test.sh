#!/usr/bin/env bash
# Builds pastemix and runs every test (doctest suites registered with CTest).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
ctest --test-dir build --output-on-failure -j "$(nproc)"
