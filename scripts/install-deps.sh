#!/usr/bin/env bash
# Installs the system packages intrinsym's build and tests need (Debian 12). Idempotent and quick
# when everything is present. Needs root or sudo.
set -euo pipefail
need=()
for cmd in cmake make g++ pkg-config python3 valgrind; do
  command -v "$cmd" >/dev/null 2>&1 || need+=("$cmd")
done
[ -f /usr/include/OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh ] || need+=(libopenmesh-dev)
[ ${#need[@]} -eq 0 ] && exit 0
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends -o DPkg::Lock::Timeout=900 \
  cmake make g++ pkg-config python3 valgrind libopenmesh-dev >/dev/null
