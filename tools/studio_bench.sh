#!/usr/bin/env bash
# The studio's scan against the CLI's on the same source and device, one after the other in one
# run: frames per second of each (reading the source included), the studio's share of the CLI's
# rate, and how often the studio's 3-D view drew a new surface while scanning. Prints a table.
#
#   tools/studio_bench.sh [SOURCE] [DEVICE] [BUILD_DIR]
#   (defaults: synthetic:frames=300,ae=flicker cpu build-ci; needs xvfb-run without a display)
set -euo pipefail
SOURCE=${1:-synthetic:frames=300,ae=flicker}
DEVICE=${2:-cpu}
BUILD=${3:-build-ci}
CLI="$BUILD/app/hdrfusion"
STUDIO="$BUILD/app/studio/hdrfusion-studio"
for b in "$CLI" "$STUDIO"; do
  [ -x "$b" ] || { echo "studio_bench: $b is not built (cmake --build --preset ci)" >&2; exit 1; }
done
FRAMES=$(echo "$SOURCE" | sed -n 's/.*frames=\([0-9]*\).*/\1/p')
[ -n "$FRAMES" ] || { echo "studio_bench: the source must name its frames (frames=N)" >&2; exit 1; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
X=""
[ -n "${DISPLAY:-}" ] || X="xvfb-run -a -s -screen\ 0\ 1920x1080x24"
"$CLI" scan "$SOURCE" --device "$DEVICE" --out "$TMP/cli" --autosave 0 >"$TMP/cli.log" 2>&1 ||
  { cat "$TMP/cli.log" >&2; exit 1; }
XDG_CONFIG_HOME="$TMP/config" eval $X "$STUDIO" --no-recovery-offer --source "'$SOURCE'" --device "$DEVICE" \
  --frames "$FRAMES" --screenshot "$TMP/studio.png" >"$TMP/studio.log" 2>&1 || { cat "$TMP/studio.log" >&2; exit 1; }
python3 - "$TMP/cli/report.json" "$TMP/studio.png.json" "$SOURCE" "$DEVICE" <<'PY'
import json, sys
cli = json.load(open(sys.argv[1]))
st = json.load(open(sys.argv[2]))
c, s = cli["wall_fps"], st["scan_fps"]
print("| source | device | frames | CLI frames/s | studio frames/s | studio / CLI | 3-D surface updates/s | studio frames shown |")
print("|---|---|---|---|---|---|---|---|")
print(f"| {sys.argv[3]} | {sys.argv[4]} | {cli['frames']} | {c:.1f} | {s:.1f} | {100 * s / c:.0f} % | "
      f"{st['mesh_updates_per_s']:.1f} | {st['frames_shown']} |")
PY
