#!/usr/bin/env bash
# session 38 (c): the GPU ray cast in two passes (rays not done after N steps listed for a second pass); gpu tests; bench base (38e00f6) / N = 16, 8, 32, one pass; ncu of the passes
set -u
(cd _base/tree && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 6 --target hdrfusion-bench > /tmp/build_tree.txt 2>&1; echo "base build rc=$?") &
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=/tmp/gc tools/gpu_check.sh > /tmp/gc.txt 2>&1
echo "gpu_check rc=$?"; grep -E "tests passed|FAILED|Failure|Expected|Which is|error|scan parity:|place limit|first pass|renderings from afar|differ" /tmp/gc/ctest_gpu.txt | head -30
cp /tmp/gc/ctest_gpu.txt $OUT/
wait
ARGS="--frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20"
run() { # tag bin [steps]
  HDRF_TMP_FIRST_STEPS=${3:-16} $2 $ARGS > /tmp/b_$1.txt 2>&1
  echo "== $1"
  awk -F'|' '/^\| device \| voxel \| size \| voxel size \| convert/{t=1} /^\| device \| voxel \| size \| voxel size \| ms\/frame timed/{t=2} /^$/{t=0} t==1 && /^\| cuda/{print $4,$5,$6,$7,$8,$10,$11,$12,$18} t==2 && /^\| cuda/{print "  untimed", $4, $5, $6, $7, $8, $9}' /tmp/b_$1.txt
}
S=_base/tree/build-gpu/app/bench/hdrfusion-bench
N=build-gpu/app/bench/hdrfusion-bench
for i in 1 2 3; do run base$i $S; run n16_$i $N 16; run n8_$i $N 8; run n32_$i $N 32; run one$i $N 1073741824; done
cp /tmp/b_base1.txt /tmp/b_n16_1.txt $OUT/
for st in 16 1073741824; do
  HDRF_TMP_FIRST_STEPS=$st /usr/local/cuda/bin/ncu --kernel-name-base demangled --kernel-name regex:Raycast --launch-skip 30 --launch-count 20 --metrics gpu__time_duration.sum,smsp__inst_executed.sum $N --frames 20 --device cuda --voxel compact --case 640x480x20 > /tmp/ncu_$st.txt 2>&1
  echo "ncu $st rc=$?"; grep -E "^  [a-z].*Kernel|RaycastTwo|gpu__time_duration|smsp__inst" /tmp/ncu_$st.txt | awk '{print $1, $NF}' | paste - - - | head -24
  cp /tmp/ncu_$st.txt $OUT/
done
