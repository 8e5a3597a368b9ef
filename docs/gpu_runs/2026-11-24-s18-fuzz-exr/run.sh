#!/usr/bin/env bash
# 16 libFuzzer workers of the exr target, 62,500 executions each, one shared corpus.
set -u
here=$(cd "$(dirname "$0")" && pwd)
out=${OUT:-/tmp/out}; mkdir -p "$out/findings" "$out/logs"
corpus=/tmp/exr_corpus; rm -rf "$corpus"; mkdir -p "$corpus"
run() { "$here/lib/ld-linux-x86-64.so.2" --library-path "$here/lib" "$here/fuzz_exr" "$@"; }
leaks=1
if run -runs=300 -artifact_prefix="$out/findings/" "$here/seed" 2>&1 | grep -q "LeakSanitizer has encountered a fatal error"; then leaks=0; fi
echo "detect_leaks=$leaks"; nproc; uname -a
export OMP_NUM_THREADS=1 ASAN_OPTIONS=detect_leaks=$leaks:allocator_may_return_null=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
start=$(date +%s)
for k in $(seq 1 16); do
  timeout 530 "$here/lib/ld-linux-x86-64.so.2" --library-path "$here/lib" "$here/fuzz_exr" -seed=$k -runs=62500 \
    -max_len=1048576 -rss_limit_mb=4096 -timeout=30 -artifact_prefix="$out/findings/" -print_final_stats=1 \
    "$corpus" "$here/seed" > "$out/logs/worker_$k.log" 2>&1 &
done
wait
echo "seconds $(( $(date +%s) - start ))"
total=0
for k in $(seq 1 16); do
  n=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$out/logs/worker_$k.log" | grep -o '[0-9]*$' || echo 0)
  echo "worker $k: ${n:-0} executions; $(grep -c 'ERROR\|SUMMARY\|deadly signal\|timeout' "$out/logs/worker_$k.log") error lines"
  total=$(( total + ${n:-0} ))
done
echo "total executions $total; corpus $(ls "$corpus" | wc -l) units; findings $(ls "$out/findings" | wc -l)"
