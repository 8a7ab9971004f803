#!/usr/bin/env bash
# Installs the Debian 12 packages shadowkit builds against (docs/architecture.md, Dependencies), only those
# missing, as root or through sudo. Safe to run repeatedly.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libglm-dev libepoxy-dev libegl1-mesa-dev libgl1-mesa-dri libglfw3-dev
  libembree-dev libtbb-dev libtinygltf-dev libstb-dev libwebp-dev nlohmann-json3-dev
  libcli11-dev libfmt-dev libmeshoptimizer-dev libtinyobjloader-dev libgtest-dev libbenchmark-dev
  libimgui-dev xvfb xauth assimp-testmodels libopenscenegraph-dev libogre-1.12-dev
  pybind11-dev python3-dev python3-numpy python3-matplotlib python3-distributed
  chromium mkdocs doxygen
  clang libclang-rt-14-dev clang-format-14
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "shadowkit: installing ${#missing[@]} missing Debian packages: ${missing[*]}" >&2
if [ "$(id -u)" -eq 0 ]; then sudo=""; elif command -v sudo >/dev/null; then sudo="sudo"; else
  echo "shadowkit: error: need root or sudo to install: ${missing[*]}" >&2; exit 1
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
