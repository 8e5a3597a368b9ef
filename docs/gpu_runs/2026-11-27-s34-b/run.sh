#!/usr/bin/env bash
# session 34 GPU run: baseline (e79b7bf) vs working tree
set -u
R=$(pwd)
mkdir -p $OUT/gc
( cd _base/tree && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > $OUT/base_cfg.txt 2>&1 && cmake --build --preset core-gpu -j 6 --target hdrfusion-bench > $OUT/base_build.txt 2>&1; echo base built rc=$? >> $OUT/base_build.txt ) &
BP=$!
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=$OUT/gc tools/gpu_check.sh > $OUT/gc_stdout.txt 2>&1
echo "gpu_check rc=$?" >> $OUT/gc_stdout.txt
wait $BP
tail -1 $OUT/base_build.txt
for i in 1 2; do
  for b in base new; do
    if [ $b = base ]; then B=_base/tree/build-gpu/app/bench/hdrfusion-bench; else B=build-gpu/app/bench/hdrfusion-bench; fi
    for c in 640x480x20 320x240x20; do
      echo "== $b $c run $i" >> $OUT/bench.txt
      $B --frames 200 --device cuda --voxel compact --case $c >> $OUT/bench.txt 2>&1
    done
  done
done
grep -E "^== |^\| cuda \| compact \| [0-9x]+ \| 20 mm \| [0-9.]+ \| [0-9.]+ \| [0-9.]+ \|" $OUT/bench.txt | head -60
