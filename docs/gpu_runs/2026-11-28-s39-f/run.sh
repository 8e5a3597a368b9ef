#!/usr/bin/env bash
# session 39 (f): where the tracker's run spends a Gauss-Newton step: clock64 marks on the lead
# block's thread 0 (HDRF_TRACK_PROFILE, an experiment build), the bench at 640x480.
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
cmake -S . -B bp -G Ninja -DCMAKE_BUILD_TYPE=Release -DHDRF_CORE_ONLY=ON -DHDRF_BUILD_TESTS=OFF -DCMAKE_CUDA_ARCHITECTURES=90 \
  -DHDRF_SHARED_DATA_DIR=/nonexistent "-DCMAKE_CUDA_FLAGS=-DHDRF_TRACK_PROFILE" > /dev/null 2>&1
cmake --build bp --target hdrfusion-bench -j 16 > /tmp/build.txt 2>&1; echo "build rc=$?"; grep -m3 error /tmp/build.txt
for c in 640x480x20 1280x960x20; do
  bp/app/bench/hdrfusion-bench --frames 200 --device cuda --voxel compact --case $c > $OUT/b_$c.txt 2>&1; echo "bench $c rc=$?"
  grep -E "track profile|Gauss|^\| cuda \| compact \| [0-9]+x[0-9]+ \| [0-9.]+ / " $OUT/b_$c.txt
  grep -A4 "track ms per iteration" $OUT/b_$c.txt | grep "^| cuda"
done
