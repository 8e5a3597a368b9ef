#!/usr/bin/env bash
# session 40 (e): where the convert stage's time goes (convert_parts.patch on 5f5db18: clock
# marks and events around the upload and the conversion's kernels, the means printed at exit),
# with the upload as now and with every thread copying first and one copy a part
# (HDRF_UPLOAD_BULK); and the host's copy bandwidth (the CPU bench's floor table), 640x480.
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
patch -p1 < docs/gpu_runs/2026-11-28-s40-e/convert_parts.patch > /dev/null || exit 1
cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 16 --target hdrfusion-bench > /tmp/build.txt 2>&1; echo "build rc=$?"
B=build-gpu/app/bench/hdrfusion-bench
$B --frames 5 --device cpu --voxel compact --case 64x48x40 2>&1 | grep -E "^\| cpu \| compact \| 64x48 \| [0-9]+ \| - \| convert" | sed 's/^/== host copy bandwidth row: /'
for i in 1 2 3; do
  for v in pieces bulk; do
    if [ $v = bulk ]; then export HDRF_UPLOAD_BULK=1; else unset HDRF_UPLOAD_BULK; fi
    $B --frames 200 --device cuda --voxel compact --case 640x480x20 > /tmp/b_${v}_$i.txt 2>&1
    grep -E '^\| cuda \| compact \| 640x480 \| [0-9]+ \| [0-9.]+ \| convert \|' /tmp/b_${v}_$i.txt | cut -d'|' -f6,8,12 | sed "s/^/== $v $i convert (bus, ms, x floor):/"
    grep "convert parts" /tmp/b_${v}_$i.txt | sed "s/^/== $v $i /"
    grep -A5 'not timed' /tmp/b_${v}_$i.txt | grep '^| cuda' | cut -d'|' -f4,6-9 | sed "s/^/== $v $i not timed:/"
  done
done
cp /tmp/b_pieces_1.txt /tmp/b_bulk_1.txt $OUT/
