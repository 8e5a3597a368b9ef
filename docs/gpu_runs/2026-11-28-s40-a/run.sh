#!/usr/bin/env bash
# session 40 (a): the integration fused (visible keys split as they are found; the new bricks
# placed by the integration's own blocks; SplitKeys and PlaceNewKernel gone from the device's
# path): gpu tests, recovery_tests on CUDA, the bench at 640x480 and 320x240 against 878e2d6
# (_base/tree) alternating, and ncu of the integration's kernels both ways.
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
( cd _base/tree && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 6 --target hdrfusion-bench > /tmp/build_base.txt 2>&1; echo "base build rc=$?" ) &
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=/tmp/gc tools/gpu_check.sh > /tmp/gc.txt 2>&1; echo "gpu_check rc=$?"
grep -E "tests passed|FAILED|Failure|Expected|Which is|scan parity:|volume:" /tmp/gc/ctest_gpu.txt | head -20
cp /tmp/gc/ctest_gpu.txt /tmp/gc/gpu_env.txt $OUT/
cmake --build --preset core-gpu -j 8 --target recovery_tests > /tmp/build_rec.txt 2>&1; echo "recovery build rc=$?"
wait
HDRF_TEST_DEVICE=cuda timeout 250 build-gpu/tests/recovery_tests > $OUT/recovery_cuda.txt 2>&1; echo "recovery_tests on cuda rc=$?"; grep -E "PASSED|FAILED|Failure" $OUT/recovery_cuda.txt | head
declare -A B=([base]=_base/tree/build-gpu/app/bench/hdrfusion-bench [fused]=build-gpu/app/bench/hdrfusion-bench)
for i in 1 2 3; do
  for v in base fused; do
    ${B[$v]} --frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20 > /tmp/b_${v}_$i.txt 2>&1
    grep -E '^\| cuda \| compact \| [0-9]+x[0-9]+ \| 20 mm \| [0-9]' /tmp/b_${v}_$i.txt | head -2 | cut -d'|' -f4,6-12,18 | sed "s/^/== $v $i timed:/"
    grep -A5 'not timed' /tmp/b_${v}_$i.txt | grep '^| cuda' | cut -d'|' -f4,6-9 | sed "s/^/== $v $i not timed:/"
  done
done
cp /tmp/b_base_1.txt /tmp/b_fused_1.txt $OUT/
for v in base fused; do
  /usr/local/cuda/bin/ncu --kernel-name-base demangled --kernel-name regex:"Integrate|SplitKeys|PlaceNew" --launch-skip 40 --launch-count 12 \
    --metrics gpu__time_duration.sum,smsp__inst_executed.sum ${B[$v]} --frames 12 --device cuda --voxel compact --case 640x480x20 > $OUT/ncu_$v.txt 2>&1
  echo "ncu $v rc=$?"; grep -E "^  [a-zA-Z].*\(|gpu__time" $OUT/ncu_$v.txt | sed 's/  */ /g' | cut -c1-100 | head -24
done
