#!/usr/bin/env bash
# Regenerates docs/performance.md, the product's current speed figures: every suite of
# `hdrfusion bench --markdown` on this machine, then the GPU tables that
# `hdrfusion-bench --markdown` printed on a machine with an NVIDIA GPU (tools/gpu_check.sh
# writes them to bench.md and bench_tonemap.md in its log folder).
#
#   tools/performance.sh [--build DIR] [--gpu FILE]... [--out FILE]
#
# Run it on an otherwise idle machine: the tables are wall-clock measurements.
set -euo pipefail
cd "$(dirname "$0")/.."
build=build out=docs/performance.md gpu=()
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build="$2"; shift 2 ;;
    --gpu) gpu+=("$2"); shift 2 ;;
    --out) out="$2"; shift 2 ;;
    *) echo "usage: tools/performance.sh [--build DIR] [--gpu FILE]... [--out FILE]" >&2; exit 2 ;;
  esac
done
cli="$build/app/hdrfusion"
[ -x "$cli" ] || { echo "performance: $cli is not built" >&2; exit 2; }
commit=$(git rev-parse --short HEAD 2>/dev/null || echo "unknown")
[ -n "$(git status --porcelain --untracked-files=no 2>/dev/null)" ] && commit="$commit with local changes"
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
{
  printf '# Performance\n\n'
  printf 'The current speed of the programs, as `tools/performance.sh` writes this page: each table\n'
  printf 'below is printed by the benchmark program named above it, on the machine it names, at\n'
  printf 'commit %s (%s). Frame rates are wall-clock time over the timed frames, after\n' "$commit" "$(date -u +%F)"
  printf 'warm-up; the synthetic frames are rendered before timing starts. Accuracy is measured\n'
  printf 'elsewhere, against ground truth: [results](results/README.md) and [evaluation.md](evaluation.md).\n\n'
  printf 'To regenerate: build (`cmake --preset default && cmake --build --preset default`), run\n'
  printf '`tools/gpu_check.sh` on a machine with an NVIDIA GPU, then\n'
  printf '`tools/performance.sh --gpu LOGS/bench.md --gpu LOGS/bench_tonemap.md` here.\n\n'
  for f in "${gpu[@]}"; do
    cat "$f"
    printf '\n'
  done
  if [ ${#gpu[@]} -eq 0 ]; then
    printf '## GPU\n\nNo GPU tables at this commit: no machine with an NVIDIA GPU was run\n'
    printf '(`tools/gpu_check.sh` there, then `--gpu` here). The CUDA backend is checked against the\n'
    printf 'CPU stage by stage by the `gpu` tests wherever a GPU is present.\n\n'
  fi
  for suite in engine sim tonemap export record; do
    echo "performance: $suite" >&2
    "$cli" bench --suite "$suite" --markdown $([ "$suite" = engine ] && echo "--device cpu")
    printf '\n'
  done
} > "$tmp"
mv "$tmp" "$out"
trap - EXIT
echo "performance: wrote $out" >&2
