#!/usr/bin/env bash
# Issue 16, item 16: staging MeshLab for a test must never write into the system plugin
# folder, even when our plugin is installed there. A fake system folder (inside the build
# folder) holds an "installed" plugin of the same name; after staging it must be unchanged.
#   stage_test.sh WORK
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
work=$1
rm -rf "$work"
mkdir -p "$work/system" "$work/new"
echo installed >"$work/system/libfilter_intrinsym.so"
echo other >"$work/system/libfilter_other.so"
echo under-test >"$work/new/libfilter_intrinsym.so"
echo exe >"$work/exe"
"$here/stage.sh" "$work/new/libfilter_intrinsym.so" "$work/stage" "$work/exe" "$work/system"
# Twice: a second run over an existing stage must not write through either.
"$here/stage.sh" "$work/new/libfilter_intrinsym.so" "$work/stage" "$work/exe" "$work/system"
[ "$(cat "$work/system/libfilter_intrinsym.so")" = installed ] || { echo "the installed plugin was overwritten"; exit 1; }
[ "$(cat "$work/stage/plugins/libfilter_intrinsym.so")" = under-test ] || { echo "the plugin under test is not staged"; exit 1; }
[ ! -L "$work/stage/plugins/libfilter_intrinsym.so" ] || { echo "the staged plugin is a link"; exit 1; }
[ -L "$work/stage/plugins/libfilter_other.so" ] || { echo "the other plugins are not linked"; exit 1; }
echo "staging writes only inside $work"
