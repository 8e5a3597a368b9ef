#!/usr/bin/env bash
# session 41 (h): the review mend (the pixel's ray made once, handed to the walk and the shading): gpu tests, recovery_tests on CUDA, the
# bench at 640x480 and 320x240 twice.
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=/tmp/gc tools/gpu_check.sh > /tmp/gc.txt 2>&1; echo "gpu_check rc=$?"
grep -E "tests passed|FAILED|Failure|Expected|Which is|scan parity:" /tmp/gc/ctest_gpu.txt | head -8
grep -cE "raycast: vertex 0 \(0% of pixels differ\) radiance 0 depth 0" /tmp/gc/ctest_gpu.txt
cp /tmp/gc/ctest_gpu.txt /tmp/gc/gpu_env.txt $OUT/
cmake --build --preset core-gpu -j 16 --target recovery_tests hdrfusion-bench > /tmp/build_rec.txt 2>&1; echo "recovery build rc=$?"
HDRF_TEST_DEVICE=cuda timeout 250 build-gpu/tests/recovery_tests > $OUT/recovery_cuda.txt 2>&1; echo "recovery_tests on cuda rc=$?"; grep -E "PASSED|FAILED|Failure" $OUT/recovery_cuda.txt | head
for i in 1 2; do
  build-gpu/app/bench/hdrfusion-bench --frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20 > $OUT/bench_$i.txt 2>&1
  grep -E '^\| cuda \| compact \| [0-9]+x[0-9]+ \| [0-9]+ \| [0-9.]+ \| [a-z]+ \|' $OUT/bench_$i.txt | cut -d'|' -f4,7,8,12 | tr '\n' ' ' | sed "s/^/== $i stages:/"; echo
  grep -A5 'not timed' $OUT/bench_$i.txt | grep '^| cuda' | cut -d'|' -f4,6-9 | sed "s/^/== $i not timed:/"
done
