#!/usr/bin/env bash
# Fuzzes every file reader (tests/fuzz, docs/dev/reliability.md): builds the fuzz preset (clang 14,
# libFuzzer, AddressSanitizer + UBSan), makes a seed corpus from files the programs write
# themselves, and runs each target.
#
#   tools/fuzz.sh [--runs N | --seconds S] [--cli PATH] [--jobs J] [TARGET...]
#
# --runs N: N executions per target (the recorded long run uses 1000000); --seconds S: S
# seconds per target (default 10: the short run the test suite makes); --cli: the hdrfusion
# program that writes the seed sequence, scan and project (default build-ci/app/hdrfusion;
# without it the corpus is the repository's own files only). Exits non-zero on the first
# finding; the input that caused it is kept in build-fuzz/findings/TARGET/. A summary line per
# target (executions, seconds, corpus size) goes to build-fuzz/fuzz-summary.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
runs="" seconds=10 cli="$root/build-ci/app/hdrfusion" targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --seconds) seconds="$2"; shift 2 ;;
    --cli) cli="$2"; shift 2 ;;
    --jobs) export CMAKE_BUILD_PARALLEL_LEVEL="$2"; shift 2 ;;
    -h|--help) sed -n '2,13p' "$0"; exit 0 ;;
    -*) echo "fuzz.sh: unknown option $1" >&2; exit 2 ;;
    *) targets+=("$1"); shift ;;
  esac
done
[ ${#targets[@]} -gt 0 ] || targets=(text_lists sensor_json options_json ply image exr project emor)
command -v clang++-14 >/dev/null || { echo "fuzz.sh: clang++-14 is missing (apt-get install clang libclang-rt-14-dev libomp-14-dev)" >&2; exit 1; }

cmake --preset fuzz >/dev/null
cmake --build --preset fuzz --target $(printf 'fuzz_%s ' "${targets[@]}")

build="$root/build-fuzz"
seed="$build/seed"
[ -d "$seed" ] || tools/fuzz_seeds.sh "$cli" "$seed"

summary="$build/fuzz-summary.txt"
: > "$summary"
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t"
  findings="$build/findings/$t"
  mkdir -p "$corpus" "$findings"
  limit=(-max_total_time="$seconds")
  [ -n "$runs" ] && limit=(-runs="$runs")
  log="$build/fuzz_$t.log"
  if [ -n "$runs" ]; then echo "fuzz.sh: $t ($runs runs)"; else echo "fuzz.sh: $t ($seconds s)"; fi
  start=$(date +%s)
  # One OpenMP thread: the engine's parallel loops (a project resumed into a session) cost
  # more to start than they save on the fuzzer's tiny inputs, and halve the executions.
  if ! OMP_NUM_THREADS=1 ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
      "$build/tests/fuzz/fuzz_$t" "${limit[@]}" -max_len=1048576 -rss_limit_mb=4096 -timeout=30 \
      -artifact_prefix="$findings/" -print_final_stats=1 "$corpus" "$seed/$t" >"$log" 2>&1; then
    tail -40 "$log" >&2
    echo "fuzz.sh: FINDING in $t: input kept in $findings/ (log $log)" >&2
    exit 1
  fi
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
  printf '%-14s %12s executions %6s s  corpus %s files\n' "$t" "$execs" "$(( $(date +%s) - start ))" \
    "$(ls "$corpus" | wc -l)" | tee -a "$summary"
done
