#!/usr/bin/env bash
# The paper's uniaxial compression study (section 2.1, Fig. 6-8): dem/scenes/uniaxial_compression.yaml with the
# normal bond strength sigma_n = 0.1, 0.5, 1.0, 1.5 MPa (the shear cohesion follows it), then the figures:
# stress-strain and broken faces (uniaxial_stress_strain.png), fracture-angle densities (uniaxial_fracture_angles.png)
# and crack pictures (uniaxial_cracks.png), with the key numbers in uniaxial.json.
#
#   bash scripts/uniaxial_study.sh [-j N] [-o RESULTS] [-f FIGURES] [-- EXTRA --set ARGS]
# (defaults: -j number of cores, -o results/uniaxial, -f RESULTS/figures; about 2 minutes per run on one core;
# the documentation's figures: -f docs/figures)
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS="$(nproc)"
OUT="results/uniaxial"
FIG=""
extra=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    -j) JOBS="$2"; shift 2 ;;
    -o) OUT="$2"; shift 2 ;;
    -f) FIG="$2"; shift 2 ;;
    -h|--help) sed -n '2,9p' "$0"; exit 0 ;;
    --) shift; extra=("$@"); break ;;
    *) echo "uniaxial_study.sh: unknown argument '$1' (try -h)" >&2; exit 2 ;;
  esac
done
[[ "$JOBS" =~ ^[1-9][0-9]*$ ]] || { echo "uniaxial_study.sh: -j wants a positive count (got '$JOBS')" >&2; exit 2; }
FIG="${FIG:-$OUT/figures}"
BIN="${POLYFLOE_BIN:-build/polyfloe}"
[ -x "$BIN" ] || bash scripts/build.sh
export BIN OUT
run_one() {
  local s="$1"; shift
  mkdir -p "$OUT"
  if "$BIN" run dem/scenes/uniaxial_compression.yaml -o "$OUT/sigma_$s" \
      --set ice_sheet.bonds.tensile_strength="${s}e6" --set ice_sheet.bonds.shear_strength="${s}e6" "$@" \
      >"$OUT/sigma_$s.log" 2>&1; then
    echo "done: sigma_n = $s MPa"
  else
    echo "FAILED: sigma_n = $s MPa (see $OUT/sigma_$s.log)" >&2
    return 1
  fi
}
export -f run_one
# Runs go side by side, so each uses one thread (the step's threads would only compete for the same cores).
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-1}"
printf '%s\n' 0.1 0.5 1.0 1.5 | xargs -P "$JOBS" -I{} bash -c 'run_one "$@"' _ {} "${extra[@]}"
mkdir -p "$FIG"
/usr/bin/python3 postprocess/plot_uniaxial.py "$OUT"/sigma_0.1 "$OUT"/sigma_0.5 "$OUT"/sigma_1.0 "$OUT"/sigma_1.5 \
  -o "$FIG" --json "$OUT/uniaxial.json"
