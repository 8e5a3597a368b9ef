#!/usr/bin/env bash
# session 40 (g): review mend (the device's placement path no longer writes the new bricks'
# to-do entries, which only the host's path reads): gpu tests and recovery_tests on CUDA.
set -u
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=/tmp/gc tools/gpu_check.sh > /tmp/gc.txt 2>&1; echo "gpu_check rc=$?"
grep -E "tests passed|FAILED|Failure|scan parity:|place limit" /tmp/gc/ctest_gpu.txt | head -8
cp /tmp/gc/ctest_gpu.txt /tmp/gc/gpu_env.txt $OUT/
cmake --build --preset core-gpu -j 16 --target recovery_tests > /tmp/build_rec.txt 2>&1; echo "recovery build rc=$?"
HDRF_TEST_DEVICE=cuda timeout 200 build-gpu/tests/recovery_tests > $OUT/recovery_cuda.txt 2>&1; echo "recovery_tests on cuda rc=$?"; grep -E "PASSED|FAILED" $OUT/recovery_cuda.txt | head -3
