#!/usr/bin/env bash
# session 40 (f): the integration's voxels with their depths read together and then their other
# images together (ReadPixel), two voxels a thread in blocks of 256 (the tree), or one a thread
# in blocks of 512 (variant b): gpu tests and recovery_tests on CUDA for the tree, then the
# bench at 640x480 and 320x240 against fe4d6f2 (_base/tree), alternating, and ncu of the
# integration's kernel each way.
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
mkdir -p /tmp/vb && tar --exclude=./build-gpu --exclude=./_base -cf - . | tar -xf - -C /tmp/vb
sed -i "s/constexpr int kIntegrateThreads = 256,/constexpr int kIntegrateThreads = 512,/" /tmp/vb/core/volume/volume_cuda.cu
grep -c "kIntegrateThreads = 512" /tmp/vb/core/volume/volume_cuda.cu
( cd _base/tree && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 5 --target hdrfusion-bench > /tmp/build_base.txt 2>&1; echo "base build rc=$?" ) &
( cd /tmp/vb && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 5 --target hdrfusion-bench > /tmp/build_vb.txt 2>&1; echo "vb build rc=$?" ) &
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=/tmp/gc tools/gpu_check.sh > /tmp/gc.txt 2>&1; echo "gpu_check rc=$?"
grep -E "tests passed|FAILED|Failure|Expected|Which is|scan parity:|volume:" /tmp/gc/ctest_gpu.txt | head -12
cp /tmp/gc/ctest_gpu.txt /tmp/gc/gpu_env.txt $OUT/
cmake --build --preset core-gpu -j 8 --target recovery_tests hdrfusion-bench > /tmp/build_rec.txt 2>&1; echo "recovery build rc=$?"
wait
HDRF_TEST_DEVICE=cuda timeout 250 build-gpu/tests/recovery_tests > $OUT/recovery_cuda.txt 2>&1; echo "recovery_tests on cuda rc=$?"; grep -E "PASSED|FAILED|Failure" $OUT/recovery_cuda.txt | head
declare -A B=([base]=_base/tree/build-gpu/app/bench/hdrfusion-bench [two]=build-gpu/app/bench/hdrfusion-bench [one]=/tmp/vb/build-gpu/app/bench/hdrfusion-bench)
for i in 1 2 3; do
  for v in base two one; do
    ${B[$v]} --frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20 > /tmp/b_${v}_$i.txt 2>&1
    grep -E '^\| cuda \| compact \| [0-9]+x[0-9]+ \| [0-9]+ \| [0-9.]+ \| integrate \|' /tmp/b_${v}_$i.txt | cut -d'|' -f4,8,12 | tr '\n' ' ' | sed "s/^/== $v $i integrate:/"; echo
    grep -A5 'not timed' /tmp/b_${v}_$i.txt | grep '^| cuda' | cut -d'|' -f4,6-9 | sed "s/^/== $v $i not timed:/"
  done
done
cp /tmp/b_base_1.txt /tmp/b_two_1.txt /tmp/b_one_1.txt $OUT/
for v in base two one; do
  /usr/local/cuda/bin/ncu --kernel-name-base demangled --kernel-name regex:"IntegrateBricks" --launch-skip 20 --launch-count 6 \
    --metrics gpu__time_duration.sum,launch__registers_per_thread ${B[$v]} --frames 12 --device cuda --voxel compact --case 640x480x20 > $OUT/ncu_$v.txt 2>&1
  echo "ncu $v rc=$?"; grep -E "gpu__time|registers" $OUT/ncu_$v.txt | sed 's/  */ /g' | tr '\n' ' '; echo
done
