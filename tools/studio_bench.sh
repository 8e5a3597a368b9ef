#!/usr/bin/env bash
# The studio's scan against the CLI's on the same source and device, one after the other in one
# run: frames per second of each (reading the source included), the studio's share of the CLI's
# rate, and how often the studio's 3-D view drew a new surface while scanning. Prints a table.
# REPEAT=N runs the pair N times, one after the other (a shared machine's speed drifts: the
# ratio of each pair and their median are what to quote).
#
#   [REPEAT=N] tools/studio_bench.sh [SOURCE] [DEVICE] [BUILD_DIR]
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
for i in $(seq 1 "${REPEAT:-1}"); do
  "$CLI" scan "$SOURCE" --device "$DEVICE" --out "$TMP/cli$i" --autosave 0 >"$TMP/cli$i.log" 2>&1 ||
    { cat "$TMP/cli$i.log" >&2; exit 1; }
  XDG_CONFIG_HOME="$TMP/config$i" eval $X "$STUDIO" --no-recovery-offer --source "'$SOURCE'" --device "$DEVICE" \
    --frames "$FRAMES" --screenshot "$TMP/studio$i.png" >"$TMP/studio$i.log" 2>&1 || { cat "$TMP/studio$i.log" >&2; exit 1; }
done
python3 - "$TMP" "${REPEAT:-1}" "$SOURCE" "$DEVICE" <<'PY'
import json, statistics, sys
tmp, n, source, device = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
print("| run | source | device | frames | CLI frames/s | studio frames/s | studio / CLI | 3-D surface updates/s | preview lattice | studio frames shown |")
print("|---|---|---|---|---|---|---|---|---|---|")
ratios, runs = [], []
for i in range(1, n + 1):
    cli = json.load(open(f"{tmp}/cli{i}/report.json"))
    st = json.load(open(f"{tmp}/studio{i}.png.json"))
    c, s = cli["wall_fps"], st["scan_fps"]
    ratios.append(s / c)
    runs.append(st)
    print(f"| {i} | {source} | {device} | {cli['frames']} | {c:.1f} | {s:.1f} | {100 * s / c:.0f} % | "
          f"{st['mesh_updates_per_s']:.1f} | {st.get('display', {}).get('preview_step', '-')} | {st['frames_shown']} |")
if n > 1:
    print(f"\nmedian studio / CLI over {n} pairs: {100 * statistics.median(ratios):.0f} %")
print()
print("Where the studio's CPU went (seconds of each thread over the whole run) and the window's own work:")
print()
names = sorted({k for st in runs for k in st.get("cpu_seconds_by_thread", {})})
print("| run | " + " | ".join(names) + " | 2-D refreshes | 2-D views CPU ms | surface hand-over CPU ms | 3-D redraws | 3-D redraw ms |")
print("|" + "---|" * (len(names) + 6))
for i, st in enumerate(runs, 1):
    th, d = st.get("cpu_seconds_by_thread", {}), st.get("display", {})
    print(f"| {i} | " + " | ".join(f"{th.get(k, 0):.1f}" for k in names) +
          f" | {st['frames_shown']} | {d.get('views_cpu_ms', 0):.0f} | {d.get('mesh_handover_cpu_ms', 0):.0f} | "
          f"{d.get('redraws', 0)} | {d.get('redraw_ms', 0):.0f} |")
PY
