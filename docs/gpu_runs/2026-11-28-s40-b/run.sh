#!/usr/bin/env bash
# session 40 (b): the tracker's level arguments copied by the lead block's threads (StartLevel),
# the integration's voxel read before its projection, the bench's least-stage table: gpu tests,
# recovery_tests on CUDA, the bench at 640x480 and 320x240 against 878e2d6 (_base/tree),
# alternating, and ncu of the tracker's run and the integration both ways.
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
( cd _base/tree && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 6 --target hdrfusion-bench > /tmp/build_base.txt 2>&1; echo "base build rc=$?" ) &
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=/tmp/gc tools/gpu_check.sh > /tmp/gc.txt 2>&1; echo "gpu_check rc=$?"
grep -E "tests passed|FAILED|Failure|Expected|Which is|scan parity:|volume:|least stage" /tmp/gc/ctest_gpu.txt | head -20
cp /tmp/gc/ctest_gpu.txt /tmp/gc/gpu_env.txt $OUT/
cmake --build --preset core-gpu -j 8 --target recovery_tests > /tmp/build_rec.txt 2>&1; echo "recovery build rc=$?"
wait
HDRF_TEST_DEVICE=cuda timeout 250 build-gpu/tests/recovery_tests > $OUT/recovery_cuda.txt 2>&1; echo "recovery_tests on cuda rc=$?"; grep -E "PASSED|FAILED|Failure" $OUT/recovery_cuda.txt | head
declare -A B=([base]=_base/tree/build-gpu/app/bench/hdrfusion-bench [new]=build-gpu/app/bench/hdrfusion-bench)
for i in 1 2 3; do
  for v in base new; do
    ${B[$v]} --frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20 > /tmp/b_${v}_$i.txt 2>&1
    grep -E '^\| cuda \| compact \| [0-9]+x[0-9]+ \| [0-9]+ \| [0-9.]+ \| (convert|normalize|track|integrate|raycast) \|' /tmp/b_${v}_$i.txt | head -10 | cut -d'|' -f4,7,8 | tr '\n' ' ' | sed "s/^/== $v $i stages:/"; echo
    grep -A5 'not timed' /tmp/b_${v}_$i.txt | grep '^| cuda' | cut -d'|' -f4,6-9 | sed "s/^/== $v $i not timed:/"
  done
done
cp /tmp/b_base_1.txt /tmp/b_new_1.txt /tmp/b_new_2.txt $OUT/
for v in base new; do
  /usr/local/cuda/bin/ncu --kernel-name-base demangled --kernel-name regex:"IntegrateBricks|RunKernel" --launch-skip 20 --launch-count 12 \
    --metrics gpu__time_duration.sum ${B[$v]} --frames 12 --device cuda --voxel compact --case 640x480x20 > $OUT/ncu_$v.txt 2>&1
  echo "ncu $v rc=$?"; grep -E "^  [a-zA-Z].*\(|gpu__time" $OUT/ncu_$v.txt | sed 's/  */ /g' | cut -c1-60 | paste - - | head -12
done
