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
# meet on the same server.
exec xvfb-run -a -n $((100 + RANDOM % 800)) -s "-screen 0 1920x1080x24 -nolisten tcp" "$pvbatch" "$@"
