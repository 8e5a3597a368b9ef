#!/usr/bin/env bash
# session 39 (d): where the ray cast's and the tracker's instructions go, per source line:
# the bench built with -lineinfo, ncu's SourceCounters of one ray cast and one tracker run at
# 640x480 (the tree at de07d82), exported per CUDA source line.
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
cmake -S . -B build-li -G Ninja -DCMAKE_BUILD_TYPE=Release -DHDRF_CORE_ONLY=ON -DHDRF_BUILD_TESTS=OFF -DCMAKE_CUDA_ARCHITECTURES=90 \
  -DHDRF_SHARED_DATA_DIR=/nonexistent -DCMAKE_CUDA_FLAGS=-lineinfo > /dev/null 2>&1
cmake --build build-li --target hdrfusion-bench -j 16 > /tmp/build.txt 2>&1; echo "build rc=$?"
N=build-li/app/bench/hdrfusion-bench
NCU=/usr/local/cuda/bin/ncu
$NCU --version | tail -1
for k in RaycastInto RunKernel; do
  $NCU --kernel-name-base demangled --kernel-name regex:$k --launch-skip 20 --launch-count 1 --section SourceCounters \
    --section WarpStateStats --import-source yes -f -o /tmp/$k $N --frames 12 --device cuda --voxel compact --case 640x480x20 > /tmp/ncu_$k.txt 2>&1
  echo "ncu $k rc=$?"; tail -2 /tmp/ncu_$k.txt
  $NCU -i /tmp/$k.ncu-rep --page source --csv --print-source cuda > $OUT/${k}_cuda_lines.csv 2> /tmp/err_$k.txt; echo "source cuda rc=$? $(wc -l < $OUT/${k}_cuda_lines.csv) lines"; head -3 /tmp/err_$k.txt
  $NCU -i /tmp/$k.ncu-rep --page details --print-details all > $OUT/${k}_details.txt 2>&1; echo "details rc=$?"
  gzip -k -c /tmp/$k.ncu-rep > $OUT/$k.ncu-rep.gz
done
ls -la $OUT
