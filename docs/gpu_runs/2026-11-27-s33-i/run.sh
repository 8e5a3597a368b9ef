#!/usr/bin/env bash
set -u
(cd _base/tree && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 8 --target hdrfusion-bench > /tmp/b1.txt 2>&1; echo "start build rc=$?") &
(cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 8 --target hdrfusion-bench > /tmp/b2.txt 2>&1; echo "end build rc=$?") &
wait
nvidia-smi --query-gpu=name --format=csv,noheader
ARGS="--frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20"
run() { # tag bin
  $2 $ARGS > $OUT/b_$1.txt 2>&1
  echo "== $1"
  awk -F'|' '/^\| device \| voxel \| size \| voxel size \| ms\/frame timed/{t=2} /^$/{t=0} t==2 && /^\| cuda/{print "  untimed", $4, $5, $6, $7, $8, $9}' $OUT/b_$1.txt
}
B=_base/tree/build-gpu/app/bench/hdrfusion-bench
N=build-gpu/app/bench/hdrfusion-bench
run start1 $B; run end1 $N; run start2 $B; run end2 $N; run start3 $B; run end3 $N; run start4 $B; run end4 $N
rm -f $OUT/b_start2.txt $OUT/b_start3.txt $OUT/b_start4.txt $OUT/b_end2.txt $OUT/b_end3.txt
