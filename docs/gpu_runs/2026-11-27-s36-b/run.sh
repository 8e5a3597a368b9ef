#!/usr/bin/env bash
# session 36 (b): the eigen decomposition unrolled on the GPU (tree) against e67ed67 (base)
set -u
(cd _base/tree && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 6 --target hdrfusion-bench > /tmp/build_base.txt 2>&1; echo "base build rc=$?") &
(cd _base/eig && nvcc -I../../core -isystem=/usr/include/eigen3 -O3 --generate-code=arch=compute_90,code=sm_90 --expt-relaxed-constexpr -fmad=false -std=c++20 -o /tmp/eig eig.cu && /tmp/eig > $OUT/eig.txt 2>&1; echo "eig rc=$?") &
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=/tmp/gc tools/gpu_check.sh > /tmp/gc.txt 2>&1
echo "gpu_check rc=$?"; grep -E "tests passed|FAILED|Failure|Expected|Which is|error|scan parity:" /tmp/gc/ctest_gpu.txt | head -20
wait
cat $OUT/eig.txt
ARGS="--frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20"
run() { # tag bin
  $2 $ARGS > /tmp/b_$1.txt 2>&1
  echo "== $1"
  awk -F'|' '/^\| device \| voxel \| size \| voxel size \| convert/{t=1} /^\| device \| voxel \| size \| voxel size \| ms\/frame timed/{t=2} /^$/{t=0} t==1 && /^\| cuda/{print $4,$5,$6,$7,$8,$10,$11,$12,$18} t==2 && /^\| cuda/{print "  untimed", $4, $5, $6, $7, $8, $9}' /tmp/b_$1.txt
}
B=_base/tree/build-gpu/app/bench/hdrfusion-bench
N=build-gpu/app/bench/hdrfusion-bench
run base1 $B; run new1 $N; run base2 $B; run new2 $N; run base3 $B; run new3 $N; run base4 $B; run new4 $N
cp /tmp/b_new1.txt /tmp/b_base1.txt $OUT/
