#!/usr/bin/env bash
set -u
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=$OUT/gc tools/gpu_check.sh > $OUT/gc.txt 2>&1
echo "gpu_check rc=$?"; grep -E "tests passed|FAILED|Failure|Expected|Which is|frame 1 parity|raycast:|volume:|Gauss-Newton run|reloc|entries|trajector" $OUT/gc/ctest_gpu.txt | head -40
ARGS="--frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20"
for i in 1 2 3; do
  build-gpu/app/bench/hdrfusion-bench $ARGS > $OUT/b_head$i.txt 2>&1
  echo "== head$i"
  awk -F'|' '/^\| device \| voxel \| size \| voxel size \| convert/{t=1} /^\| device \| voxel \| size \| voxel size \| ms\/frame timed/{t=2} /^$/{t=0} t==1 && /^\| cuda/{print $4,$5,$6,$7,$8,$10,$11,$12,$18} t==2 && /^\| cuda/{print "  untimed", $4, $5, $6, $7, $8, $9}' $OUT/b_head$i.txt
done
rm -f $OUT/gc/build.txt
