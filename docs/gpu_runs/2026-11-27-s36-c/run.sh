#!/usr/bin/env bash
# session 36 (c): the gpu tests with the run's new checks (fewer blocks: the same bits; ICP alone, NR alone),
# and a mutant (the count-first path skipped) that the new checks must catch
set -u
(cd _base/mut && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 6 --target gpu_tests > /tmp/build_mut.txt 2>&1; echo "mutant build rc=$?"; grep -m3 error /tmp/build_mut.txt) &
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=/tmp/gc tools/gpu_check.sh > /tmp/gc.txt 2>&1
echo "gpu_check rc=$?"; grep -E "tests passed|FAILED|Failure|Expected|Which is|error|scan parity:|alone|valid pixels|device-stepped|Gauss-Newton run" /tmp/gc/ctest_gpu.txt | head -40
cp /tmp/gc/ctest_gpu.txt $OUT/
wait
_base/mut/build-gpu/tests/gpu_tests --gtest_filter='*StageParity*compact' > /tmp/mut.txt 2>&1
echo "mutant gpu_tests rc=$?"; grep -E "Failure|blocks|Expected|Which is|OK \]|FAILED" /tmp/mut.txt | head -20
