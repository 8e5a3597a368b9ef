#!/usr/bin/env bash
# session 36: the tracker's run as one cooperative kernel, the count in idle blocks (tree) and with 2 pixels unrolled (varU), against the start
set -u
(cd _base/tree && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 5 --target hdrfusion-bench > /tmp/build_base.txt 2>&1; echo "base build rc=$?") &
(cd _base/varU && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 5 --target hdrfusion-bench > /tmp/build_u.txt 2>&1; echo "varU build rc=$?"; grep -m3 error /tmp/build_u.txt) &
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=$OUT/gc tools/gpu_check.sh > $OUT/gc.txt 2>&1
echo "gpu_check rc=$?"; grep -E "tests passed|FAILED|Failure|Expected|Which is|error|scan parity:" $OUT/gc/ctest_gpu.txt | head -20
wait
ARGS="--frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20"
run() { # tag bin
  $2 $ARGS > $OUT/b_$1.txt 2>&1
  echo "== $1"
  awk -F'|' '/^\| device \| voxel \| size \| voxel size \| convert/{t=1} /^\| device \| voxel \| size \| voxel size \| ms\/frame timed/{t=2} /^$/{t=0} t==1 && /^\| cuda/{print $4,$5,$6,$7,$8,$10,$11,$12,$18} t==2 && /^\| cuda/{print "  untimed", $4, $5, $6, $7, $8, $9}' $OUT/b_$1.txt
}
B=_base/tree/build-gpu/app/bench/hdrfusion-bench
N=build-gpu/app/bench/hdrfusion-bench
U=_base/varU/build-gpu/app/bench/hdrfusion-bench
run base1 $B; run new1 $N; run u1 $U; run base2 $B; run new2 $N; run u2 $U; run base3 $B; run new3 $N; run u3 $U
/usr/local/cuda/bin/ncu --set full --kernel-name regex:RunKernel --launch-skip 30 --launch-count 1 $N --frames 40 --case 640x480x20 --device cuda --voxel compact > $OUT/ncu_run_full.txt 2>&1
grep -E "Duration|Registers|Achieved Occupancy|Theoretical Occupancy|Memory Throughput|L1/TEX Hit|L2 Hit|DRAM Throughput|Executed Instructions  |Warp Cycles Per Issued|Stall|stall" $OUT/ncu_run_full.txt | head -30
HDRF_TEST_DEVICE=cuda timeout 200 build-gpu/tests/recovery_tests > $OUT/recovery_cuda.txt 2>&1
echo "recovery_tests on cuda rc=$?"
grep -cE "OK \]" $OUT/recovery_cuda.txt; grep -E "FAILED|Failure" $OUT/recovery_cuda.txt | head
rm -f $OUT/gc/build.txt
