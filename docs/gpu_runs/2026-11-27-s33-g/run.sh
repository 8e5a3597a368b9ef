#!/usr/bin/env bash
set -u
(cd _base/tree && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 5 --target hdrfusion-bench > /tmp/build_base.txt 2>&1; echo "head build rc=$?") &
(cd _base/diag && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 4 --target hdrfusion-bench > /tmp/build_diag.txt 2>&1; echo "diag build rc=$?") &
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=$OUT/gc tools/gpu_check.sh > $OUT/gc.txt 2>&1
echo "gpu_check rc=$?"; grep -E "tests passed|FAILED|Failure|Expected|Which is|frame 1 parity|reloc|entries|trajector|error" $OUT/gc/ctest_gpu.txt | head -20
wait
ARGS="--frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20"
run() { # tag bin
  $2 $ARGS > $OUT/b_$1.txt 2>&1
  echo "== $1"
  awk -F'|' '/^\| device \| voxel \| size \| voxel size \| convert/{t=1} /^\| device \| voxel \| size \| voxel size \| ms\/frame timed/{t=2} /^$/{t=0} t==1 && /^\| cuda/{print $4,$5,$6,$7,$8,$10,$11,$12,$18} t==2 && /^\| cuda/{print "  untimed", $4, $5, $6, $7, $8, $9}' $OUT/b_$1.txt
}
B=_base/tree/build-gpu/app/bench/hdrfusion-bench
N=build-gpu/app/bench/hdrfusion-bench
run head1 $B; run new1 $N; run head2 $B; run new2 $N; run head3 $B; run new3 $N
D=_base/diag/build-gpu/app/bench/hdrfusion-bench
HDRF_DIAG=1 $D --frames 100 --device cuda --voxel compact --case 640x480x20 > /tmp/diag.txt 2>&1
grep -A17 "over 95 frames" /tmp/diag.txt > $OUT/diag_640.txt; cat $OUT/diag_640.txt
/usr/local/cuda/bin/ncu --cache-control none --clock-control none --metrics gpu__time_duration.sum --launch-skip 1500 --launch-count 50 $N --frames 40 --case 640x480x20 --device cuda --voxel compact > /tmp/ncu.txt 2>&1
grep -E "^  [A-Za-z_].*\(|gpu__time_duration" /tmp/ncu.txt | paste - - | awk -F'gpu__time_duration.sum' '{n=$1; sub(/^ +/,"",n); t=$2; gsub(/ +/," ",t); printf "%-12s %s\n", t, substr(n,1,110)}' > $OUT/ncu_kernels.txt
grep -E "Select|Rank|RowPass|ColumnPass|Integrate|Bilateral" $OUT/ncu_kernels.txt | head -20
rm -f $OUT/gc/build.txt $OUT/gc/gpu_env.txt $OUT/b_head2.txt $OUT/b_head3.txt $OUT/b_new2.txt $OUT/b_new3.txt
