#!/usr/bin/env bash
# Stages a private MeshLab next to a plugins/ folder: Debian's plugins, symlinked, and the
# plugin under test, copied. Writes only inside WORK.
#   stage.sh PLUGIN.so WORK EXECUTABLE [SYSTEM_PLUGIN_DIR]
# Pitfall (issue 16, item 16): with our plugin installed, the system folder holds a file of the
# same name; symlinking it and then `cp`ing the plugin under test "onto" the symlink writes
# through it into /usr (a running MeshLab died of SIGBUS). So the system copy of our own plugin
# is never linked, and the copy refuses to follow a link.
set -euo pipefail
plugin=$1 work=$2 exe=$3 sysdir=${4:-/usr/lib/x86_64-linux-gnu/meshlab/plugins}
name=$(basename "$plugin")
mkdir -p "$work/plugins"
cp "$exe" "$work/"
for p in "$sysdir"/*.so; do
  [ -e "$p" ] || continue
  [ "$(basename "$p")" = "$name" ] && continue
  ln -sf "$p" "$work/plugins/"
done
rm -f "$work/plugins/$name"
cp --remove-destination "$plugin" "$work/plugins/$name"
