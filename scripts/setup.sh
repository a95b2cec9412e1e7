#!/usr/bin/env bash
# Installs the Debian 12 packages rtm needs that are missing. Run as root (or with sudo available).
set -euo pipefail
# What uses each: the build (compiler, cmake, ninja, pkg-config for osmesa; git for the checkout); the libraries
# (OpenImageIO, libpng for the usual PNG files without it, GLM, OSMesa, GLFW, glad, oneTBB, nlohmann-json, CLI11); the
# tests (GoogleTest; openimageio-tools' oiiotool and idiff; xvfb-run, which needs xauth, for the window tests); the
# fuzzers (clang, libclang-rt-14-dev); scripts/format.sh (clang-format); the mesh import, SIMD and viewer work in
# progress (assimp and its test models, Highway, Dear ImGui); the comparison page's tests (headless chromium, and
# xmllint from libxml2-utils); and the instruction counter's test (qemu-user, which scripts/arm.sh also uses). Google
# Benchmark and Google Mock are not used: rtm bench is its own program.
packages=(
  build-essential cmake ninja-build pkg-config git
  libopenimageio-dev openimageio-tools libpng-dev libglm-dev libosmesa6-dev libglfw3-dev python3-glad
  libtbb-dev nlohmann-json3-dev libcli11-dev libgtest-dev
  libassimp-dev assimp-testmodels libhwy-dev libimgui-dev
  xvfb xauth clang libclang-rt-14-dev clang-format
  chromium libxml2-utils qemu-user
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: all packages present"
fi
