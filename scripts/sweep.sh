#!/usr/bin/env bash
# Runs the paper's channel families (section 2.2) from dem/scenes/channel.yaml with --set overrides:
#   concentration  0.50 / 0.55 / 0.60            (alpha = 2, 5-10 corners)
#   exponent       alpha = 1.2 / 1.6 / 2.0       (50 %, 5-10 corners)
#   corners        5-10 / 10-15 / 15-20          (60 %, alpha = 2)
# for each seed of -s (default 1). Member <m> of family <f> with seed <s> writes results/sweep/<f>/<m>/s<s>/
# (results.h5, VTK) and its log beside it. A scene shared by two families (50 %/alpha 2/5-10 and 60 %/alpha 2/5-10)
# runs once; the other family's folder is a symbolic link to it. Runs -j at a time (default: the number of cores).
# Arguments after -- go to every run (no spaces inside one argument). Then:
#   /usr/bin/python3 postprocess/plot_sweep.py results/sweep -o figures
#
#   bash scripts/sweep.sh [-j N] [-s 1,2,3] [-o DIR] [FAMILY...] [-- EXTRA --set ARGS]
set -euo pipefail
cd "$(dirname "$0")/.."

JOBS="$(nproc)"
OUT="results/sweep"
SEEDS="1"
families=()
extra=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    -j) JOBS="$2"; shift 2 ;;
    -o) OUT="$2"; shift 2 ;;
    -s) SEEDS="$2"; shift 2 ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    --) shift; extra=("$@"); break ;;
    concentration|exponent|corners) families+=("$1"); shift ;;
    *) echo "sweep.sh: unknown argument '$1' (families: concentration, exponent, corners; try -h)" >&2; exit 2 ;;
  esac
done
[[ "$SEEDS" =~ ^[0-9]+(,[0-9]+)*$ ]] || { echo "sweep.sh: -s wants seeds like 1,2,3 (got '$SEEDS')" >&2; exit 2; }
[[ "$JOBS" =~ ^[1-9][0-9]*$ ]] || { echo "sweep.sh: -j wants a positive count (got '$JOBS')" >&2; exit 2; }
[ ${#families[@]} -gt 0 ] || families=(concentration exponent corners)
BIN="${POLYFLOE_BIN:-build/polyfloe}"  # the polyfloe binary (default: the one scripts/build.sh makes)
[ -x "$BIN" ] || bash scripts/build.sh
export BIN

# member name : concentration : exponent : corners
members() {
  case "$1" in
    concentration) echo "c0.50:0.5:2.0:[5,10] c0.55:0.55:2.0:[5,10] c0.60:0.6:2.0:[5,10]" ;;
    exponent) echo "a1.2:0.5:1.2:[5,10] a1.6:0.5:1.6:[5,10] a2.0:0.5:2.0:[5,10]" ;;
    corners) echo "k05-10:0.6:2.0:[5,10] k10-15:0.6:2.0:[10,15] k15-20:0.6:2.0:[15,20]" ;;
  esac
}

declare -A first_dir=()
jobs_list=()
links=()
for s in ${SEEDS//,/ }; do
  for f in "${families[@]}"; do
    for m in $(members "$f"); do
      IFS=: read -r name conc alpha corners <<<"$m"
      key="$conc|$alpha|$corners|$s"
      dir="$f/$name/s$s"
      if [ -n "${first_dir[$key]:-}" ]; then
        links+=("${first_dir[$key]}|$dir")
        continue
      fi
      first_dir[$key]="$dir"
      jobs_list+=("$dir|--set floe_field.concentration=$conc --set floe_field.size.exponent=$alpha --set floe_field.corners=$corners --set floe_field.seed=$s ${extra[*]}")
    done
  done
done

for l in "${links[@]}"; do   # the second family's member points at the run of the first
  src="${l%%|*}" dst="${l#*|}"
  mkdir -p "$OUT/$(dirname "$dst")"
  rm -rf "${OUT:?}/$dst" "$OUT/$dst.log"
  ln -s "$(realpath -m "$OUT/$src")" "$OUT/$dst"
  ln -s "$(realpath -m "$OUT/$src.log")" "$OUT/$dst.log"
done

run_one() {
  local dir="${1%%|*}" args="${1#*|}"
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
# Runs go side by side, so each uses one thread (the step's threads would only compete for the same cores).
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-1}"
printf '%s\n' "${jobs_list[@]}" | xargs -P "$JOBS" -I{} bash -c 'run_one "$@"' _ {} || status=$?
exit $status
