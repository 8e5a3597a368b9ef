#!/usr/bin/env bash
# session 38 (f): the photometric terms in two halves (7ff4b65): gpu tests; bench against 3d3e631 (PhotoTerm in one piece), three pairs
set -u
(cd _base/tree && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 6 --target hdrfusion-bench > /tmp/build_tree.txt 2>&1; echo "base build rc=$?") &
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=/tmp/gc tools/gpu_check.sh > /tmp/gc.txt 2>&1
echo "gpu_check rc=$?"; grep -E "tests passed|FAILED|Failure|Expected|Which is|error|scan parity:|place limit|Gauss-Newton level 0" /tmp/gc/ctest_gpu.txt | head -20
cp /tmp/gc/ctest_gpu.txt /tmp/gc/gpu_env.txt $OUT/
wait
S=_base/tree/build-gpu/app/bench/hdrfusion-bench
N=build-gpu/app/bench/hdrfusion-bench
for i in 1 2 3; do for t in S N; do b=${!t}
  $b --frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20 > /tmp/b_$t$i.txt 2>&1
  echo "== $t$i $(grep -E '^\| cuda \| compact \| 640x480 \| 20 mm \| [0-9]' /tmp/b_$t$i.txt | head -1 | awk -F'|' '{print "track", $8}')"; grep -A4 "not timed" /tmp/b_$t$i.txt | grep "^| cuda"
done; done
cp /tmp/b_N1.txt /tmp/b_S1.txt $OUT/
