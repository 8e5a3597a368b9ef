#!/usr/bin/env bash
# session 41 (f): the six-sample gradient fallback (GradientOfSamples, taken where one of the
# 32 voxels is missing) out of line on the GPU (variant "cold"), now that the shading is a
# kernel of its own and not inside the walk's loop. The same arithmetic (no contraction), so
# the same bits. Bench at 640x480 and 320x240 against the tree (0048607), alternating, three
# rounds; ncu of the shading kernel each way.
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
mkdir -p /tmp/cold && tar --exclude=./build-gpu --exclude=./_base -cf - . | tar -xf - -C /tmp/cold
python3 - /tmp/cold/core/volume/volume_impl.h <<'PY'
import sys
p = sys.argv[1]; s = open(p).read()
old = "  HDRF_HD bool GradientOfSamples("
assert old in s
s = s.replace(old, "#if defined(__CUDACC__)\n  __host__ __device__ __noinline__\n#else\n  inline\n#endif\n  bool GradientOfSamples(")
open(p, "w").write(s)
PY
grep -c "__noinline__" /tmp/cold/core/volume/volume_impl.h
cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1
cmake --build --preset core-gpu -j 8 --target hdrfusion-bench > /tmp/build_tree.txt 2>&1 &
( cd /tmp/cold && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 8 --target hdrfusion-bench gpu_tests > /tmp/build_cold.txt 2>&1; echo "cold build rc=$?"; grep -E " error" /tmp/build_cold.txt | head -3 ) &
wait
declare -A B=([tree]=build-gpu/app/bench/hdrfusion-bench [cold]=/tmp/cold/build-gpu/app/bench/hdrfusion-bench)
for i in 1 2 3; do
  for v in tree cold; do
    ${B[$v]} --frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20 > /tmp/b_${v}_$i.txt 2>&1
    grep -E '^\| cuda \| compact \| [0-9]+x[0-9]+ \| [0-9]+ \| [0-9.]+ \| raycast \|' /tmp/b_${v}_$i.txt | cut -d'|' -f4,8,12 | tr '\n' ' ' | sed "s/^/== $v $i raycast:/"; echo
    grep -A5 'not timed' /tmp/b_${v}_$i.txt | grep '^| cuda' | cut -d'|' -f4,6-9 | sed "s/^/== $v $i not timed:/"
  done
done
cp /tmp/b_tree_1.txt /tmp/b_cold_1.txt $OUT/
for v in tree cold; do
  /usr/local/cuda/bin/ncu --kernel-name-base demangled --kernel-name regex:"RaycastInTwoPasses" --launch-skip 40 --launch-count 4 \
    --metrics gpu__time_duration.sum,launch__registers_per_thread,smsp__inst_executed.sum,smsp__average_warps_issue_stalled_no_instruction_per_issue_active.ratio \
    ${B[$v]} --frames 30 --device cuda --voxel compact --case 640x480x20 > $OUT/ncu_$v.txt 2>&1
  echo "ncu $v rc=$?"; grep -E "gpu__time|registers|inst_executed|stalled" $OUT/ncu_$v.txt | sed 's/  */ /g' | head -8
done
( cd /tmp/cold && ctest --test-dir build-gpu -R "GpuStageParity|HundredFrame" --output-on-failure > $OUT/cold_parity.txt 2>&1; echo "cold parity rc=$?"; grep -E "raycast:|tests passed" $OUT/cold_parity.txt | head -4 )
