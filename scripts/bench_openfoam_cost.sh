#!/usr/bin/env bash
# What an OpenFOAM current costs: the strait's ice scene (of_cases/strait/ice.yaml, 355 floes, 60 s) on one thread
# in the OpenFOAM field (field.h5 of of_cases/strait) and the same run in a uniform 1 m/s current, side by side;
# the median wall time of each and their ratio.
#
#   bash scripts/bench_openfoam_cost.sh            # 3 repetitions each; runs of_cases/strait/Allrun --quick first
#                                                  # in a scratch copy when the case has no field.h5
#   bash scripts/bench_openfoam_cost.sh -r 5       # 5 repetitions
#   bash scripts/bench_openfoam_cost.sh -u 1       # with the drift evaluated every step (forcing.update_every: 1)
#
# Prints the medians and the ratio (docs/performance.md, "Sampling OpenFOAM currents").
set -euo pipefail
cd "$(dirname "$0")/.."

REPS=3
UPDATE=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    -r) REPS="$2"; shift 2 ;;
    -u) UPDATE="$2"; shift 2 ;;
    -h|--help) sed -n '2,11p' "$0"; exit 0 ;;
    *) echo "bench_openfoam_cost.sh: unknown argument '$1' (try -h)" >&2; exit 2 ;;
  esac
done
[[ "$REPS" =~ ^[1-9][0-9]*$ ]] || { echo "bench_openfoam_cost.sh: -r expects a positive integer, got '$REPS'" >&2; exit 2; }
[[ -z "$UPDATE" || "$UPDATE" =~ ^[1-9][0-9]*$ ]] ||
  { echo "bench_openfoam_cost.sh: -u expects a positive integer, got '$UPDATE'" >&2; exit 2; }

BUILD="${POLYFLOE_BUILD_DIR:-build}"
[ -x "$BUILD/polyfloe" ] || POLYFLOE_BUILD_DIR="$BUILD" bash scripts/build.sh >&2
POLYFLOE="$(cd "$BUILD" && pwd)/polyfloe"
WORK=$(mktemp -d "${TMPDIR:-/tmp}/polyfloe-bench-of.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
CASE=of_cases/strait
if [ ! -f "$CASE/field.h5" ]; then
  mkdir -p "$WORK/of_cases"
  cp -r of_cases/common of_cases/strait "$WORK/of_cases/"
  echo "bench_openfoam_cost: running the strait case (of_cases/strait/Allrun --quick) in $WORK" >&2
  POLYFLOE_ROOT="$PWD" POLYFLOE_BUILD_DIR="$(cd "$BUILD" && pwd)" bash "$WORK/of_cases/strait/Allrun" --quick \
    > "$WORK/allrun.log" 2>&1 || { tail -n 20 "$WORK/allrun.log" >&2; exit 1; }
  CASE="$WORK/of_cases/strait"
fi

# run MODE: the wall time [s] of one 60 s run.
run() {
  local -a set=(--set run.duration=60 --set output.interval=60)
  [ -n "$UPDATE" ] && set+=(--set "forcing.update_every=$UPDATE")
  [ "$1" = uniform ] && set+=(--set "forcing.ocean.field={type: uniform, velocity: [1, 0]}")
  local t0 t1
  t0=$(date +%s.%N)
  OMP_NUM_THREADS=1 "$POLYFLOE" run "$CASE/ice.yaml" -o "$WORK/out_$1" "${set[@]}" > /dev/null 2> "$WORK/log_$1" ||
    { cat "$WORK/log_$1" >&2; exit 1; }
  t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN {print b - a}'
}

median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }

field_times=() uniform_times=()
for ((i = 0; i < REPS; i++)); do  # alternated, so that a change in the machine's load touches both alike
  field_times+=("$(run field)")
  uniform_times+=("$(run uniform)")
done
f=$(printf '%s\n' "${field_times[@]}" | median)
u=$(printf '%s\n' "${uniform_times[@]}" | median)
printf 'strait ice, 60 s, 1 thread%s: OpenFOAM field %.3f s, uniform current %.3f s (medians of %d): ratio %.2f\n' \
  "${UPDATE:+, update_every $UPDATE}" "$f" "$u" "$REPS" "$(awk -v a="$f" -v b="$u" 'BEGIN {print a / b}')"
