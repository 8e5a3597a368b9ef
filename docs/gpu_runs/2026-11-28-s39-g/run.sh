#!/usr/bin/env bash
# session 39 (g): the weak directions' eigen decomposition on a warp (SymmetricEigen6OnWarp):
# gpu tests (with GpuStepParity), the bench at 640x480, and the step's clock marks
# (track_profile2.patch on a copy of the tree) to compare with s39-f.
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=/tmp/gc tools/gpu_check.sh > /tmp/gc.txt 2>&1; echo "gpu_check rc=$?"
grep -E "tests passed|FAILED|Failure|Expected|Which is|scan parity:|decompositions differ" /tmp/gc/ctest_gpu.txt | head -20
cp /tmp/gc/ctest_gpu.txt /tmp/gc/gpu_env.txt $OUT/
rm -rf /tmp/ptree && mkdir /tmp/ptree && tar --exclude=./build-gpu --exclude=./.git -cf - . | tar -x -C /tmp/ptree
( cd /tmp/ptree && P=$OLDPWD/docs/gpu_runs/2026-11-28-s39-g/track_profile2.patch; (patch -p1 -s < $P || git apply $P) && echo "patch ok"
  cmake -S . -B bp -G Ninja -DCMAKE_BUILD_TYPE=Release -DHDRF_CORE_ONLY=ON -DHDRF_BUILD_TESTS=OFF -DCMAKE_CUDA_ARCHITECTURES=90 \
    -DHDRF_SHARED_DATA_DIR=/nonexistent "-DCMAKE_CUDA_FLAGS=-DHDRF_TRACK_PROFILE" > /dev/null 2>&1
  cmake --build bp --target hdrfusion-bench -j 16 > /tmp/build_p.txt 2>&1; echo "profile build rc=$?"; grep -m3 error /tmp/build_p.txt ) &
for i in 1 2; do
  build-gpu/app/bench/hdrfusion-bench --frames 200 --device cuda --voxel compact --case 640x480x20 > /tmp/b_$i.txt 2>&1
  grep -E '^\| cuda \| compact \| 640x480 \| 20 mm \| [0-9]' /tmp/b_$i.txt | head -1 | cut -d'|' -f6-12,18 | sed "s/^/== $i timed:/"
  grep -A5 'not timed' /tmp/b_$i.txt | grep '^| cuda' | cut -d'|' -f4,6-9 | sed "s/^/== $i not timed:/"
done
wait
cp /tmp/b_1.txt $OUT/
/tmp/ptree/bp/app/bench/hdrfusion-bench --frames 200 --device cuda --voxel compact --case 640x480x20 > $OUT/b_profile.txt 2>&1; echo "profile bench rc=$?"
grep -E "profile" $OUT/b_profile.txt | sort -u
