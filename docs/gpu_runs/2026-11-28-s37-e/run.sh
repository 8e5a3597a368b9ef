#!/usr/bin/env bash
# session 37 (e): the exposure select's weights added per bin within a warp first; gpu tests, ncu of the select, start (HEAD) / new
set -u
(cd _base/tree && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 6 --target hdrfusion-bench > /tmp/build_base.txt 2>&1; echo "base build rc=$?") &
cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1
cmake --build --preset core-gpu -j 10 --target gpu_tests hdrfusion-bench > /tmp/build_new.txt 2>&1; echo "new build rc=$?"; grep -E "error" /tmp/build_new.txt | head -5
build-gpu/tests/gpu_tests --gtest_filter='GpuExposureParity.*:GpuParity.HundredFrameScanTrajectoriesAgree:GpuParity.StagesNotTimedGiveTheSameScan:Encodings/GpuStageParity.*' > $OUT/gpu_tests.txt 2>&1; echo "gpu_tests rc=$?"; grep -E "PASSED|FAILED|Failure|SKIPPED|scan parity|median" $OUT/gpu_tests.txt | head -20
wait
S=_base/tree/build-gpu/app/bench/hdrfusion-bench
N=build-gpu/app/bench/hdrfusion-bench
for t in S N; do b=${!t}
  /usr/local/cuda/bin/ncu --kernel-name regex:SelectKernel --launch-skip 10 --launch-count 12 --metrics gpu__time_duration.sum $b --frames 20 --device cuda --voxel compact --case 640x480x20 > /tmp/ncu_$t.txt 2>&1
  echo "ncu $t rc=$?: $(grep -E 'gpu__time_duration' /tmp/ncu_$t.txt | awk '{print $NF}' | tr '\n' ' ')"
done
cp /tmp/ncu_S.txt /tmp/ncu_N.txt $OUT/
ARGS="--frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20"
run() { # tag bin
  $2 $ARGS > /tmp/b_$1.txt 2>&1
  echo "== $1"
  awk -F'|' '/^\| device \| voxel \| size \| voxel size \| convert/{t=1} /^\| device \| voxel \| size \| voxel size \| ms\/frame timed/{t=2} /^$/{t=0} t==1 && /^\| cuda/{print $4,$5,$6,$7,$8,$10,$11,$12,$18} t==2 && /^\| cuda/{print "  untimed", $4, $5, $6, $7, $8, $9}' /tmp/b_$1.txt
}
for i in 1 2; do run start$i $S; run new$i $N; done
cp /tmp/b_new1.txt /tmp/b_start1.txt $OUT/
