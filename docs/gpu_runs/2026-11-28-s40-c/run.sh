#!/usr/bin/env bash
# session 40 (c): how much of the GPU's integrate stage is the relocalisation keyframe (made in
# that stage's window): the bench at 8c55aa6 with relocalisation on and off (no_reloc.patch,
# by HDRF_NO_RELOC), and with the keyframe made once the ray cast is queued
# (keyframe_after_raycast.patch), alternating, 640x480.
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
R=docs/gpu_runs/2026-11-28-s40-c
patch -p1 < $R/no_reloc.patch > /dev/null || exit 1
mkdir -p /tmp/moved && tar --exclude=./build-gpu --exclude=./_base -cf - . | tar -xf - -C /tmp/moved
( cd /tmp/moved && patch -p1 < $R/keyframe_after_raycast.patch > /dev/null && \
  cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 8 --target hdrfusion-bench > /tmp/build_moved.txt 2>&1; echo "moved build rc=$?" ) &
cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 8 --target hdrfusion-bench > /tmp/build_head.txt 2>&1; echo "head build rc=$?"
wait
run() {  # name, binary, env
  env $3 $2 --frames 200 --device cuda --voxel compact --case 640x480x20 > /tmp/b_$1_$i.txt 2>&1
  grep -E '^\| cuda \| compact \| [0-9]+x[0-9]+ \| [0-9]+ \| [0-9.]+ \| (convert|normalize|track|integrate|raycast) \|' /tmp/b_$1_$i.txt | cut -d'|' -f7,8 | tr '\n' ' ' | sed "s/^/== $1 $i stages:/"; echo
  grep -A5 'not timed' /tmp/b_$1_$i.txt | grep '^| cuda' | cut -d'|' -f4,6-9 | sed "s/^/== $1 $i not timed:/"
  grep -A4 'worst integrate' /tmp/b_$1_$i.txt | grep '^| cuda' | sed "s/^/== $1 $i slow:/"
}
for i in 1 2 3; do
  run head build-gpu/app/bench/hdrfusion-bench HDRF_X=1
  run noreloc build-gpu/app/bench/hdrfusion-bench HDRF_NO_RELOC=1
  run moved /tmp/moved/build-gpu/app/bench/hdrfusion-bench HDRF_X=1
done
cp /tmp/b_head_1.txt /tmp/b_noreloc_1.txt /tmp/b_moved_1.txt $OUT/
