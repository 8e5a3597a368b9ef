#!/usr/bin/env bash
# Writes the generated reference pages from the programs themselves:
#   docs/reference/cli.md       every program's and command's --help
#   docs/reference/settings.md  the engine's settings registry (hdrfusion settings --markdown)
#
#   tools/make_reference.sh [BUILD_DIR [OUT_DIR]]     (defaults: build, docs/reference)
#
# The test `ReferenceDocs.MatchThePrograms` runs this into a temporary folder and compares;
# after changing an option or a setting, rerun it and commit the two pages.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
out="${2:-docs/reference}"
cli="$build/app/hdrfusion"
[ -x "$cli" ] || { echo "make_reference: $cli is not built" >&2; exit 2; }
mkdir -p "$out"
export QT_QPA_PLATFORM=offscreen LC_ALL=C.UTF-8 LANGUAGE=en
commands=$("$cli" --help | sed -n '/^Subcommands:/,/^$/p' | awk 'NR > 1 && NF { print $1 }')

help_block() {  # TITLE, then the command line to run
  local title="$1"; shift
  printf '\n## %s\n\n```\n' "$title"
  # The program as a user types it, not the build folder it ran from.
  "$@" --help 2>/dev/null | sed -e 's/[[:space:]]*$//' -e "s|$(dirname "$1")/||g"
  printf '```\n'
}

{
  printf '# Command-line reference\n\n'
  printf 'Each program'"'"'s `--help`, as `tools/make_reference.sh` writes it from the programs (a test\n'
  printf 'fails when this page and the programs disagree). The engine settings every scan takes\n'
  printf '(`--KEY VALUE`) are in [settings.md](settings.md); what the programs print when something\n'
  printf 'goes wrong, and what to do, in [the FAQ](../faq.md).\n\n'
  printf 'Programs: `hdrfusion` (commands: %s), `hdrfusion-studio`, `hdrfusion-calibration-wizard`.\n' \
    "$(echo $commands | sed 's/\([a-z-]*\)/[\1](#hdrfusion-\1)/g; s/ /, /g')"
  help_block "hdrfusion" "$cli"
  for c in $commands; do help_block "hdrfusion $c" "$cli" "$c"; done
  for p in studio/hdrfusion-studio wizard/hdrfusion-calibration-wizard; do
    if [ -x "$build/app/$p" ]; then help_block "$(basename "$p")" "$build/app/$p"; fi
  done
} > "$out/cli.md"
"$cli" settings --markdown > "$out/settings.md"
echo "make_reference: wrote $out/cli.md and $out/settings.md"
