#!/usr/bin/env bash
# session 39 (b): the ray cast's reach (each tile's depth range of the allocated bricks, from
# projecting every brick): gpu tests with it, then the bench at 640x480 and 320x240 with it and
# without it (HDRF_NO_REACH=1, the same binary), alternating; ncu of one ray cast each way.
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=/tmp/gc tools/gpu_check.sh > /tmp/gc.txt 2>&1; echo "gpu_check rc=$?"
grep -E "tests passed|FAILED|Failure|Expected|Which is|scan parity:|volume:" /tmp/gc/ctest_gpu.txt | head -20
cp /tmp/gc/ctest_gpu.txt /tmp/gc/gpu_env.txt $OUT/
N=build-gpu/app/bench/hdrfusion-bench
for i in 1 2 3; do
  for v in 1 0; do
    if [ $v = 1 ]; then export HDRF_NO_REACH=1; else unset HDRF_NO_REACH; fi
    $N --frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20 > /tmp/b_${v}_$i.txt 2>&1
    grep -E '^\| cuda \| compact \| [0-9]+x[0-9]+ \| 20 mm \| [0-9]' /tmp/b_${v}_$i.txt | head -2 | cut -d'|' -f4,6-12,18 | sed "s/^/== noreach=$v $i timed:/"
    grep -A5 'not timed' /tmp/b_${v}_$i.txt | grep '^| cuda' | cut -d'|' -f4,6-9 | sed "s/^/== noreach=$v $i not timed:/"
  done
done
cp /tmp/b_0_1.txt /tmp/b_1_1.txt $OUT/
for v in 1 0; do
  if [ $v = 1 ]; then export HDRF_NO_REACH=1; else unset HDRF_NO_REACH; fi
  /usr/local/cuda/bin/ncu --kernel-name-base demangled --kernel-name regex:"RaycastInto|RaycastReach" --launch-skip 20 --launch-count 6 \
    --metrics gpu__time_duration.sum,smsp__inst_executed.sum $N --frames 12 --device cuda --voxel compact --case 640x480x20 > $OUT/ncu_$v.txt 2>&1
  echo "ncu noreach=$v rc=$?"; grep -E "RaycastInto|RaycastReach|gpu__time|inst_exec" $OUT/ncu_$v.txt | sed 's/  */ /g' | cut -c1-120 | head -24
done
