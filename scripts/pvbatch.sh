#!/usr/bin/env bash
# ParaView's pvbatch, headless: runs SCRIPT.py (and its arguments) with the ParaView that
# `bash scripts/setup.sh paraview` unpacked into .paraview/ (or POLYFLOE_PARAVIEW_DIR), under a virtual display
# (xvfb-run) when there is no $DISPLAY.
#
#   bash scripts/pvbatch.sh postprocess/paraview/channel.py results/channel -o figures/
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
pv_dir=${POLYFLOE_PARAVIEW_DIR:-$repo/.paraview}
pvbatch=$pv_dir/root/usr/bin/pvbatch
if [ ! -x "$pvbatch" ]; then
  echo "pvbatch.sh: no ParaView in $pv_dir; install it with: bash scripts/setup.sh paraview" >&2
  exit 2
fi
unset PYTHONPATH  # ParaView brings its own vtkmodules; another VTK's on the path would shadow them
if [ -n "${DISPLAY:-}" ]; then
  exec "$pvbatch" "$@"
fi
# A display number of its own (free, from a random start): runs side by side, or one right after another, do not
# meet on the same server. Under load a virtual display sometimes refuses the first connection ("bad X server
# connection", pvbatch aborts before doing anything): then it is tried again, at most three times.
for attempt in 1 2 3; do
  log=$(mktemp)
  set +e
  xvfb-run -a -n $((100 + RANDOM % 800)) -s "-screen 0 1920x1080x24 -nolisten tcp" "$pvbatch" "$@" \
    2> >(tee "$log" >&2)
  rc=$?
  set -e
  wait  # for tee
  if [ "$rc" -ne 0 ] && [ "$attempt" -lt 3 ] && grep -q "bad X server connection\|cannot open display" "$log"; then
    rm -f "$log"
    echo "pvbatch.sh: the virtual display refused the connection; trying again" >&2
    continue
  fi
  rm -f "$log"
  exit "$rc"
done
