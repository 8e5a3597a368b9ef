#!/usr/bin/env bash
# A timeline of the GPU's work without Nsight Systems (the GPU machine has none): a CUPTI
# activity tracer loaded into the process through CUDA_INJECTION64_PATH writes every kernel,
# copy, memset and runtime call with its start and end; timeline.py prints a frame of it.
#
#   tools/gpu_timeline/run.sh OUT_DIR [hdrfusion-bench arguments]
#
# Builds the tracer against the CUDA toolkit's CUPTI, runs the bench under it (default: 40
# frames at 640x480 on CUDA, compact voxels) and writes OUT_DIR/trace.csv and
# OUT_DIR/bench_traced.txt. The tracer costs host time (each runtime call takes longer), so
# its timings are for finding the order and gaps of the work, not for reporting speed.
set -euo pipefail
cd "$(dirname "$0")/../.."
out="${1:?usage: tools/gpu_timeline/run.sh OUT_DIR [bench arguments]}"
shift
mkdir -p "$out"
cuda=/usr/local/cuda
g++ -O2 -shared -fPIC -I"$cuda/include" tools/gpu_timeline/tracer.cpp -L"$cuda/lib64" -lcupti \
  -Wl,-rpath,"$cuda/lib64" -o "$out/libtracer.so"
args=("$@")
[ ${#args[@]} -gt 0 ] || args=(--frames 40 --device cuda --voxel compact --case 640x480x20)
CUDA_INJECTION64_PATH="$out/libtracer.so" TRACE_OUT="$out/trace.csv" build-gpu/app/bench/hdrfusion-bench "${args[@]}" \
  > "$out/bench_traced.txt" 2>&1
echo "$(wc -l < "$out/trace.csv") events in $out/trace.csv; a frame: tools/gpu_timeline/timeline.py $out/trace.csv -4"
