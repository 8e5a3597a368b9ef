#!/usr/bin/env bash
# session 35 experiment: the ray cast's warps take tiles from a counter (HDRF_RC_TAKE=1: one block set per SM's room, 2: twice that)
set -u
HDRF_RC_TAKE=1 HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=$OUT/gc tools/gpu_check.sh > $OUT/gc.txt 2>&1
echo "gpu_check (take=1) rc=$?"; grep -E "tests passed|FAILED|Failure|Expected|Which is|error|scan parity" $OUT/gc/ctest_gpu.txt | head -20
ARGS="--frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20"
N=build-gpu/app/bench/hdrfusion-bench
run() { # tag mode
  HDRF_RC_TAKE=$2 $N $ARGS > $OUT/b_$1.txt 2>&1
  echo "== $1"
  awk -F'|' '/^\| device \| voxel \| size \| voxel size \| convert/{t=1} /^\| device \| voxel \| size \| voxel size \| ms\/frame timed/{t=2} /^$/{t=0} t==1 && /^\| cuda/{print $4,$5,$6,$7,$8,$10,$11,$12,$18} t==2 && /^\| cuda/{print "  untimed", $4, $5, $6, $7, $8, $9}' $OUT/b_$1.txt
}
for i in 1 2 3; do run base$i 0; run take$i 1; run take2x$i 2; done
for m in 0 1; do
  HDRF_RC_TAKE=$m /usr/local/cuda/bin/ncu --kernel-name-base demangled --kernel-name regex:"RaycastInto|RaycastTakeTiles" --launch-skip 30 --launch-count 20 --metrics gpu__time_duration.sum,sm__warps_active.avg.pct_of_peak_sustained_active $N --frames 60 --case 640x480x20 --device cuda --voxel compact > $OUT/ncu_$m.txt 2>&1
  echo "== ncu take=$m: $(grep gpu__time_duration $OUT/ncu_$m.txt | awk '{print $NF}' | sort -n | awk '{a[NR]=$1} END {print "min", a[1], "median", a[int(NR/2)+1], "max", a[NR]}') occupancy $(grep warps_active $OUT/ncu_$m.txt | awk '{print $NF}' | sort -n | awk '{a[NR]=$1} END {print a[int(NR/2)+1]}')"
done
rm -f $OUT/gc/build.txt
