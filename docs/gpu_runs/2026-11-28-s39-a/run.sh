#!/usr/bin/env bash
# session 39 (a): gpu tests at fd81667 (session 38's review mend a40d42e, host code only);
# then the bench at 640x480 for the tracker's run kernel at two blocks an SM (128 registers)
# and the ray cast's tile kernel held to fewer registers, against fd81667, alternating.
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
( cd _base/tree && HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=/tmp/gc tools/gpu_check.sh > /tmp/gc.txt 2>&1; echo "gpu_check (fd81667) rc=$?" )
grep -E "tests passed|FAILED|Failure|scan parity:|volume:" /tmp/gc/ctest_gpu.txt | head -8
cp /tmp/gc/ctest_gpu.txt /tmp/gc/gpu_env.txt $OUT/
build() {  # dir, run blocks, tile blocks
  cmake -S . -B $1 -G Ninja -DCMAKE_BUILD_TYPE=Release -DHDRF_CORE_ONLY=ON -DHDRF_BUILD_TESTS=OFF -DCMAKE_CUDA_ARCHITECTURES=90 \
    -DHDRF_SHARED_DATA_DIR=/nonexistent "-DCMAKE_CUDA_FLAGS=-DHDRF_RUN_MIN_BLOCKS=$2 -DHDRF_TILE_MIN_BLOCKS=$3" > /dev/null 2>&1
  cmake --build $1 --target hdrfusion-bench -j 5 > /tmp/build_$1.txt 2>&1; echo "build $1 rc=$?"
}
build bv_2_16 2 16 & build bv_2_20 2 20 & build bv_1_20 1 20 & wait
declare -A B=([base]=_base/tree/build-gpu/app/bench/hdrfusion-bench [r2t16]=bv_2_16/app/bench/hdrfusion-bench [r2t20]=bv_2_20/app/bench/hdrfusion-bench [r1t20]=bv_1_20/app/bench/hdrfusion-bench)
for i in 1 2 3; do
  for v in base r2t16 r2t20 r1t20; do
    ${B[$v]} --frames 200 --device cuda --voxel compact --case 640x480x20 > /tmp/b_${v}_$i.txt 2>&1
    echo "== $v $i: $(grep '^| cuda | compact | 640x480 | 20 mm | [0-9]' /tmp/b_${v}_$i.txt | head -1 | cut -d'|' -f6-12) not timed: $(grep -A4 'not timed' /tmp/b_${v}_$i.txt | grep '^| cuda' | cut -d'|' -f6-8)"
  done
done
cp /tmp/b_base_1.txt /tmp/b_r2t16_1.txt $OUT/
