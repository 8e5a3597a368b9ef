#!/usr/bin/env bash
# GPU checks: builds the core and its tests for sm_90 with CMake (only Eigen, OpenMP,
# GoogleTest and CUDA are needed) and runs them, the `gpu` parity tests among them.
#
#   On a machine with an NVIDIA GPU:      tools/gpu_check.sh
#   Through the workplace's device tool:  run command "tools/gpu_check.sh" (logs land in $OUT)
#
# Exit status is non-zero if the build fails, a test fails, or a `gpu` test was skipped
# (a GPU check that did not touch the GPU is not a pass).
set -euo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-build-gpu/logs}"
mkdir -p "$out"
{
  echo "== $(date -u +%FT%TZ) $(uname -m) $(nproc) cores, commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
  nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader || true
  nvcc --version | tail -n 2
  cmake --version | head -n 1
} | tee "$out/gpu_env.txt"

cmake --preset core-gpu -DHDRF_SHARED_DATA_DIR=/nonexistent 2>&1 | tail -n 3
set +e
cmake --build --preset core-gpu -j "$(nproc)" > "$out/build.txt" 2>&1
built=$?
grep -iE "error|warning" "$out/build.txt"
if [ "$built" -ne 0 ]; then
  echo "gpu_check: the build failed (rc=$built); see build.txt" >&2
  exit 2
fi
all=0
if [ "${HDRF_GPU_ALL:-1}" = 1 ]; then  # the CPU tests too (about 10 minutes); 0 runs the gpu ones only
  ctest --preset core-gpu -j 4 -LE gpu 2>&1 | tee "$out/ctest_all.txt" | tail -n 15
  all=${PIPESTATUS[0]}
fi
ctest --preset core-gpu -L gpu -V 2>&1 | tee "$out/ctest_gpu.txt" | grep -E "GPU:|parity|level|raycast|volume:|Gauss|PASSED|FAILED|SKIPPED|OK \]|Failure|Expected|Which is|<=|error" 
gpu=${PIPESTATUS[0]}
bench=0
if [ "${HDRF_GPU_BENCH:-1}" = 1 ]; then
  # Markdown with its heading, for docs/performance.md (tools/performance.sh --gpu bench.md).
  build-gpu/app/bench/hdrfusion-bench --markdown --frames "${HDRF_BENCH_FRAMES:-100}" --device "${HDRF_BENCH_DEVICE:-both}" --voxel "${HDRF_BENCH_VOXEL:-all}" 2>> "$out/bench_progress.txt" | tee "$out/bench.md"
  bench=${PIPESTATUS[0]}
fi
tonemap=0
if [ "${HDRF_TONEMAP_BENCH:-1}" = 1 ]; then
  build-gpu/app/bench/hdrfusion-bench --markdown --suite tonemap --frames "${HDRF_TONEMAP_FRAMES:-50}" 2>> "$out/bench_progress.txt" | tee "$out/bench_tonemap.md"
  tonemap=${PIPESTATUS[0]}
fi
archs=0
if [ -n "${HDRF_GPU_ARCHS:-}" ]; then
  # The release architectures (e.g. "75;86;89;90"): the core's CUDA code must compile for each.
  cmake -S . -B build-gpu-archs -G Ninja -DCMAKE_BUILD_TYPE=Release -DHDRF_CORE_ONLY=ON -DHDRF_BUILD_TESTS=OFF \
    -DCMAKE_CUDA_ARCHITECTURES="$HDRF_GPU_ARCHS" 2>&1 | tail -n 2
  cmake --build build-gpu-archs --target hdrfusion_core -j "$(nproc)" 2>&1 | tee "$out/build_archs.txt" | tail -n 3
  archs=${PIPESTATUS[0]}
  cuobjdump --list-elf build-gpu-archs/core/libhdrfusion_core.a 2>/dev/null | grep -o "sm_[0-9]*" | sort | uniq -c | tee -a "$out/build_archs.txt"
fi
set -e
echo "gpu_check: all tests rc=$all, gpu tests rc=$gpu, bench rc=$bench, tone-mapping bench rc=$tonemap, release architectures rc=$archs"
if grep -q "\[  SKIPPED \]" "$out/ctest_gpu.txt"; then
  echo "gpu_check: a gpu test was SKIPPED: no usable GPU here" >&2
  exit 3
fi
[ "$all" -eq 0 ] && [ "$gpu" -eq 0 ] && [ "$bench" -eq 0 ] && [ "$tonemap" -eq 0 ] && [ "$archs" -eq 0 ]
