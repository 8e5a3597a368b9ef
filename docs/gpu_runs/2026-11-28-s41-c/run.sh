#!/usr/bin/env bash
# session 41 (c): the ray cast in two kernels, a ray's walk to its crossing (its distance
# stored) and then the hits' shading, against the one kernel (split.patch: s41-b's experiment
# and the split, timed beside the one-pass ray cast, its five images compared byte for byte
# with the one pass's each ray cast). ncu: instructions and registers of each kernel.
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
patch -p1 < docs/gpu_runs/2026-11-28-s41-c/split.patch
cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1
cmake --build --preset core-gpu -j 16 --target hdrfusion-bench > /tmp/build.txt 2>&1; echo "build rc=$?"; grep -iE " error" /tmp/build.txt | head
for c in 640x480x20 320x240x20; do
  HDRF_RAYCAST_ORACLE=1 build-gpu/app/bench/hdrfusion-bench --frames 100 --device cuda --voxel compact --case $c > $OUT/split_${c}.txt 2>&1
  echo "== $c rc=$?"; grep -E "oracle:|count:|split:" $OUT/split_${c}.txt
done
for k in RaycastInto SplitMarch SplitShade OracleShade; do
  HDRF_RAYCAST_ORACLE=1 /usr/local/cuda/bin/ncu --kernel-name-base demangled --kernel-name regex:"$k" --launch-skip 60 --launch-count 4 \
    --metrics gpu__time_duration.sum,launch__registers_per_thread,smsp__inst_executed.sum,smsp__thread_inst_executed_per_inst_executed.ratio \
    build-gpu/app/bench/hdrfusion-bench --frames 30 --device cuda --voxel compact --case 640x480x20 > $OUT/ncu_$k.txt 2>&1
  echo "ncu $k rc=$?"; grep -E "gpu__time|registers|inst_executed" $OUT/ncu_$k.txt | sed 's/  */ /g' | tr '\n' ' '; echo
done
