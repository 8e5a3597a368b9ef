#!/usr/bin/env bash
# Installs the Debian 12 packages HDRFusion needs to build and test, only those missing.
# Run as root (or with sudo available). pfstools and pfstmo (GPL programs) are the tone-mapping
# reference the tests run; nothing links them. assimp-utils is a third-party reader the
# export tests read the OBJ and glTF back with. The CUDA toolkit is optional and never installed
# here: when nvcc is present the CUDA backend is built, otherwise the CPU backend only.
# --peers also installs the peers of the tracking benchmark (OpenCV contrib rgbd, Open3D),
# so that hdrfusion-peers is built and `hdrfusion-experiments paper --peers ...` runs them.
set -euo pipefail
packages=(
  build-essential cmake ninja-build ccache pkg-config
  libeigen3-dev libgtest-dev libcli11-dev nlohmann-json3-dev
  libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev libopencv-calib3d-dev
  libopencv-photo-dev
  libopenexr-dev zlib1g-dev libopenni2-dev
  qt6-base-dev libqt6opengl6-dev qt6-tools-dev qt6-l10n-tools qt6-translations-l10n libxkbcommon-dev libvtk9-dev libopencolorio-dev libgl-dev xvfb xauth
  libmeshoptimizer-dev libtinygltf-dev
  assimp-utils help2man
  pfstools pfstmo
)
if [ "${1:-}" = "--peers" ]; then
  packages+=(libopencv-contrib-dev libopen3d-dev)
elif [ $# -gt 0 ]; then
  echo "install_deps: unknown option '$1' (the only option is --peers)" >&2
  exit 2
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install_deps: run as root (missing: ${missing[*]})" >&2; exit 1; }
  sudo="sudo"
fi
echo "install_deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q
$sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
