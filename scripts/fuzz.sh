#!/usr/bin/env bash
# Fuzzes every parser of user input with libFuzzer under AddressSanitizer + UBSan (issue 20).
#
#   scripts/fuzz.sh [SECONDS] [TARGET ...]   # default 60 s each: csv params manifest scene block_id
#   scripts/fuzz.sh --minimize               # merge what the runs found into the committed corpus
#
# Builds build-fuzz/ with clang (-DPASTEMIX_FUZZ=ON; the normal build does not need clang), seeds each target
# from its committed corpus fuzz/corpus/NAME (taken from datasets/), writes new inputs to
# build-fuzz/corpus/NAME and crashes to build-fuzz/crashes/. Not part of scripts/test.sh or CTest.
# Runs at nice 19: on a shared machine it only takes idle CPU. Exit 1 if any target found a crash.
set -euo pipefail
cd "$(dirname "$0")/.."
all=(csv params manifest scene block_id)
minimize=0
if [ "${1:-}" = "--minimize" ]; then minimize=1; shift; fi
secs=${1:-60}
[ $# -gt 0 ] && shift
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=("${all[@]}")
command -v clang++ >/dev/null || { echo "fuzz: needs clang (apt-get install clang libclang-rt-dev)"; exit 2; }
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
  -DCMAKE_CXX_COMPILER=clang++ -DPASTEMIX_FUZZ=ON -DPASTEMIX_BUILD_TESTS=OFF >/dev/null
nice -n 19 cmake --build build-fuzz --target "${targets[@]/#/fuzz_}"
mkdir -p build-fuzz/crashes
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
status=0
for t in "${targets[@]}"; do
  mkdir -p "build-fuzz/corpus/$t" "fuzz/corpus/$t"
  if [ $minimize -eq 1 ]; then
    rm -rf "build-fuzz/min-$t" && mkdir -p "build-fuzz/min-$t"
    nice -n 19 "build-fuzz/fuzz/fuzz_$t" -merge=1 -timeout=10 -rss_limit_mb=2048 \
      "build-fuzz/min-$t" "fuzz/corpus/$t" "build-fuzz/corpus/$t" 2>&1 | tail -1
    rm -rf "fuzz/corpus/$t" && mv "build-fuzz/min-$t" "fuzz/corpus/$t"
    echo "fuzz: $t corpus: $(ls "fuzz/corpus/$t" | wc -l) files"
    continue
  fi
  log="build-fuzz/fuzz_$t.log"
  # Keys, table names, --set paths and odd numbers of the format, so mutations reach past the first error.
  dict=()
  [ -f "fuzz/dict/$t.dict" ] && dict=(-dict="fuzz/dict/$t.dict")
  set +e
  # -timeout is wall-clock: at nice 19 on a loaded machine an input can wait minutes for a core, and a
  # 10 s limit then reports starved runs as hangs (seen: "timeout" and "slow-unit" inputs that run in
  # 0.02 s of CPU). Re-run any timeout input alone before calling it a hang.
  nice -n 19 "build-fuzz/fuzz/fuzz_$t" -max_total_time="$secs" -timeout=300 -report_slow_units=300 \
    -rss_limit_mb=2048 -max_len=8192 "${dict[@]}" \
    -print_final_stats=1 -artifact_prefix="build-fuzz/crashes/$t-" "build-fuzz/corpus/$t" "fuzz/corpus/$t" >"$log" 2>&1
  rc=$?
  set -e
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
  if [ $rc -ne 0 ]; then
    status=1
    echo "fuzz: $t: FOUND A CRASH (exit $rc) after $execs runs; see $log and build-fuzz/crashes/$t-*"
  else
    echo "fuzz: $t: $execs runs in $secs s, no crash"
  fi
done
exit $status
