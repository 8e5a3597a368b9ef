#!/usr/bin/env bash
# The tree documents the product as it is; its history lives in git. Fails naming each file
# and line that speaks of the making of it: numbered work sessions or rounds, run ids (a
# letter, a number and a dash), hired machines, internal issue numbers, stories of what was
# tried, a folder of run logs.
set -uo pipefail
src="$1"
cd "$src" || exit 2
if git rev-parse --is-inside-work-tree > /dev/null 2>&1; then
  files=$(git ls-files)
else
  files=$(find . -type f -not -path './build*' -not -path './.git/*' | sed 's|^\./||')
fi
# Built from pieces so that this script does not match itself.
s='[Ss]''ession [0-9]+|\bs[0-9]{1,3}-[a-z][a-z0-9-]*\b|\b[Rr]ound [0-9]+ of|\b(rented|lease[sd]?)\b'
s="$s"'|not ''kept|tried,? (but )?not|#[0-9]{2,3}\b|\b[Ii]ssue [0-9]+|gpu''_runs|work ''history'
hits=$(echo "$files" | grep -v -e '^tests/docs/history_test.sh$' -e '\.png$' -e '\.ts$' -e '\.svg$' \
       | tr '\n' '\0' | xargs -0 grep -nIE "$s" -- 2>/dev/null)
if [ -n "$hits" ]; then
  echo "these lines speak of the history of the work (it belongs in git and in issues, not the tree):"
  echo "$hits"
  exit 1
fi
logs="docs/gpu""_runs"
[ -d "$logs" ] && { echo "$logs: run logs belong in the issue, not the tree"; exit 1; }
echo "no file speaks of the history of the work ($(echo "$files" | wc -l) files)"
