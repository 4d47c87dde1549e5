#!/usr/bin/env bash
# Configures (Release, Ninja) and builds pastemix into build/. Extra arguments go to cmake's configure step,
# e.g. scripts/build.sh -DPASTEMIX_SANITIZE=ON.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build build -j "$(nproc)"
