#!/usr/bin/env bash
# session 40 (d): the keyframe made once the ray cast is queued (in the tree): gpu tests and
# recovery_tests on CUDA; then the frame's upload in pieces of 128 KiB (as now), 512 KiB, 1 MiB
# and 4 MiB (each part whole), chosen by HDRF_PIECE_KIB in an experiment build
# (piece_env.patch), alternating, 640x480 and 320x240.
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
R=docs/gpu_runs/2026-11-28-s40-d
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=/tmp/gc tools/gpu_check.sh > /tmp/gc.txt 2>&1; echo "gpu_check rc=$?"
grep -E "tests passed|FAILED|Failure|Expected|Which is|scan parity:|least stage" /tmp/gc/ctest_gpu.txt | head -20
cp /tmp/gc/ctest_gpu.txt /tmp/gc/gpu_env.txt $OUT/
cmake --build --preset core-gpu -j 16 --target recovery_tests > /tmp/build_rec.txt 2>&1; echo "recovery build rc=$?"
HDRF_TEST_DEVICE=cuda timeout 250 build-gpu/tests/recovery_tests > $OUT/recovery_cuda.txt 2>&1; echo "recovery_tests on cuda rc=$?"; grep -E "PASSED|FAILED|Failure" $OUT/recovery_cuda.txt | head
patch -p1 < $R/piece_env.patch > /dev/null || exit 1
cmake --build --preset core-gpu -j 16 --target hdrfusion-bench > /tmp/build_piece.txt 2>&1; echo "piece build rc=$?"
for i in 1 2 3; do
  for k in 128 512 1024 4096; do
    HDRF_PIECE_KIB=$k build-gpu/app/bench/hdrfusion-bench --frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20 > /tmp/b_${k}_$i.txt 2>&1
    grep -E '^\| cuda \| compact \| [0-9]+x[0-9]+ \| [0-9]+ \| [0-9.]+ \| (convert|integrate) \|' /tmp/b_${k}_$i.txt | cut -d'|' -f4,6,7,8,11,12 | tr '\n' ' ' | sed "s/^/== $k $i:/"; echo
    grep -A5 'not timed' /tmp/b_${k}_$i.txt | grep '^| cuda' | cut -d'|' -f4,6-9 | sed "s/^/== $k $i not timed:/"
  done
done
cp /tmp/b_128_1.txt /tmp/b_512_1.txt /tmp/b_1024_1.txt /tmp/b_4096_1.txt $OUT/
