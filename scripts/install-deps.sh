#!/usr/bin/env bash
# Installs what intrinsym's build and tests need on Debian 12: compilers and CMake, valgrind,
# OpenMesh (adapter), Debian's MeshLab 2020.09 with Qt/GLEW/Eigen/Xvfb (plugin and its headless
# tests), and MeshLab's source headers (`apt-get source meshlab`, which needs a deb-src entry)
# in ~/.cache/intrinsym/meshlab-src. Idempotent and quick when everything is present. Needs
# root or sudo.
set -euo pipefail
packages=(cmake make g++ pkg-config python3 valgrind libopenmesh-dev
          meshlab qtbase5-dev libqt5opengl5-dev libglew-dev libeigen3-dev libglu1-mesa-dev
          xvfb xauth libgl1-mesa-dri dpkg-dev)
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
need=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need+=("$p")
done
src_root="${XDG_CACHE_HOME:-$HOME/.cache}/intrinsym/meshlab-src"
have_src=$(ls -d "$src_root"/meshlab-2020.09*/src/common/interfaces.h 2>/dev/null | head -1 || true)
updated=0
if [ ${#need[@]} -gt 0 ]; then
  $SUDO apt-get update -qq
  updated=1
  $SUDO apt-get install -y -qq --no-install-recommends -o DPkg::Lock::Timeout=900 "${need[@]}" >/dev/null
fi
if [ -z "$have_src" ]; then
  # Source packages for bookworm, same mirrors and keyring as the binary ones.
  if ! grep -rqs "deb-src" /etc/apt/sources.list /etc/apt/sources.list.d/; then
    $SUDO tee /etc/apt/sources.list.d/intrinsym-deb-src.sources >/dev/null <<'SRC'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm bookworm-updates
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
    updated=0
  fi
  [ "$updated" -eq 1 ] || $SUDO apt-get update -qq
  mkdir -p "$src_root"
  (cd "$src_root" && apt-get source -qq meshlab >/dev/null 2>&1)
  ls -d "$src_root"/meshlab-2020.09*/src/common/interfaces.h >/dev/null
fi
