#!/usr/bin/env bash
# The main job on the built-in synthetic scene: what the README's first command runs.
# Grows with the project; today: simulate an auto-exposure RGB-D sequence of the built-in
# room and describe it.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/app/hdrfusion
out=${1:-out/demo}
if [ -e "$out" ]; then rm -rf "$out.previous"; mv "$out" "$out.previous"; fi
"$bin" simulate --out "$out" --scene room --frames 90 --size 320x240 --ae flicker
"$bin" info "$out"
echo "demo: sequence in $out (rgb/, depth/, hdr/, exposure.txt, groundtruth.txt, sensor.json)"
