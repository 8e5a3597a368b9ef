#!/usr/bin/env bash
# Brings translations/*.ts up to date with the sources: writes gui/registry_strings.cpp (the
# core's settings and tone-mapping words) from a build, then runs Qt Linguist's lupdate over
# the studio's and the wizard's sources. New strings arrive unfinished: translate them (Qt
# Linguist, or by hand in the .ts), and the Translations tests pass again.
#   tools/update_translations.sh [BUILD_DIR]   (default build-ci)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build-ci}"
lupdate=/usr/lib/qt6/bin/lupdate
[ -x "$lupdate" ] || { echo "update_translations: $lupdate is missing (apt-get install qt6-l10n-tools)" >&2; exit 1; }
cmake --build "$build" --target hdrfusion-registry-strings
"$build"/tests/hdrfusion-registry-strings > gui/registry_strings.cpp.new
mv gui/registry_strings.cpp.new gui/registry_strings.cpp
for ts in translations/*.ts; do
  "$lupdate" -silent -no-obsolete -locations none -I . -I core gui calibration_wizard app/studio app/wizard -ts "$ts"
done
echo "update_translations: $(grep -c '<message' translations/hdrfusion_de.ts) messages," \
     "$(grep -c 'type="unfinished"' translations/hdrfusion_de.ts) unfinished"
