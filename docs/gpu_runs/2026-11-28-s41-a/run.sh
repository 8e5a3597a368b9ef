#!/usr/bin/env bash
# session 41 (a): the ray cast beside what any ray cast giving the same images must at least do
# (oracle.patch, an experiment build, not kept): the hits' shading alone with each ray's hit
# depth given, the same with one TSDF sample either side of the hit, and the images written
# with constants; the real ray cast timed the same way. 640x480 and 320x240, compact voxels.
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
patch -p1 < docs/gpu_runs/2026-11-28-s41-a/oracle.patch
cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1
cmake --build --preset core-gpu -j 16 --target hdrfusion-bench > /tmp/build.txt 2>&1; echo "build rc=$?"; grep -iE "error|warning" /tmp/build.txt | head
for c in 640x480x20 320x240x20; do
  for v in compact full; do
    HDRF_RAYCAST_ORACLE=1 build-gpu/app/bench/hdrfusion-bench --frames 100 --device cuda --voxel $v --case $c > $OUT/oracle_${c}_$v.txt 2>&1
    echo "== $c $v rc=$?"; grep "oracle:" $OUT/oracle_${c}_$v.txt
  done
done
