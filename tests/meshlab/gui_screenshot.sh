#!/usr/bin/env bash
# The GUI check behind docs/meshlab.png (manual, not run by ctest: it clicks at screen
# coordinates of MeshLab 2020.09's default layout). Needs xvfb, xdotool and imagemagick.
#   gui_screenshot.sh PLUGIN.so MESH OUT.png
set -euo pipefail
plugin=$1 mesh=$2 out=$3
dir=$(mktemp -d)
"$(cd "$(dirname "$0")" && pwd)/stage.sh" "$plugin" "$dir" /usr/bin/meshlab
export LD_LIBRARY_PATH=/usr/lib/x86_64-linux-gnu/meshlab DISPLAY=:77
Xvfb :77 -screen 0 1280x900x24 & xvfb=$!
sleep 2
"$dir/meshlab" "$mesh" & gui=$!
sleep 8
wid=$(xdotool search --name MeshLab | head -1)
xdotool windowactivate --sync "$wid"; xdotool windowsize "$wid" 1280 900; xdotool windowmove "$wid" 0 0
xdotool mousemove 120 10 click 1; sleep 1          # Filters
xdotool mousemove 240 261 click 1; sleep 1         # Quality Measure and Computations
xdotool mousemove 626 536 click 1; sleep 2         # Intrinsic Symmetry: Detect
xdotool mousemove 289 577 click 1; sleep 12        # Apply
xdotool mousemove 101 577 click 1; sleep 2         # Close
xdotool mousemove 220 330 mousedown 1 mousemove 260 320 mousemove 300 300 mousemove 330 290 mouseup 1; sleep 2
import -window root -crop 853x724+0+0 "$out"
kill "$gui" "$xvfb"
rm -rf "$dir"
