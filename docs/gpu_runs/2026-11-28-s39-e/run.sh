#!/usr/bin/env bash
# session 39 (e): the ray cast's code out of line in device code (HDRF_OUTLINE_MASK: 1 the
# gradient's six-sample fallback, 2 the radiance sample and the 32-voxel gradient, 4 the TSDF
# sample, 8 the hash look-up, 16 the cell's corner slots): the kernel's 9496 SASS instructions
# overflow the instruction cache ("no instruction" is 58 % of its stall samples, s39-d).
# The bench at 640x480 and 320x240 for masks 0, 7, 15, 31, alternating.
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
build() {
  cmake -S . -B bm_$1 -G Ninja -DCMAKE_BUILD_TYPE=Release -DHDRF_CORE_ONLY=ON -DHDRF_BUILD_TESTS=OFF -DCMAKE_CUDA_ARCHITECTURES=90 \
    -DHDRF_SHARED_DATA_DIR=/nonexistent "-DCMAKE_CUDA_FLAGS=-DHDRF_OUTLINE_MASK=$1" > /dev/null 2>&1
  cmake --build bm_$1 --target hdrfusion-bench -j 4 > /tmp/build_$1.txt 2>&1; echo "build $1 rc=$?"
}
for m in 0 7 15 31; do build $m & done; wait
for i in 1 2 3; do
  for m in 0 7 15 31; do
    bm_$m/app/bench/hdrfusion-bench --frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20 > /tmp/b_${m}_$i.txt 2>&1
    grep -E '^\| cuda \| compact \| [0-9]+x[0-9]+ \| 20 mm \| [0-9]' /tmp/b_${m}_$i.txt | head -2 | cut -d'|' -f4,6-12,18 | sed "s/^/== mask $m $i timed:/"
    grep -A5 'not timed' /tmp/b_${m}_$i.txt | grep '^| cuda' | cut -d'|' -f4,6-9 | sed "s/^/== mask $m $i not timed:/"
  done
done
cp /tmp/b_0_1.txt /tmp/b_15_1.txt $OUT/
/usr/local/cuda/bin/ncu --kernel-name-base demangled --kernel-name regex:RaycastInto --launch-skip 20 --launch-count 3 \
  --metrics gpu__time_duration.sum,smsp__inst_executed.sum,smsp__pcsamp_warps_issue_stalled_no_instructions,smsp__pcsamp_sample_count \
  bm_15/app/bench/hdrfusion-bench --frames 12 --device cuda --voxel compact --case 640x480x20 > $OUT/ncu_15.txt 2>&1
grep -E "gpu__time|inst_exec|pcsamp" $OUT/ncu_15.txt | sed 's/  */ /g' | head -12
