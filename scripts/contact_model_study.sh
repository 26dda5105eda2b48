#!/usr/bin/env bash
# The contact models against what users read off the shipped scenes (docs/validation.md, "Which contact model a
# scene may use"): each force model at its own automatic step - centroid, gradient, foundation - and the reference,
# the foundation model at a quarter of its step (run.steps_per_contact x 4), on
#   channel   dem/scenes/channel.yaml at 50, 55 and 60 % concentration (the paper's concentration family), seeds
#             -s (default 1,2,3,4,5): ice area through the strait against time, the first jam and how long it
#             holds, the mean speed in the strait;
#   uniaxial  dem/scenes/uniaxial_compression.yaml, sheet seeds -s: the stress-strain curve, its peak, the
#             fracture-angle histogram.
# Run <model>/<member>/s<seed> writes RESULTS/<scene>/<model>/<member>/s<seed>/ (results.h5; no VTK), its log beside
# it and, once it has finished, a stamp <dir>.done holding its wall time [s]: the study is resumable - run it again
# and only the runs without a stamp run (each anew). -j runs at a time (default: the number of cores), each on one
# thread. Arguments after -- go to every run. Then the charts and the table:
#   /usr/bin/python3 postprocess/plot_contact_study.py RESULTS -o docs/figures --json docs/data/contact_study.json
#
#   bash scripts/contact_model_study.sh [-j N] [-s 1,2,3,4,5] [-o RESULTS] [-m MODELS] [SCENE...] [-- EXTRA --set ARGS]
# (defaults: RESULTS = results/contact_study, MODELS = centroid,gradient,foundation,reference, both scenes. The whole
# study is long: docs/validation.md states its cost.)
set -euo pipefail
cd "$(dirname "$0")/.."

JOBS="$(nproc)"
OUT="results/contact_study"
SEEDS="1,2,3,4,5"
MODELS="centroid,gradient,foundation,reference"
scenes=()
extra=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    -j) JOBS="$2"; shift 2 ;;
    -o) OUT="$2"; shift 2 ;;
    -s) SEEDS="$2"; shift 2 ;;
    -m) MODELS="$2"; shift 2 ;;
    -h|--help) sed -n '2,19p' "$0"; exit 0 ;;
    --) shift; extra=("$@"); break ;;
    channel|uniaxial) scenes+=("$1"); shift ;;
    *) echo "contact_model_study.sh: unknown argument '$1' (scenes: channel, uniaxial; try -h)" >&2; exit 2 ;;
  esac
done
[[ "$SEEDS" =~ ^[0-9]+(,[0-9]+)*$ ]] || { echo "contact_model_study.sh: -s wants seeds like 1,2,3 (got '$SEEDS')" >&2; exit 2; }
[[ "$JOBS" =~ ^[1-9][0-9]*$ ]] || { echo "contact_model_study.sh: -j wants a positive count (got '$JOBS')" >&2; exit 2; }
for m in ${MODELS//,/ }; do
  case "$m" in
    centroid|gradient|foundation|reference) ;;
    *) echo "contact_model_study.sh: -m: unknown model '$m' (centroid, gradient, foundation, reference)" >&2; exit 2 ;;
  esac
done
[ ${#scenes[@]} -gt 0 ] || scenes=(channel uniaxial)
BIN="${POLYFLOE_BIN:-build/polyfloe}"  # the polyfloe binary (default: the one scripts/build.sh makes)
[ -x "$BIN" ] || POLYFLOE_BUILD_TARGETS=polyfloe bash scripts/build.sh
export BIN OUT

# A model's settings: its force model and, for the reference, four times the steps per contact of the scene (40).
model_args() {
  case "$1" in
    reference) echo "--set contact.force_model=foundation --set run.steps_per_contact=160" ;;
    *) echo "--set contact.force_model=$1" ;;
  esac
}

jobs_list=()
for s in ${SEEDS//,/ }; do
  for scene in "${scenes[@]}"; do
    for m in ${MODELS//,/ }; do
      if [ "$scene" = channel ]; then
        for c in 0.50 0.55 0.60; do
          jobs_list+=("channel/$m/c$c/s$s|dem/scenes/channel.yaml|$(model_args "$m") --set floe_field.concentration=$c --set floe_field.seed=$s --set output.vtk=false --set output.contacts=false --set output.velocity_grid.enabled=false ${extra[*]}")
        done
      else
        jobs_list+=("uniaxial/$m/sigma1.5/s$s|dem/scenes/uniaxial_compression.yaml|$(model_args "$m") --set ice_sheet.seed=$s --set output.vtk=false ${extra[*]}")
      fi
    done
  done
done

run_one() {
  local dir="${1%%|*}" rest="${1#*|}"
  local scene="${rest%%|*}" args="${rest#*|}"
  if [ -f "$OUT/$dir.done" ]; then
    echo "kept: $dir ($(cat "$OUT/$dir.done") s)"
    return 0
  fi
  rm -rf "${OUT:?}/$dir"
  mkdir -p "$(dirname "$OUT/$dir")"
  local t0 t1
  t0=$(date +%s.%N)
  # shellcheck disable=SC2086
  if "$BIN" run "$scene" -o "$OUT/$dir" --threads 1 $args >"$OUT/$dir.log" 2>&1; then
    t1=$(date +%s.%N)
    awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f\n", b - a }' >"$OUT/$dir.done"
    echo "done: $dir ($(cat "$OUT/$dir.done") s)"
  else
    echo "FAILED: $dir (see $OUT/$dir.log)" >&2
    return 1
  fi
}
export -f run_one
status=0
export OMP_NUM_THREADS=1
# The longest first (the reference, then the foundation model), so that the last runs left are short ones.
printf '%s\n' "${jobs_list[@]}" | awk -F'|' '{ k = ($1 ~ /\/reference\//) ? 0 : ($1 ~ /\/foundation\//) ? 1 : 2; print k "\t" $0 }' |
  sort -s -n -k1,1 | cut -f2- | xargs -P "$JOBS" -I{} bash -c 'run_one "$@"' _ {} || status=$?
exit $status
