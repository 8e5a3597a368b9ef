#!/usr/bin/env bash
# The fuzz targets' seed corpus: the repository's own files, and files the programs write.
#   tools/fuzz_seeds.sh HDRFUSION_PROGRAM OUT_FOLDER
# Writes OUT_FOLDER/<target>/ for every target of tests/fuzz (a 3-frame 32x24 synthetic
# sequence, its scan, mesh, renders and project). Without the program (an empty first
# argument), only the repository's files.
set -euo pipefail
cli="$1" out="$2"
root="$(cd "$(dirname "$0")/.." && pwd)"
rm -rf "$out"
mkdir -p "$out"/{text_lists,sensor_json,options_json,ply,image,exr,project,emor}
# An EMoR basis in the distribution's layout: named blocks of 1024 values (E, f0, h(1), h(2)).
awk 'BEGIN { n = split("E f0 h(1) h(2)", names, " ");
  for (b = 1; b <= n; ++b) { print names[b] " = "; for (i = 0; i < 1024; ++i) printf "%.6e%s", (b == 1 ? i / 1023 : (b == 2 ? (i / 1023) ^ 0.45 : 0.01 * sin(b * i / 160))), (i % 8 == 7 ? "\n" : " ") } }' \
  > "$out/emor/invemor.txt"
cp "$root"/resources/sensors/*.json "$out/sensor_json/"
printf '{"tracker": {"kind": "nr+icp", "frame_to_model": true}, "volume": {"voxel_m": 0.02, "tau0": 0.5}}\n' \
  > "$out/options_json/a.json"
printf '{"nr": {"patch": 5}, "pcf": 2}\n' > "$out/options_json/b.json"
if [ -z "$cli" ] || [ ! -x "$cli" ]; then
  echo "fuzz_seeds.sh: no hdrfusion program given: the corpus holds the repository's files only" >&2
  exit 0
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$cli" simulate --out "$work/seq" --frames 3 --size 32x24 >/dev/null 2>&1
XDG_STATE_HOME="$work/state" "$cli" scan "$work/seq" --out "$work/scan" --voxel-size 0.2 --frames 2 --autosave 0 >/dev/null 2>&1
cp "$work/seq/rgb.txt" "$work/seq/exposure.txt" "$work/seq/groundtruth.txt" "$out/text_lists/"
cp "$work/seq/sensor.json" "$out/sensor_json/sim.json"
cp "$(ls "$work"/seq/rgb/*.png | head -1)" "$out/image/colour.png"
cp "$(ls "$work"/seq/depth/*.png | head -1)" "$out/image/depth.png"
cp "$(ls "$work"/seq/hdr/*.exr | head -1)" "$out/exr/frame.exr"
cp "$work/scan/render_last.exr" "$out/exr/render.exr"
cp "$work/scan/mesh.ply" "$out/ply/mesh.ply"
cp "$work/scan/scan.hdrproj" "$out/project/scan.hdrproj"
echo "fuzz_seeds.sh: $(find "$out" -type f | wc -l) seed files in $out"
