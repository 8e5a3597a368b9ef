#!/usr/bin/env bash
# session 35 GPU run: baseline (0ff6aae) vs working tree (group brick masks)
set -u
(cd _base/tree && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 6 --target hdrfusion-bench > /tmp/build_base.txt 2>&1; echo "base build rc=$?") &
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=$OUT/gc tools/gpu_check.sh > $OUT/gc.txt 2>&1
echo "gpu_check rc=$?"; grep -E "tests passed|FAILED|Failure|Expected|Which is|error" $OUT/gc/ctest_gpu.txt | head -20
wait
ARGS="--frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20"
run() { # tag bin
  $2 $ARGS > $OUT/b_$1.txt 2>&1
  echo "== $1"
  awk -F'|' '/^\| device \| voxel \| size \| voxel size \| convert/{t=1} /^\| device \| voxel \| size \| voxel size \| ms\/frame timed/{t=2} /^$/{t=0} t==1 && /^\| cuda/{print $4,$5,$6,$7,$8,$10,$11,$12,$18} t==2 && /^\| cuda/{print "  untimed", $4, $5, $6, $7, $8, $9}' $OUT/b_$1.txt
}
B=_base/tree/build-gpu/app/bench/hdrfusion-bench
N=build-gpu/app/bench/hdrfusion-bench
run base1 $B; run new1 $N; run base2 $B; run new2 $N; run base3 $B; run new3 $N
for t in base new; do
  if [ $t = base ]; then X=$B; else X=$N; fi
  for c in 640x480x20 320x240x20; do
    /usr/local/cuda/bin/ncu --cache-control none --clock-control none --metrics gpu__time_duration.sum --kernel-name regex:RaycastInto --launch-skip 30 --launch-count 40 $X --frames 60 --case $c --device cuda --voxel compact > /tmp/ncu_$t.txt 2>&1
    echo "== ncu $t $c: unit $(grep -m1 gpu__time_duration /tmp/ncu_$t.txt | awk "{print \$(NF-1)}"); ray cast kernel (40 launches): $(grep gpu__time_duration /tmp/ncu_$t.txt | awk '{print $NF}' | sort -n | awk '{a[NR]=$1} END {print "min", a[1], "median", a[int(NR/2)+1], "max", a[NR], "n", NR}')"
  done
done
rm -f $OUT/gc/build.txt
