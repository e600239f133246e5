#!/usr/bin/env bash
# Installs what is needed, builds everything through CMake (which drives cargo), and runs the
# main job: symmetry detection on the bundled example, writing JSON, PLY and an HTML report.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j 2
"${CARGO_TARGET_DIR:-target}/release/intrinsym" detect examples/data/quadruped.off \
  --json build/quadruped.json --ply build/quadruped.ply --report build/quadruped.html
