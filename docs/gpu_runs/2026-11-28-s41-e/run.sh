#!/usr/bin/env bash
# session 41 (e): the trilinear sample's short way (a cell inside one brick: one look-up, fixed
# offsets) on the GPU, now that the ray's walk is a kernel of its own: variant "all" takes it
# wherever the CPU does; variant "walk" only in the walk's samples (the shading's radiance the
# general way). The same corners, order and weights either way, so the same bits. Bench at
# 640x480 and 320x240 against the tree (aa7babb), alternating, three rounds; ncu's stall
# reasons of the tree's two ray-cast kernels.
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
for v in all walk; do
  mkdir -p /tmp/$v && tar --exclude=./build-gpu --exclude=./_base -cf - . | tar -xf - -C /tmp/$v
  python3 - /tmp/$v/core/volume/volume_impl.h <<'PY'
import sys
p = sys.argv[1]; s = open(p).read()
old = "    (void)wanted;\n    return false;\n#else"
assert old in s
s = s.replace(old, "    return wanted;\n#else")
open(p, "w").write(s)
PY
done
python3 - /tmp/walk/core/volume/raycast_impl.h <<'PY'
import sys
p = sys.argv[1]; s = open(p).read()
old = "V.SampleRadiance(ps, &rad, &nrv, hint)) {"
assert old in s
s = s.replace(old, "V.SampleRadiance(ps, &rad, &nrv, hint, false)) {")
open(p, "w").write(s)
PY
cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1
cmake --build --preset core-gpu -j 6 --target hdrfusion-bench > /tmp/build_tree.txt 2>&1 &
for v in all walk; do ( cd /tmp/$v && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 5 --target hdrfusion-bench > /tmp/build_$v.txt 2>&1; echo "$v build rc=$?" ) & done
wait
declare -A B=([tree]=build-gpu/app/bench/hdrfusion-bench [all]=/tmp/all/build-gpu/app/bench/hdrfusion-bench [walk]=/tmp/walk/build-gpu/app/bench/hdrfusion-bench)
for i in 1 2 3; do
  for v in tree all walk; do
    ${B[$v]} --frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20 > /tmp/b_${v}_$i.txt 2>&1
    grep -E '^\| cuda \| compact \| [0-9]+x[0-9]+ \| [0-9]+ \| [0-9.]+ \| raycast \|' /tmp/b_${v}_$i.txt | cut -d'|' -f4,8,12 | tr '\n' ' ' | sed "s/^/== $v $i raycast:/"; echo
    grep -A5 'not timed' /tmp/b_${v}_$i.txt | grep '^| cuda' | cut -d'|' -f4,6-9 | sed "s/^/== $v $i not timed:/"
  done
done
cp /tmp/b_tree_1.txt /tmp/b_all_1.txt /tmp/b_walk_1.txt $OUT/
for v in tree all; do
  /usr/local/cuda/bin/ncu --kernel-name-base demangled --kernel-name regex:"RaycastInTwoPasses" --launch-skip 40 --launch-count 4 \
    --metrics gpu__time_duration.sum,launch__registers_per_thread,smsp__inst_executed.sum,smsp__thread_inst_executed_per_inst_executed.ratio,smsp__average_warps_issue_stalled_no_instruction_per_issue_active.ratio,smsp__average_warps_issue_stalled_long_scoreboard_per_issue_active.ratio,smsp__average_warps_issue_stalled_wait_per_issue_active.ratio,smsp__warps_active.avg.per_cycle_active \
    ${B[$v]} --frames 30 --device cuda --voxel compact --case 640x480x20 > $OUT/ncu_$v.txt 2>&1
  echo "ncu $v rc=$?"; grep -E "gpu__time|registers|inst_executed|stalled|warps_active" $OUT/ncu_$v.txt | sed 's/  */ /g' | head -16
done
