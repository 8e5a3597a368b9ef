#!/usr/bin/env bash
# session 39 (f, second run): the same marks, and inside the step (thread 0 of the lead block).
set -u
cmake -S . -B bp -G Ninja -DCMAKE_BUILD_TYPE=Release -DHDRF_CORE_ONLY=ON -DHDRF_BUILD_TESTS=OFF -DCMAKE_CUDA_ARCHITECTURES=90 \
  -DHDRF_SHARED_DATA_DIR=/nonexistent "-DCMAKE_CUDA_FLAGS=-DHDRF_TRACK_PROFILE" > /dev/null 2>&1
cmake --build bp --target hdrfusion-bench -j 16 > /tmp/build.txt 2>&1; echo "build rc=$?"; grep -m3 error /tmp/build.txt
bp/app/bench/hdrfusion-bench --frames 200 --device cuda --voxel compact --case 640x480x20 > $OUT/b2_640.txt 2>&1; echo "bench rc=$?"
grep -E "profile" $OUT/b2_640.txt | sort -u
grep -A4 "track ms per iteration" $OUT/b2_640.txt | grep "^| cuda" | head -1
