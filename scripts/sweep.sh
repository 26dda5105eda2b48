#!/usr/bin/env bash
# Runs the paper's channel families (section 2.2) from dem/scenes/channel.yaml with --set overrides:
#   concentration  0.50 / 0.55 / 0.60            (alpha = 2, 5-10 corners)
#   exponent       alpha = 1.2 / 1.6 / 2.0       (50 %, 5-10 corners)
#   corners        5-10 / 10-15 / 15-20          (60 %, alpha = 2)
# Each member writes results/sweep/<family>/<member>/ (results.h5, VTK) and <member>.log. Runs -j at a time
# (default: the number of cores). Arguments after -- go to every run (no spaces inside one argument). Then: /usr/bin/python3 postprocess/plot_sweep.py results/sweep -o docs/figures
#
#   bash scripts/sweep.sh [-j N] [-o DIR] [FAMILY...] [-- EXTRA --set ARGS]
set -euo pipefail
cd "$(dirname "$0")/.."

JOBS="$(nproc)"
OUT="results/sweep"
families=()
extra=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    -j) JOBS="$2"; shift 2 ;;
    -o) OUT="$2"; shift 2 ;;
    -h|--help) sed -n '2,9p' "$0"; exit 0 ;;
    --) shift; extra=("$@"); break ;;
    concentration|exponent|corners) families+=("$1"); shift ;;
    *) echo "sweep.sh: unknown argument '$1' (families: concentration, exponent, corners; try -h)" >&2; exit 2 ;;
  esac
done
[ ${#families[@]} -gt 0 ] || families=(concentration exponent corners)
BIN="${POLYFLOE_BIN:-build/polyfloe}"  # the polyfloe binary (default: the one scripts/build.sh makes)
[ -x "$BIN" ] || bash scripts/build.sh
export BIN

members() {
  case "$1" in
    concentration) echo "c0.50:floe_field.concentration=0.5 c0.55:floe_field.concentration=0.55 c0.60:floe_field.concentration=0.6" ;;
    exponent) echo "a1.2:floe_field.size.exponent=1.2 a1.6:floe_field.size.exponent=1.6 a2.0:floe_field.size.exponent=2.0" ;;
    corners) echo "k05-10:floe_field.corners=[5,10] k10-15:floe_field.corners=[10,15] k15-20:floe_field.corners=[15,20]" ;;
  esac
}

jobs_list=()
for f in "${families[@]}"; do
  for m in $(members "$f"); do
    name="${m%%:*}"
    sets="${m#*:}"
    args=(--set "${sets}")
    [ "$f" = corners ] && args+=(--set floe_field.concentration=0.6)
    jobs_list+=("$f/$name|${args[*]} ${extra[*]}")
  done
done

run_one() {
  local spec="$1" dir="${1%%|*}" args="${1#*|}"
  mkdir -p "$OUT/$dir"
  # shellcheck disable=SC2086
  if "$BIN" run dem/scenes/channel.yaml -o "$OUT/$dir" $args >"$OUT/$dir.log" 2>&1; then
    echo "done: $dir ($(grep -E '^Channel' "$OUT/$dir.log" || true))"
  else
    echo "FAILED: $dir (see $OUT/$dir.log)" >&2
    return 1
  fi
}
export -f run_one
export OUT
status=0
printf '%s\n' "${jobs_list[@]}" | xargs -P "$JOBS" -I{} bash -c 'run_one "$@"' _ {} || status=$?
exit $status
