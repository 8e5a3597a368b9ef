#!/usr/bin/env bash
set -u
mkdir -p $OUT/gc
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=$OUT/gc tools/gpu_check.sh > $OUT/gc_stdout.txt 2>&1
echo "gpu_check rc=$?" >> $OUT/gc_stdout.txt
for i in 1 2; do for c in 640x480x20 320x240x20; do echo "== final $c run $i" >> $OUT/bench.txt; build-gpu/app/bench/hdrfusion-bench --frames 200 --device cuda --voxel compact --case $c >> $OUT/bench.txt 2>&1; done; done
grep -E "^== |^\| cuda \| compact \| [0-9x]+ \| 20 mm \| [0-9.]+ \| [0-9.]+ \| [0-9.]+ \|" $OUT/bench.txt
