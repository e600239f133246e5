#!/usr/bin/env bash
# Runs the intrinsym filter in a headless meshlabserver without touching /usr: a copy of
# Debian's meshlabserver next to a plugins/ folder with Debian's plugins and ours (MeshLab
# 2020.09 derives its plugin folder from the executable's real path).
#   run.sh PLUGIN.so WORKDIR INPUT good|bad|varied [TRUTH.txt]
# good:   the filter succeeds and the PLY's colours/quality say that mirror vertices correspond.
# varied: the filter succeeds and the Correspondence colours vary over the surface (a sphere).
# bad:    the filter fails cleanly: a non-zero exit without a crash signal, the message logged.
# Environment: INTRINSYM_SET="name=value ..." overrides parameters of the script;
# INTRINSYM_FILTER="name" runs that filter of the plugin instead (same parameters);
# INTRINSYM_TWICE=1 applies the filter twice (the second time with Colouring = Groups);
# INTRINSYM_EXPECT=REGEX must match a line of meshlabserver's log; INTRINSYM_ABSENT=REGEX must
# match none.
set -euo pipefail
plugin=$1 work=$2 input=$3 mode=$4 truth=${5:-}
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"
"$here/stage.sh" "$plugin" "$work" /usr/bin/meshlabserver
export LD_LIBRARY_PATH=/usr/lib/x86_64-linux-gnu/meshlab
script="$work/script.mlx"
cp "$here/intrinsym.mlx" "$script"
if [ -n "${INTRINSYM_FILTER:-}" ]; then
  sed -i "s/<filter name=\"[^\"]*\">/<filter name=\"${INTRINSYM_FILTER}\">/" "$script"
fi
for setting in ${INTRINSYM_SET:-}; do
  sed -i "s/name=\"${setting%%=*}\" value=\"[^\"]*\"/name=\"${setting%%=*}\" value=\"${setting#*=}\"/" "$script"
done
if [ -n "${INTRINSYM_TWICE:-}" ]; then
  filter=$(sed -n '/<filter /,/<\/filter>/p' "$script" | sed 's/name="colouring" value="[^"]*"/name="colouring" value="1"/')
  python3 - "$script" "$filter" <<'PY'
import sys
path, block = sys.argv[1], sys.argv[2]
text = open(path).read()
open(path, "w").write(text.replace("</FilterScript>", block + "\n</FilterScript>"))
PY
fi
set +e
xvfb-run -a "$work/meshlabserver" -i "$input" -o "$work/out.ply" -m vc vq -s "$script" >"$work/log.txt" 2>&1
status=$?
set -e
echo "meshlabserver exit status: $status"
if [ -n "${INTRINSYM_EXPECT:-}" ]; then
  grep -E "$INTRINSYM_EXPECT" "$work/log.txt" || { echo "the log lacks /$INTRINSYM_EXPECT/"; cat "$work/log.txt"; exit 1; }
fi
if [ -n "${INTRINSYM_ABSENT:-}" ] && grep -E "$INTRINSYM_ABSENT" "$work/log.txt"; then
  echo "the log has /$INTRINSYM_ABSENT/"; exit 1
fi
if [ "$mode" = varied ]; then
  [ "$status" -eq 0 ] || { cat "$work/log.txt"; exit 1; }
  python3 "$here/check_ply.py" "$work/out.ply" --varied
elif [ "$mode" = good ]; then
  grep -E "Symmetry #" "$work/log.txt" | head -5 || true
  [ "$status" -eq 0 ] || { cat "$work/log.txt"; exit 1; }
  python3 "$here/check_ply.py" "$work/out.ply" $truth
else
  grep -iE "no faces|intrinsic" "$work/log.txt" | head -5 || true
  [ "$status" -ne 0 ] || { echo "the filter should have failed"; exit 1; }
  # 129..192 is death by a signal; meshlabserver's own failure is exit(-1) = 255.
  if [ "$status" -gt 128 ] && [ "$status" -le 192 ]; then echo "meshlabserver crashed (signal $((status - 128)))"; cat "$work/log.txt"; exit 1; fi
  [ -n "${INTRINSYM_EXPECT:-}" ] || grep -q "has no faces" "$work/log.txt" || { echo "the library's message is not in the log"; cat "$work/log.txt"; exit 1; }
  echo "failed cleanly with the message logged"
fi
