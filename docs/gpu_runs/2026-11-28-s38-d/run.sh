#!/usr/bin/env bash
# session 38 (d): the session's final tree (2f6014c): gpu tests, the bench at 640x480 and 320x240 four times
set -u
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=/tmp/gc tools/gpu_check.sh > /tmp/gc.txt 2>&1
echo "gpu_check rc=$?"; grep -E "tests passed|FAILED|Failure|Expected|Which is|error|scan parity:|place limit" /tmp/gc/ctest_gpu.txt | head -30
cp /tmp/gc/ctest_gpu.txt /tmp/gc/gpu_env.txt $OUT/
N=build-gpu/app/bench/hdrfusion-bench
for i in 1 2 3 4; do
  $N --frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20 > /tmp/b_$i.txt 2>&1
  echo "== $i"; grep -A4 "not timed" /tmp/b_$i.txt | grep "^| cuda"
done
cp /tmp/b_1.txt $OUT/
