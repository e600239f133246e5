#!/usr/bin/env bash
# Installs the build into a prefix inside the build folder (tests never write outside it), then
# builds examples/c/detect.c against it with find_package (CMake) and with pkg-config, and runs
# both on the bundled quadruped.
set -euo pipefail
build=$1 src=$2 mesh=$3
prefix="$build/installed-package"
rm -rf "$prefix"
mkdir -p "$prefix"
cmake --install "$build" --prefix "$prefix" >/dev/null
cmake -S "$src/examples/c" -B "$prefix/example-build" -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$prefix/example-build" >/dev/null
"$prefix/example-build/detect" "$mesh" | tee "$prefix/out1.txt"
grep -q "symmetries" "$prefix/out1.txt"
libdir=$(ls -d "$prefix"/lib*/ | head -1)
export PKG_CONFIG_PATH="$libdir/pkgconfig"
cc "$src/examples/c/detect.c" -o "$prefix/detect-pc" $(pkg-config --cflags intrinsym) $(pkg-config --libs --static intrinsym)
LD_LIBRARY_PATH="$libdir" "$prefix/detect-pc" "$mesh" | tee "$prefix/out2.txt"
diff "$prefix/out1.txt" "$prefix/out2.txt"
echo "installed package: find_package and pkg-config builds agree"
