#!/usr/bin/env bash
# session 41 (d): the GPU's ray cast in two passes (RaycastInTwoPasses): gpu tests and
# recovery_tests on CUDA, then the bench at 640x480 and 320x240 against 9e080ab (_base/tree),
# alternating, three rounds.
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
( cd _base/tree && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 6 --target hdrfusion-bench > /tmp/build_base.txt 2>&1; echo "base build rc=$?" ) &
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=/tmp/gc tools/gpu_check.sh > /tmp/gc.txt 2>&1; echo "gpu_check rc=$?"
grep -E "tests passed|FAILED|Failure|Expected|Which is|scan parity:|volume:|raycast" /tmp/gc/ctest_gpu.txt | head -20
cp /tmp/gc/ctest_gpu.txt /tmp/gc/gpu_env.txt $OUT/
cmake --build --preset core-gpu -j 10 --target recovery_tests hdrfusion-bench > /tmp/build_rec.txt 2>&1; echo "recovery build rc=$?"
wait
HDRF_TEST_DEVICE=cuda timeout 250 build-gpu/tests/recovery_tests > $OUT/recovery_cuda.txt 2>&1; echo "recovery_tests on cuda rc=$?"; grep -E "PASSED|FAILED|Failure" $OUT/recovery_cuda.txt | head
declare -A B=([base]=_base/tree/build-gpu/app/bench/hdrfusion-bench [two]=build-gpu/app/bench/hdrfusion-bench)
for i in 1 2 3; do
  for v in base two; do
    ${B[$v]} --frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20 > /tmp/b_${v}_$i.txt 2>&1
    grep -E '^\| cuda \| compact \| [0-9]+x[0-9]+ \| [0-9]+ \| [0-9.]+ \| raycast \|' /tmp/b_${v}_$i.txt | cut -d'|' -f4,8,12 | tr '\n' ' ' | sed "s/^/== $v $i raycast:/"; echo
    grep -A5 'not timed' /tmp/b_${v}_$i.txt | grep '^| cuda' | cut -d'|' -f4,6-9 | sed "s/^/== $v $i not timed:/"
  done
done
cp /tmp/b_base_1.txt /tmp/b_two_1.txt /tmp/b_two_3.txt $OUT/
