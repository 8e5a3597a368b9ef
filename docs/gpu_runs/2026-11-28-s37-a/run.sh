#!/usr/bin/env bash
# session 37 (a): the frame's integration queued without a host wait; gpu tests, a mutant, recovery on CUDA, A/B bench
set -u
(cd _base/tree && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 5 --target hdrfusion-bench > /tmp/build_base.txt 2>&1; echo "start build rc=$?") &
# the mutant: no second ray cast after the host placed a frame's new bricks
rm -rf /tmp/mut && mkdir /tmp/mut && tar --exclude=./_base --exclude="./build-*" -cf - . | tar -xf - -C /tmp/mut
sed -i 's/ && raycast_unsettled_) Raycast(render_pose_, raycast_start_);/ \&\& false) Raycast(render_pose_, raycast_start_);/' /tmp/mut/core/pipeline/cuda_backend.cu
grep -c "&& false) Raycast" /tmp/mut/core/pipeline/cuda_backend.cu
(cd /tmp/mut && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 5 --target gpu_tests > /tmp/build_mut.txt 2>&1; echo "mutant build rc=$?") &
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=/tmp/gc tools/gpu_check.sh > /tmp/gc.txt 2>&1
echo "gpu_check rc=$?"; grep -E "tests passed|FAILED|Failure|Expected|Which is|error|scan parity:|new bricks a frame|place limit" /tmp/gc/ctest_gpu.txt | head -30
cp /tmp/gc/ctest_gpu.txt $OUT/
cmake --build --preset core-gpu -j 16 --target recovery_tests > /tmp/build_rec.txt 2>&1; echo "recovery build rc=$?"
HDRF_TEST_DEVICE=cuda timeout 250 build-gpu/tests/recovery_tests > $OUT/recovery_cuda.txt 2>&1; echo "recovery_tests on cuda rc=$?"; grep -E "PASSED|FAILED" $OUT/recovery_cuda.txt | head
wait
/tmp/mut/build-gpu/tests/gpu_tests --gtest_filter='*NewBricksPlaced*' > $OUT/mutant.txt 2>&1; echo "mutant rc=$? (expected to fail)"; grep -E "differ|Failure|FAILED|PASSED" $OUT/mutant.txt | head -8
ARGS="--frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20"
run() { # tag bin
  $2 $ARGS > /tmp/b_$1.txt 2>&1
  echo "== $1"
  awk -F'|' '/^\| device \| voxel \| size \| voxel size \| convert/{t=1} /^\| device \| voxel \| size \| voxel size \| ms\/frame timed/{t=2} /^$/{t=0} t==1 && /^\| cuda/{print $4,$5,$6,$7,$8,$10,$11,$12,$18} t==2 && /^\| cuda/{print "  untimed", $4, $5, $6, $7, $8, $9}' /tmp/b_$1.txt
}
B=_base/tree/build-gpu/app/bench/hdrfusion-bench
N=build-gpu/app/bench/hdrfusion-bench
for i in 1 2 3 4; do run start$i $B; run new$i $N; done
cp /tmp/b_new1.txt /tmp/b_start1.txt $OUT/
_base/prof2.sh
