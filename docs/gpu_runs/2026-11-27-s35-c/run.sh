#!/usr/bin/env bash
set -u
B=_base/tree/build-gpu/app/bench/hdrfusion-bench
N=build-gpu/app/bench/hdrfusion-bench
H=_base/hint/build-gpu/app/bench/hdrfusion-bench
[ -x $B ] || (cd _base/tree && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 5 --target hdrfusion-bench > /tmp/build_base.txt 2>&1; echo "base build rc=$?") &
(cd _base/hint && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 5 --target hdrfusion-bench > /tmp/build_hint.txt 2>&1; echo "hint build rc=$?") &
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=$OUT/gc tools/gpu_check.sh > $OUT/gc.txt 2>&1
echo "gpu_check rc=$?"; grep -E "tests passed|FAILED|Failure|Expected|Which is|error" $OUT/gc/ctest_gpu.txt | head -20
wait
for t in base new hint; do
  case $t in base) X=$B;; new) X=$N;; hint) X=$H;; esac
  /usr/local/cuda/bin/ncu --kernel-name-base demangled --kernel-name regex:RaycastInto --launch-skip 30 --launch-count 20 --metrics gpu__time_duration.sum,smsp__inst_executed.sum,launch__registers_per_thread,smsp__pcsamp_warps_issue_stalled_no_instructions $X --frames 60 --case 640x480x20 --device cuda --voxel compact > $OUT/ncu_$t.txt 2>&1
  echo "== $t time: $(grep gpu__time_duration $OUT/ncu_$t.txt | awk '{print $NF}' | sort -n | awk '{a[NR]=$1} END {print a[1], a[int(NR/2)+1], a[NR]}') inst: $(grep smsp__inst_executed.sum $OUT/ncu_$t.txt | awk '{print $NF}' | sort -n | awk '{a[NR]=$1} END {print a[int(NR/2)+1]}') regs: $(grep -m1 launch__registers $OUT/ncu_$t.txt | awk '{print $NF}')"
done
ARGS="--frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20"
run() { # tag bin
  $2 $ARGS > $OUT/b_$1.txt 2>&1
  echo "== $1"
  awk -F'|' '/^\| device \| voxel \| size \| voxel size \| convert/{t=1} /^\| device \| voxel \| size \| voxel size \| ms\/frame timed/{t=2} /^$/{t=0} t==1 && /^\| cuda/{print $4,$5,$6,$7,$8,$10,$11,$12,$18} t==2 && /^\| cuda/{print "  untimed", $4, $5, $6, $7, $8, $9}' $OUT/b_$1.txt
}
run base1 $B; run new1 $N; run hint1 $H; run base2 $B; run new2 $N; run hint2 $H
rm -f $OUT/gc/build.txt
