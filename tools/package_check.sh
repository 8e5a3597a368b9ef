#!/usr/bin/env bash
# Builds the Debian package and tries it where a new user meets it: a fresh Debian 12 root.
#
#   tools/package_check.sh [ROOT]      (as root; ROOT default /srv/chroot/hdrfusion-pkg)
#
# 1. cpack in build-ci (the ci preset, built first) makes hdrfusion-studio_VERSION_amd64.deb;
# 2. appstreamcli validates the metainfo, and the package's file list is checked for the
#    programs, desktop entries, metainfo and icons;
# 3. ROOT is made with `debootstrap --variant=minbase bookworm` unless it exists, the package
#    is installed there with `apt-get install ./hdrfusion-studio_*.deb` (dependencies from
#    Debian), and its programs are started: `hdrfusion --help`, a 10-frame scan of the
#    synthetic room, `hdrfusion-studio --help`, and the studio and the wizard under Xvfb
#    (xvfb installed beside the package for this), with a screenshot of the studio; then
#    `man hdrfusion` and the installed documentation the Help menus open.
# The programs must start with the package's dependencies alone: a build made where the CUDA
# toolkit is installed links its runtime statically (core/CMakeLists.txt), so the package
# never needs the toolkit. Prints what it checked; exits non-zero at the first failure. The screenshot is left in
# build-ci/package-check/.
set -euo pipefail
cd "$(dirname "$0")/.."
root_dir=${1:-/srv/chroot/hdrfusion-pkg}
out=$PWD/build-ci/package-check
mkdir -p "$out"

cmake --preset ci >/dev/null
cmake --build --preset ci
(cd build-ci && cpack -G DEB >/dev/null)
deb=$(ls -t build-ci/hdrfusion-studio_*_amd64.deb | head -1)
echo "package_check: built $deb ($(du -h "$deb" | cut -f1))"
appstreamcli validate --no-net --pedantic packaging/io.github.hdrfusion.studio.metainfo.xml
dpkg-deb -c "$deb" | awk '{print $6}' > "$out/files.txt"
for f in ./usr/bin/hdrfusion ./usr/bin/hdrfusion-studio ./usr/bin/hdrfusion-calibration-wizard \
         ./usr/share/applications/hdrfusion-studio.desktop ./usr/share/applications/hdrfusion-calibration-wizard.desktop \
         ./usr/share/metainfo/io.github.hdrfusion.studio.metainfo.xml \
         ./usr/share/icons/hicolor/48x48/apps/hdrfusion-studio.png ./usr/share/icons/hicolor/scalable/apps/hdrfusion-studio.svg \
         ./usr/share/hdrfusion/sensors/xtion_1406120314.json ./usr/share/hdrfusion/ocio/config.ocio \
         ./usr/share/man/man1/hdrfusion.1 ./usr/share/man/man1/hdrfusion-studio.1 \
         ./usr/share/man/man1/hdrfusion-calibration-wizard.1 ./usr/share/doc/hdrfusion-studio/index.md \
         ./usr/share/doc/hdrfusion-studio/tutorials/scan-a-room.md ./usr/share/doc/hdrfusion-studio/LICENSE; do
  grep -qx "$f" "$out/files.txt" || { echo "package_check: $f is not in the package" >&2; exit 1; }
done
echo "package_check: depends: $(dpkg-deb -f "$deb" Depends)"

if [ ! -x "$root_dir/usr/bin/apt-get" ]; then
  echo "package_check: making a fresh Debian 12 root in $root_dir"
  debootstrap --variant=minbase bookworm "$root_dir" http://deb.debian.org/debian >/dev/null
fi
cp /etc/resolv.conf "$root_dir/etc/resolv.conf"
cp "$deb" "$root_dir/tmp/"
mountpoint -q "$root_dir/proc" || mount -t proc proc "$root_dir/proc"
trap 'umount "$root_dir/proc" 2>/dev/null || true' EXIT
in_root() { chroot "$root_dir" /usr/bin/env -i HOME=/root PATH=/usr/sbin:/usr/bin:/sbin:/bin LANG=C.UTF-8 bash -c "set -eo pipefail; $1"; }
in_root "apt-get update -q >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -q /tmp/$(basename "$deb") > /tmp/install.log 2>&1 || { tail -20 /tmp/install.log; exit 1; }"
echo "package_check: installed with apt-get install ./$(basename "$deb")"
in_root "hdrfusion --help | sed -n 1,3p"
in_root "hdrfusion scan synthetic:frames=10,size=160x120 --out /tmp/scan --autosave 0 | tail -2"
in_root "hdrfusion-studio --help | sed -n 1,3p"
in_root "DEBIAN_FRONTEND=noninteractive apt-get install -y -q xvfb xauth >/dev/null 2>&1"
in_root "xvfb-run -a -s '-screen 0 1366x768x24' hdrfusion-studio --source synthetic:frames=30 --frames 30 --start --screenshot /tmp/studio.png >/tmp/studio.log 2>&1 || { cat /tmp/studio.log; exit 1; }"
cp "$root_dir/tmp/studio.png" "$out/studio_installed.png"
# In German, as a German system starts it (the translation is inside the program; Qt's own
# words come with the package's dependency qt6-translations-l10n).
in_root "LANGUAGE=de LC_ALL=C.UTF-8 xvfb-run -a -s '-screen 0 1366x768x24' hdrfusion-studio --source synthetic:frames=5 --frames 5 --screenshot /tmp/studio_de.png >/tmp/studio_de.log 2>&1 || { cat /tmp/studio_de.log; exit 1; }"
in_root "grep -q '\"language\": \"de\"' /tmp/studio_de.png.json || { echo 'the studio did not start in German'; exit 1; }"
in_root "test -f /usr/share/qt6/translations/qtbase_de.qm"
cp "$root_dir/tmp/studio_de.png" "$out/studio_installed_de.png"
echo "package_check: the studio starts in German on a German system"
in_root "timeout 20 xvfb-run -a hdrfusion-calibration-wizard --help | sed -n 1,3p"
# The manual and the documentation the Help menus open (man-db comes as a recommended package).
in_root "MANWIDTH=80 man hdrfusion | sed -n 1,4p && man -w hdrfusion-studio hdrfusion-calibration-wizard"
in_root "test -f /usr/share/doc/hdrfusion-studio/index.md"
echo "package_check: man hdrfusion works and the documentation is installed"
echo "package_check: the installed studio's screenshot is $out/studio_installed.png"
