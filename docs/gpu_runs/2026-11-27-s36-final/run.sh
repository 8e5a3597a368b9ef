#!/usr/bin/env bash
# session 36 (final): the GPU checks at the session's final code, and its frame against the session's start (85f5361)
set -u
(cd _base/tree && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 6 --target hdrfusion-bench > /tmp/build_base.txt 2>&1; echo "start build rc=$?") &
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=/tmp/gc tools/gpu_check.sh > /tmp/gc.txt 2>&1
echo "gpu_check rc=$?"; grep -E "tests passed|FAILED|Failure|Expected|Which is|error|scan parity:" /tmp/gc/ctest_gpu.txt | head -20
cp /tmp/gc/ctest_gpu.txt $OUT/
wait
ARGS="--frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20"
run() { # tag bin
  $2 $ARGS > /tmp/b_$1.txt 2>&1
  echo "== $1"
  awk -F'|' '/^\| device \| voxel \| size \| voxel size \| convert/{t=1} /^\| device \| voxel \| size \| voxel size \| ms\/frame timed/{t=2} /^$/{t=0} t==1 && /^\| cuda/{print $4,$5,$6,$7,$8,$10,$11,$12,$18} t==2 && /^\| cuda/{print "  untimed", $4, $5, $6, $7, $8, $9}' /tmp/b_$1.txt
}
B=_base/tree/build-gpu/app/bench/hdrfusion-bench
N=build-gpu/app/bench/hdrfusion-bench
run start1 $B; run final1 $N; run start2 $B; run final2 $N; run start3 $B; run final3 $N; run start4 $B; run final4 $N
cp /tmp/b_final1.txt /tmp/b_start1.txt $OUT/
