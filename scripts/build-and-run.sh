#!/usr/bin/env bash
# Installs what is needed, builds everything through CMake (which drives cargo), and runs the
# main job on the bundled example.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j 2
"${CARGO_TARGET_DIR:-target}/release/intrinsym" spectrum examples/data/bumpy_torus.off -k 100
