#!/usr/bin/env bash
set -u
(cd _base/tree && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 6 --target hdrfusion-bench > /tmp/build_base.txt 2>&1; echo "head build rc=$?") &
HDRF_GPU_ALL=0 HDRF_TONEMAP_BENCH=0 HDRF_GPU_BENCH=0 OUT=$OUT/gc tools/gpu_check.sh > $OUT/gc.txt 2>&1
echo "gpu_check rc=$?"; grep -E "tests passed|FAILED|Failure|Expected|Which is|trajector|error" $OUT/gc/ctest_gpu.txt | head -12
wait
ARGS="--frames 200 --device cuda --voxel compact --case 640x480x20 --case 320x240x20"
run() { # tag bin
  $2 $ARGS > $OUT/b_$1.txt 2>&1
  echo "== $1"
  awk -F'|' '/^\| device \| voxel \| size \| voxel size \| ms\/frame timed/{t=2} /^$/{t=0} t==2 && /^\| cuda/{print "  untimed", $4, $5, $6, $7, $8, $9}' $OUT/b_$1.txt
}
B=_base/tree/build-gpu/app/bench/hdrfusion-bench
N=build-gpu/app/bench/hdrfusion-bench
run head1 $B; run new1 $N; run head2 $B; run new2 $N; run head3 $B; run new3 $N
for b in $B $N; do
/usr/local/cuda/bin/ncu --cache-control none --clock-control none --metrics gpu__time_duration.sum -k regex:SelectKernel --launch-skip 20 --launch-count 5 $b --frames 40 --case 640x480x20 --device cuda --voxel compact > /tmp/ncu.txt 2>&1
echo "ncu $b"; grep -E "gpu__time_duration" /tmp/ncu.txt
done
timeout 240 env HDRF_GPU_ARCHS="75;86;89;90" bash -c 'cmake -S . -B build-gpu-archs -G Ninja -DCMAKE_BUILD_TYPE=Release -DHDRF_CORE_ONLY=ON -DHDRF_BUILD_TESTS=OFF -DCMAKE_CUDA_ARCHITECTURES="75;86;89;90" > /dev/null 2>&1 && cmake --build build-gpu-archs --target hdrfusion_core -j 16 > /tmp/archs.txt 2>&1; echo "release archs build rc=$?"; grep -E "error" /tmp/archs.txt | head -5'
rm -f $OUT/gc/build.txt $OUT/gc/gpu_env.txt $OUT/b_head2.txt $OUT/b_head3.txt $OUT/b_new2.txt $OUT/b_new3.txt
