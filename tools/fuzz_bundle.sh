#!/usr/bin/env bash
# Packs fuzz targets to run on another Linux machine with more cores (the GPU machine's CPUs:
# `device` carries build-fuzz/bundle there), without Debian's libraries installed:
#
#   tools/fuzz_bundle.sh TARGET...          (e.g. exr; default: exr text_lists sensor_json options_json ply)
#   # there:  RUNS=62500 WORKERS=16 build-fuzz/bundle/run.sh exr   (findings and logs in $OUT)
#
# Each target is relinked with --as-needed, so it needs only the libraries it calls, stripped of
# its line tables, and goes
# with them, this machine's dynamic loader (so the other machine's C library does not matter)
# and its seed corpus. Targets whose libraries come to more than 48 MB (OpenCV's image codecs
# pull in GDAL: image, project) are refused: the device carries 64 MB at most.
set -euo pipefail
cd "$(dirname "$0")/.."
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(exr text_lists sensor_json options_json ply)
out=build-fuzz/bundle
rm -rf "$out"
mkdir -p "$out/lib" "$out/seed"
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz --target $(printf 'fuzz_%s ' "${targets[@]}")
[ -d build-fuzz/seed ] || tools/fuzz_seeds.sh build-ci/app/hdrfusion build-fuzz/seed
for t in "${targets[@]}"; do
  link=$(cd build-fuzz && ninja -t commands "tests/fuzz/fuzz_$t" | tail -1)
  (cd build-fuzz && eval "${link/-o tests\/fuzz\/fuzz_$t/-Wl,--as-needed -o bundle/fuzz_$t}")
  # Without line tables (reports still name functions; a finding's input comes back and is
  # replayed here with them).
  strip --strip-debug "$out/fuzz_$t"
  for l in $(ldd "$out/fuzz_$t" | awk '$3 ~ /^\// {print $3}'); do cp -Lu "$l" "$out/lib/"; done
  cp -r "build-fuzz/seed/$t" "$out/seed/$t"
done
cp -L "$(ldd "$out/fuzz_${targets[0]}" | awk '/ld-linux/ {print $1}')" "$out/lib/ld-linux.so"
size=$(du -sm "$out" | cut -f1)
if [ "$size" -gt 48 ]; then
  echo "fuzz_bundle: $out is $size MB, more than the 48 MB a device run can carry; leave out image and project" >&2
  exit 1
fi
cat > "$out/run.sh" <<'RUN'
#!/usr/bin/env bash
# WORKERS libFuzzer workers (default: the cores) of TARGET on one shared corpus, RUNS
# executions each (default 62500: 10^6 in all with 16), leak detection on. Prints the total.
set -u
t=${1:?target}; here=$(cd "$(dirname "$0")" && pwd)
out=${OUT:-/tmp/fuzz-out}; mkdir -p "$out/findings/$t" "$out/logs"
workers=${WORKERS:-$(nproc)}; runs=${RUNS:-62500}
corpus=/tmp/fuzz-corpus/$t; mkdir -p "$corpus"
export OMP_NUM_THREADS=1 ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
start=$(date +%s)
for k in $(seq 1 "$workers"); do
  "$here/lib/ld-linux.so" --library-path "$here/lib" "$here/fuzz_$t" -seed="$k" -runs="$runs" -max_len=1048576 \
    -rss_limit_mb=4096 -timeout=30 -artifact_prefix="$out/findings/$t/" -print_final_stats=1 \
    "$corpus" "$here/seed/$t" > "$out/logs/${t}_$k.log" 2>&1 &
done
wait
total=0 slowest=0
for k in $(seq 1 "$workers"); do
  n=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$out/logs/${t}_$k.log" | grep -o '[0-9]*$' || echo 0)
  s=$(grep -o 'stat::slowest_unit_time_sec: *[0-9]*' "$out/logs/${t}_$k.log" | grep -o '[0-9]*$' || echo 0)
  total=$((total + ${n:-0})); [ "${s:-0}" -gt "$slowest" ] && slowest=$s
done
findings=$(ls "$out/findings/$t" | wc -l)
echo "$t: $total executions in $(( $(date +%s) - start )) s by $workers workers; corpus $(ls "$corpus" | wc -l); slowest input ${slowest} s; findings $findings"
[ "$findings" -eq 0 ]
RUN
chmod +x "$out/run.sh"
echo "fuzz_bundle: $out ($size MB): $(printf '%s ' "${targets[@]}")"
