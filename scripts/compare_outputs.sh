#!/usr/bin/env bash
# Bitwise before/after for a change that must not change results (a refactoring): runs every scene of dem/scenes/
# and the OpenFOAM strait's ice (shortened to seconds of wall time each, one thread) with this checkout's polyfloe
# and with another commit's, built alike, and compares the output folders with scripts/compare_outputs.py: every
# file, every HDF5 dataset's bits and attribute (less code_version), every VTK file byte for byte. Exit 0 when all
# are bitwise the same, 1 when some differ (each difference printed), 2 on bad arguments.
#
#   bash scripts/compare_outputs.sh                 # this working tree against HEAD (uncommitted changes)
#   bash scripts/compare_outputs.sh -r main~3       # against another commit
#   bash scripts/compare_outputs.sh -k channel      # only the cases whose name contains "channel"
#
# The other commit is unpacked with git archive and its polyfloe built (target polyfloe only) under
# .cache/compare/<commit>/, kept for the next call; this checkout's under build-compare/ (POLYFLOE_BUILD_DIR to
# choose). The strait case needs of_cases/strait/field.h5 (of_cases/strait/Allrun makes it); without it, it is
# skipped and said so.
set -euo pipefail
cd "$(dirname "$0")/.."
REV=HEAD
FILTER=""
usage() { sed -n '2,15p' "$0"; }
while [[ $# -gt 0 ]]; do
  case "$1" in
    -r) REV="$2"; shift 2 ;;
    -k) FILTER="$2"; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "compare_outputs.sh: unknown argument '$1' (try -h)" >&2; exit 2 ;;
  esac
done
sha=$(git rev-parse --verify --quiet "$REV^{commit}") || { echo "compare_outputs.sh: no commit '$REV'" >&2; exit 2; }
root=$PWD
base=$root/.cache/compare/$sha
if [[ ! -x $base/build/polyfloe ]]; then
  rm -rf "$base/src"
  mkdir -p "$base/src"
  git archive "$sha" | tar -x -C "$base/src"
  echo "building $REV ($sha) in $base/build"
  POLYFLOE_BUILD_DIR=$base/build POLYFLOE_BUILD_TARGETS=polyfloe bash "$base/src/scripts/build.sh"
fi
new_build=${POLYFLOE_BUILD_DIR:-build-compare}
echo "building this checkout in $new_build"
POLYFLOE_BUILD_DIR=$new_build POLYFLOE_BUILD_TARGETS=polyfloe bash scripts/build.sh

# name | scene | overrides (each scene cut to a few seconds of wall time, with frames on the way)
cases=(
  "two_floes|dem/scenes/two_floes.yaml|"
  "cube_plate|dem/scenes/cube_plate.yaml|output.checkpoint.every=0"
  "uniaxial_compression|dem/scenes/uniaxial_compression.yaml|run.duration=0.5 output.interval=0.1"
  "pack_ice_sheet|dem/scenes/pack_ice_sheet.yaml|run.duration=6 output.interval=2"
  "drift_vortex|dem/scenes/drift_vortex.yaml|run.duration=30 output.interval=10"
  "drift_tidal|dem/scenes/drift_tidal.yaml|run.duration=7200 output.interval=1800"
  "channel|dem/scenes/channel.yaml|run.duration=10 output.interval=2 output.checkpoint.every=2"
  "channel_gradient|dem/scenes/channel.yaml|run.duration=5 output.interval=1 contact.force_model=gradient"
  "channel_foundation|dem/scenes/channel.yaml|run.duration=2 output.interval=0.5 contact.force_model=foundation"
  "channel_realistic|dem/scenes/channel_realistic.yaml|run.duration=20 output.interval=5"
  "strait|of_cases/strait/ice.yaml|run.duration=20 output.interval=5 forcing.ocean.field.path=$root/of_cases/strait/field.h5"
)
out=$root/.cache/compare/runs
rm -rf "$out"
mkdir -p "$out"
failed=0
compared=0
for c in "${cases[@]}"; do
  IFS='|' read -r name scene overrides <<<"$c"
  [[ -z $FILTER || $name == *"$FILTER"* ]] || continue
  if [[ $name == strait && ! -f of_cases/strait/field.h5 ]]; then
    echo "$name: skipped (no of_cases/strait/field.h5: run of_cases/strait/Allrun)"
    continue
  fi
  sets=()
  for o in $overrides; do sets+=(--set "$o"); done
  mkdir -p "$out/$name"
  for side in old new; do
    bin=$base/build/polyfloe
    [[ $side == new ]] && bin=$root/$new_build/polyfloe
    code=0
    "$bin" run "$scene" -o "$out/$name/$side" --threads 1 "${sets[@]}" >"$out/$name/$side.log" 2>&1 || code=$?
    # (a run that fails alike on both sides compares alike: its exit code and outputs are part of the result)
    echo "$code" >"$out/$name/$side.exit"
  done
  if ! cmp -s "$out/$name/old.exit" "$out/$name/new.exit"; then
    failed=$((failed + 1))
    echo "$name: DIFFERS: exit $(cat "$out/$name/old.exit") before, $(cat "$out/$name/new.exit") after (logs in $out/$name)"
    continue
  fi
  compared=$((compared + 1))
  if /usr/bin/python3 scripts/compare_outputs.py "$out/$name/old" "$out/$name/new" >"$out/$name/diff.txt"; then
    echo "$name: bitwise the same"
  else
    failed=$((failed + 1))
    echo "$name: DIFFERS"
    sed 's/^/    /' "$out/$name/diff.txt"
  fi
done
echo "$compared cases compared against $REV ($sha): $failed differ"
[[ $failed -eq 0 ]]
