#!/usr/bin/env bash
# session 38 (b): the bench's floors with the bus and the margin table, at 320/640/1280/2560; ncu per kernel (instructions, bytes) at 640x480
set -u
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader
cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1
cmake --build --preset core-gpu -j 16 --target hdrfusion-bench > /tmp/build.txt 2>&1; echo "build rc=$?"; grep -E "error" /tmp/build.txt | head
N=build-gpu/app/bench/hdrfusion-bench
for p in "320x240x20 640x480x20" "640x480x20 1280x960x20" "640x480x20 2560x1920x20"; do
  set -- $p
  f=$OUT/b_${1%%x*}_${2%%x*}.txt
  $N --frames 100 --device cuda --voxel compact --case $1 --case $2 > $f 2>&1; echo "bench $p rc=$?"
  sed -n '/^| cuda | compact | [0-9]*x[0-9]* | 20 mm | [0-9]/p;/How each stage/,/Gauss/p' $f | grep "^|" 
  grep -A4 "not timed" $f | grep "^| cuda"
done
/usr/local/cuda/bin/ncu --csv --page raw --metrics gpu__time_duration.sum,smsp__inst_executed.sum,dram__bytes.sum,lts__t_bytes.sum,sm__cycles_elapsed.avg.per_second,launch__grid_size,launch__block_size,launch__registers_per_thread --launch-skip 400 --launch-count 300 $N --frames 12 --device cuda --voxel compact --case 640x480x20 > $OUT/ncu_640.csv 2> /tmp/ncu_err.txt; echo "ncu rc=$? $(wc -l < $OUT/ncu_640.csv) lines"; tail -3 /tmp/ncu_err.txt
