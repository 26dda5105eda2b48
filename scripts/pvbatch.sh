#!/usr/bin/env bash
# ParaView's pvbatch, headless: runs SCRIPT.py (and its arguments) with the ParaView that
# `bash scripts/setup.sh paraview` unpacked into .paraview/ (or POLYFLOE_PARAVIEW_DIR), on a virtual display of its
# own (Xvfb) when there is no $DISPLAY.
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
# A virtual display of its own: Xvfb picks a free display number itself and writes it to a file when it accepts
# connections (-displayfd: no race between runs side by side, which xvfb-run -a has), and is stopped at the end.
# -noreset: by default the server resets when its last client disconnects, and pvbatch connects more than once, so
# a connection made during the reset failed ("bad X server connection", pvbatch aborts; 2 runs in 5 here, and
# under load with xvfb-run). Should a display still refuse, the whole is tried again, at most three times.
run_on_xvfb() {
  local number log rc xvfb wait_for_tee
  number=$(mktemp)
  log=$(mktemp)
  Xvfb -displayfd 3 -screen 0 1920x1080x24 -nolisten tcp -noreset 3>"$number" 2>/dev/null &
  xvfb=$!
  for _ in $(seq 300); do
    [ -s "$number" ] && break
    if ! kill -0 "$xvfb" 2>/dev/null; then break; fi
    sleep 0.1
  done
  if [ ! -s "$number" ]; then
    kill "$xvfb" 2>/dev/null || true
    rm -f "$number" "$log"
    echo "pvbatch.sh: the virtual display (Xvfb) did not start" >&2
    return 75
  fi
  rc=0
  DISPLAY=":$(tr -d '[:space:]' <"$number")" "$pvbatch" "$@" 2> >(tee "$log" >&2) || rc=$?
  wait_for_tee=$(jobs -p | grep -v "^$xvfb$" || true)
  kill "$xvfb" 2>/dev/null || true
  wait "$xvfb" 2>/dev/null || true
  [ -z "$wait_for_tee" ] || wait $wait_for_tee 2>/dev/null || true
  if [ "$rc" -ne 0 ] && grep -q "bad X server connection\|cannot open display" "$log"; then rc=75; fi
  rm -f "$number" "$log"
  return "$rc"
}
for attempt in 1 2 3; do
  rc=0
  run_on_xvfb "$@" || rc=$?
  if [ "$rc" -eq 75 ] && [ "$attempt" -lt 3 ]; then
    echo "pvbatch.sh: the virtual display failed; trying again" >&2
    continue
  fi
  exit "$rc"
done
