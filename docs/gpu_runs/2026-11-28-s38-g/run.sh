#!/usr/bin/env bash
# session 38 (g): the final tree (b9cb1d6): gpu tests only
set -u
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=/tmp/gc tools/gpu_check.sh > /tmp/gc.txt 2>&1
echo "gpu_check rc=$?"; grep -E "tests passed|FAILED|Failure|scan parity:|volume:" /tmp/gc/ctest_gpu.txt | head -8
cp /tmp/gc/ctest_gpu.txt /tmp/gc/gpu_env.txt $OUT/
