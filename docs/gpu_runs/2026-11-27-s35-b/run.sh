#!/usr/bin/env bash
set -u
N=build-gpu/app/bench/hdrfusion-bench
B=_base/tree/build-gpu/app/bench/hdrfusion-bench
[ -x $B ] || (cd _base/tree && cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 16 --target hdrfusion-bench > /tmp/build_base.txt 2>&1; echo "base build rc=$?")
[ -x $N ] || (cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent > /dev/null 2>&1 && cmake --build --preset core-gpu -j 16 --target hdrfusion-bench > /tmp/build_new.txt 2>&1; echo "new build rc=$?")
ls -la $N $B | awk '{print $5, $NF}'
/usr/local/cuda/bin/ncu --kernel-name-base demangled --kernel-name regex:RaycastInto --launch-skip 30 --launch-count 1 --set full $B --frames 40 --case 640x480x20 --device cuda --voxel compact > $OUT/ncu_rc_full.txt 2>&1
echo "ncu rc=$?"
grep -v "^==PROF==" $OUT/ncu_rc_full.txt | grep -E "Duration|Registers|Achieved Occupancy|Theoretical Occupancy|Memory Throughput|L1/TEX Hit|L2 Hit|DRAM Throughput|Compute \(SM\)|Warp Cycles Per Issued|Stall|Block Limit|Branch Efficiency|Avg. Active Threads|Issued Warp|No Eligible|Waves Per SM|Local" | head -60
for X in $B $N; do
/usr/local/cuda/bin/ncu --kernel-name-base demangled --kernel-name regex:RaycastInto --launch-skip 30 --launch-count 30 --metrics gpu__time_duration.sum $X --frames 60 --case 640x480x20 --device cuda --voxel compact > /tmp/n.txt 2>&1
echo "== $X: $(grep gpu__time_duration /tmp/n.txt | head -1 | awk '{print $(NF-1)}') $(grep gpu__time_duration /tmp/n.txt | awk '{print $NF}' | sort -n | tr '\n' ' ')"
done
