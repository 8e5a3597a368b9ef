#!/usr/bin/env bash
# The main job on the built-in synthetic scene (what the README's first command runs).
#
# With a display: opens HDRFusion Studio on the synthetic sensor (room, flickering auto
# exposure) and starts scanning; the operator watches, pauses, exports.
# Without a display (a server, CI, a container): says so and runs the same scan headless:
# simulate the sequence, scan it with the HDRFusion engine (normalized radiance + ICP
# tracking, TSDF + HDR radiance fusion, mesh), measure the result against the truth, and
# export it as a textured HDR asset (docs/export.md).
#   DEMO_HEADLESS=1 forces the headless run; FRAMES sets the length (150).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/app/hdrfusion
studio=build/app/studio/hdrfusion-studio
out=${1:-out/demo}
frames=${FRAMES:-150}
# The GPU when this build has CUDA and a GPU answers (a 5-frame probe), the CPU otherwise.
device=${DEVICE:-cpu}
if [ -z "${DEVICE:-}" ] && [ -x build/app/bench/hdrfusion-bench ] &&
   build/app/bench/hdrfusion-bench --frames 5 --device cuda --case 64x48x40 2>/dev/null | grep -q "| cuda |"; then
  device=cuda
fi
if [ -z "${DEMO_HEADLESS:-}" ] && { [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; } && [ -x "$studio" ]; then
  echo "demo: opening HDRFusion Studio on the synthetic room ($frames frames, flickering exposure, $device)"
  exec "$studio" --source "synthetic:scene=room,frames=$frames,ae=flicker" --device "$device" --start
fi
if [ -z "${DEMO_HEADLESS:-}" ]; then
  echo "demo: no display here (DISPLAY is not set), so the studio cannot open; running the same scan headless"
fi
rm -rf "$out.previous"
if [ -e "$out" ]; then mv "$out" "$out.previous"; fi
"$bin" simulate --out "$out/sequence" --scene room --frames "$frames" --size 320x240 --ae flicker
"$bin" info "$out/sequence"
"$bin" scan "$out/sequence" --out "$out/scan" --device "$device"
"$bin" eval "$out/sequence" "$out/scan"
"$bin" export "$out/scan" --out "$out/asset" --render 1280x960
echo "demo: sequence in $out/sequence; mesh, trajectory, renders and report in $out/scan;"
echo "demo: textured HDR asset (OBJ + EXR texture, glTF, PLY, render) in $out/asset"
