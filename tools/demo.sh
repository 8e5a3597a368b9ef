#!/usr/bin/env bash
# The main job on the built-in synthetic scene (what the README's first command runs):
# simulate an auto-exposure RGB-D sequence with flickering exposure, scan it with the HDRFusion
# engine (normalized radiance + ICP tracking, TSDF + HDR radiance fusion, mesh), and measure
# the result against the ground truth.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/app/hdrfusion
out=${1:-out/demo}
frames=${FRAMES:-150}
rm -rf "$out.previous"
if [ -e "$out" ]; then mv "$out" "$out.previous"; fi
"$bin" simulate --out "$out/sequence" --scene room --frames "$frames" --size 320x240 --ae flicker
"$bin" info "$out/sequence"
"$bin" scan "$out/sequence" --out "$out/scan"
"$bin" eval "$out/sequence" "$out/scan"
echo "demo: sequence in $out/sequence; mesh, trajectory, renders and report in $out/scan"
