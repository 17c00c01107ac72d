#!/usr/bin/env bash
# Installs the Debian 12 packages sss needs to build, test and run, if any are missing.
# Usage: scripts/install-deps.sh [--ci | --dev]
#   --ci   adds what CI's extra jobs use: clang + libFuzzer runtime (make fuzz-ci), valgrind and
#          chromium (the valgrind smoke test and the report screenshot test skip without them)
#   --dev  adds, on top, what only developers need (scikit-image to recompute SSIM test vectors)
set -euo pipefail

PKGS=(
  build-essential cmake pkg-config git
  libmeshoptimizer-dev libcjson-dev libstb-dev libjpeg62-turbo-dev libopenexr-dev liblapacke-dev
  libcairo2-dev libembree-dev libdraco-dev
  libepoxy-dev libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libglfw3-dev libimgui-dev xvfb xauth
  python3-dev python3-numpy python3-setuptools
)
case "${1:-}" in
  --ci) PKGS+=(clang libclang-rt-14-dev valgrind chromium) ;;
  --dev) PKGS+=(clang libclang-rt-14-dev valgrind chromium python3-skimage python3-pip) ;;
esac

missing=()
for p in "${PKGS[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "install-deps: missing packages: ${missing[*]}; run this script as root" >&2; exit 1
  fi
fi
echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
