#!/usr/bin/env bash
# Writes the programs' manual pages with help2man, from their own --help:
#   tools/make_man.sh OUT_DIR HDRFUSION STUDIO WIZARD BENCH
# hdrfusion(1) also holds every command's --help (section COMMANDS). The build runs this
# (target `man`, where help2man is installed) and the package installs the pages.
set -euo pipefail
[ $# -eq 5 ] || { echo "usage: tools/make_man.sh OUT_DIR HDRFUSION STUDIO WIZARD BENCH" >&2; exit 2; }
out="$1" cli="$2" studio="$3" wizard="$4" bench="$5"
export QT_QPA_PLATFORM=offscreen LC_ALL=C.UTF-8 LANGUAGE=en
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
mkdir -p "$out"
version=$("$cli" --version | awk '{ print $2 }')
inc=$(mktemp)
trap 'rm -f "$inc"' EXIT

roff_text() {  # stdin to roff that prints as is: backslashes escaped, no line read as a request
  sed -e 's/\\/\\e/g' -e "s/^\([.']\)/\\\\\&\1/"
}
see_also() {  # the other pages and the documentation
  printf '[SEE ALSO]\n%s\n.PP\nThe documentation: /usr/share/doc/hdrfusion-studio/index.md (docs/index.md in the source).\n' "$1"
}

{
  printf '[COMMANDS]\n'
  for c in $("$cli" --help | sed -n '/^Subcommands:/,/^$/p' | awk 'NR > 1 && NF { print $1 }'); do
    printf '.SS "hdrfusion %s"\n.nf\n' "$c"
    "$cli" "$c" --help | roff_text
    printf '.fi\n'
  done
  printf '[EXIT STATUS]\n0 done; 1 a named error (one line on stderr naming the file, line or setting at fault); 2 an unexpected error; 130 interrupted (Ctrl-C), the model kept in the recovery file.\n'
  see_also '.BR hdrfusion-studio (1),
.BR hdrfusion-calibration-wizard (1),
.BR hdrfusion-bench (1)'
} > "$inc"
help2man --no-info --section 1 --name "HDR RGB-D scanning for auto-exposure cameras" \
  --include "$inc" "$cli" > "$out/hdrfusion.1"

see_also '.BR hdrfusion (1),
.BR hdrfusion-calibration-wizard (1)' > "$inc"
help2man --no-info --section 1 --version-string "$version" --name "the HDRFusion scanning studio" \
  --include "$inc" "$studio" > "$out/hdrfusion-studio.1"

see_also '.BR hdrfusion (1),
.BR hdrfusion-studio (1)' > "$inc"
help2man --no-info --section 1 --version-string "$version" --name "guided camera calibration for HDRFusion" \
  --include "$inc" "$wizard" > "$out/hdrfusion-calibration-wizard.1"

see_also '.BR hdrfusion (1)' > "$inc"
help2man --no-info --section 1 --no-discard-stderr --version-string "$version" \
  --name "the HDRFusion engine benchmark on the core alone" --include "$inc" "$bench" > "$out/hdrfusion-bench.1"
echo "make_man: wrote $(ls "$out"/*.1 | wc -l) manual pages to $out"
