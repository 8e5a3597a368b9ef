#!/usr/bin/env bash
# session 41 (b): s41-a's experiment with each ray's steps counted (oracle_count.patch: s41-a's
# oracle.patch and a copy of the ray's walk that counts its steps, TSDF samples and skips of
# absent bricks, every fourth ray cast): how many steps a ray takes, how they spread, and how
# many a warp's longest ray takes.
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
patch -p1 < docs/gpu_runs/2026-11-28-s41-b/oracle_count.patch
cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1
cmake --build --preset core-gpu -j 16 --target hdrfusion-bench > /tmp/build.txt 2>&1; echo "build rc=$?"; grep -iE " error" /tmp/build.txt | head
for c in 640x480x20 320x240x20; do
  HDRF_RAYCAST_ORACLE=1 build-gpu/app/bench/hdrfusion-bench --frames 100 --device cuda --voxel compact --case $c > $OUT/count_${c}.txt 2>&1
  echo "== $c rc=$?"; grep -E "oracle:|count:" $OUT/count_${c}.txt
done
