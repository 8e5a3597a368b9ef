#!/usr/bin/env bash
# session 35: GPU checks of the tree (review mend) and the recovery tests on the CUDA backend
set -u
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=$OUT/gc tools/gpu_check.sh > $OUT/gc.txt 2>&1
echo "gpu_check rc=$?"; grep -E "tests passed|FAILED|Failure|Expected|Which is|error|parity:" $OUT/gc/ctest_gpu.txt | head -20
HDRF_TEST_DEVICE=cuda timeout 400 build-gpu/tests/recovery_tests > $OUT/recovery_cuda.txt 2>&1
echo "recovery_tests on cuda rc=$?"
grep -E "^(uninterrupted|covered|joined|blank first|fast clock|real clock|smooth|flicker|degraded)|OK \]|FAILED|Failure" $OUT/recovery_cuda.txt | cut -c1-200
for c in 640x480x20 320x240x20; do build-gpu/app/bench/hdrfusion-bench --frames 200 --device cuda --voxel compact --case $c > $OUT/b_$c.txt 2>&1; grep -A3 "not timed" $OUT/b_$c.txt | tail -1; done
rm -f $OUT/gc/build.txt
