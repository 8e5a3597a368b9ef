#!/usr/bin/env bash
# The generated reference pages match the programs: regenerates docs/reference into a
# temporary folder with tools/make_reference.sh and compares. On failure, rerun
#   tools/make_reference.sh BUILD_DIR
# and commit docs/reference.
set -uo pipefail
src="$1" build="$2"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$src/tools/make_reference.sh" "$build" "$tmp" > /dev/null || exit 1
rc=0
for page in cli.md settings.md; do
  if ! diff -u "$src/docs/reference/$page" "$tmp/$page"; then
    echo "docs/reference/$page is out of date: run tools/make_reference.sh $build and commit it" >&2
    rc=1
  fi
done
[ $rc -eq 0 ] && echo "docs/reference/cli.md and settings.md match the programs"
exit $rc
