#!/usr/bin/env bash
# Every relative link in the Markdown documentation points at a file that exists, so a page
# moved or renamed cannot leave a reader at a dead end.
set -uo pipefail
cd "$1" || exit 2
rc=0 n=0
while IFS= read -r md; do
  dir=$(dirname "$md")
  while IFS= read -r target; do
    path="${target%%#*}"
    [ -z "$path" ] && continue
    n=$((n + 1))
    if [ ! -e "$dir/$path" ]; then echo "$md: link to $target: no such file"; rc=1; fi
  done < <(grep -oE '\]\([^) ]+\)' "$md" | sed -E 's/^\]\(//; s/\)$//' | grep -vE '^(https?:|mailto:|#)')
done < <(find . -name '*.md' -not -path './build*' -not -path './.git/*' -not -path './_deps/*')
[ $rc -eq 0 ] && echo "all $n relative links in the Markdown pages resolve"
exit $rc
