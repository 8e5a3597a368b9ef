#!/usr/bin/env bash
# session 38 (e): the CPU's four-lane projections (3d3e631) against the GPU: gpu tests (CPU-GPU parity, bit for bit), recovery on CUDA, the bench
set -u
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=/tmp/gc tools/gpu_check.sh > /tmp/gc.txt 2>&1
echo "gpu_check rc=$?"; grep -E "tests passed|FAILED|Failure|Expected|Which is|error|scan parity:|place limit|volume:|Gauss" /tmp/gc/ctest_gpu.txt | head -30
cp /tmp/gc/ctest_gpu.txt /tmp/gc/gpu_env.txt $OUT/
cmake --build --preset core-gpu -j 16 --target recovery_tests core_tests > /tmp/build_rec.txt 2>&1; echo "recovery build rc=$?"
build-gpu/tests/core_tests --gtest_filter='Lanes*' 2>&1 | tail -1
HDRF_TEST_DEVICE=cuda timeout 250 build-gpu/tests/recovery_tests > $OUT/recovery_cuda.txt 2>&1; echo "recovery_tests on cuda rc=$?"; grep -E "PASSED|FAILED|first relocalisation" $OUT/recovery_cuda.txt | head
N=build-gpu/app/bench/hdrfusion-bench
for i in 1 2 3; do
  $N --frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20 > /tmp/b_$i.txt 2>&1
  echo "== $i"; grep -A4 "not timed" /tmp/b_$i.txt | grep "^| cuda"
done
cp /tmp/b_1.txt $OUT/
