#!/usr/bin/env bash
# Polygons against disks, side by side in one run: LAMMPS (Debian's `lammps`, pair gran/hertz/history) on the
# jammed periodic disk pack of tests/bench/lammps/disk_pack.in, and PolyFloe's DensePack benchmark
# (tests/bench/bench_step.cpp: 12-gon floes in a jammed pack), one core each, one after the other.
#
#   bash scripts/bench_lammps.sh              # 1.6k, 14.4k and 160k disks; DensePack 1.5k, 15k, 150k floes and
#                                             # DensePackContactOnly (no drift terms, as the disks) up to 1.5M
#   bash scripts/bench_lammps.sh -s 1,3,10,31 # ... and 1.54M disks
#   bash scripts/bench_lammps.sh -r 3         # medians of 3 repetitions
#   bash scripts/bench_lammps.sh -s 1,3       # only the 1.6k and 14.4k disk packs (replication factors)
#
# Prints ns per particle-step for LAMMPS (its "Loop time" / (steps x atoms)), PolyFloe's us_per_floe_step counter,
# and their ratio; writes results/bench/lammps.csv. Installs lammps through scripts/setup.sh bench.
set -euo pipefail
cd "$(dirname "$0")/.."

REPS=1
REPLICAS=1,3,10
while [[ $# -gt 0 ]]; do
  case "$1" in
    -r) REPS="$2"; shift 2 ;;
    -s) REPLICAS="$2"; shift 2 ;;
    -h|--help) sed -n '2,13p' "$0"; exit 0 ;;
    *) echo "bench_lammps.sh: unknown argument '$1' (try -h)" >&2; exit 2 ;;
  esac
done
[[ "$REPS" =~ ^[1-9][0-9]*$ ]] || { echo "bench_lammps.sh: -r expects a positive integer, got '$REPS'" >&2; exit 2; }
[[ "$REPLICAS" =~ ^[1-9][0-9]*(,[1-9][0-9]*)*$ ]] ||
  { echo "bench_lammps.sh: -s expects replication factors like 1,3,10, got '$REPLICAS'" >&2; exit 2; }

bash scripts/setup.sh bench
BUILD_DIR=build-bench
source scripts/bench_build.sh
bench_build "$BUILD_DIR" bench_step >/dev/null

OUT=results/bench
mkdir -p "$OUT"
WORK=$(mktemp -d "${TMPDIR:-/tmp}/polyfloe-lammps.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
# Open MPI refuses to start as root unless told; LAMMPS runs as a single process here (no mpirun).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

echo "disks,lammps_ns_per_particle_step,contacts_per_disk,area_fraction" >"$OUT/lammps.csv"
declare -A lammps_ns
IFS=, read -r -a reps_list <<<"$REPLICAS"
for rep in "${reps_list[@]}"; do
  steps=$(( rep <= 1 ? 2000 : (rep <= 3 ? 500 : (rep <= 10 ? 50 : 10)) ))
  values=()
  for ((k = 0; k < REPS; ++k)); do
    lmp -in tests/bench/lammps/disk_pack.in -var rep "$rep" -var steps "$steps" -var data "$WORK/base.data" -log none -screen "$WORK/out" >/dev/null
    loop=$(grep "^Loop time" "$WORK/out" | tail -1)
    atoms=$(awk '{ print $(NF - 1) }' <<<"$loop")
    secs=$(awk '{ print $4 }' <<<"$loop")
    values+=("$(awk -v s="$secs" -v n="$steps" -v a="$atoms" 'BEGIN { printf "%.1f", s / n / a * 1e9 }')")
  done
  ns=$(printf '%s\n' "${values[@]}" | median)
  read -r contacts area < <(awk '/Step Atoms c_cm v_area/ { getline; c = $3; a = $4 } END { print c, a }' "$WORK/out")
  lammps_ns[$atoms]=$ns
  echo "$atoms,$ns,$contacts,$area" >>"$OUT/lammps.csv"
  printf 'LAMMPS  %8d disks   %7.1f ns per particle-step   %.2f contacts per disk   area fraction %s\n' \
    "$atoms" "$ns" "$contacts" "$area"
done

bench_args=(--benchmark_filter='BM_DensePack(ContactOnly)?/[0-9]+/1/' --benchmark_format=console)
[[ "$REPS" -gt 1 ]] && bench_args+=(--benchmark_repetitions="$REPS" --benchmark_report_aggregates_only=true)
"$BUILD_DIR/tests/bench_step" "${bench_args[@]}" --benchmark_out="$OUT/bench_step_densepack.json" \
  --benchmark_out_format=json >"$WORK/poly" 2>/dev/null
echo "case,floes,polyfloe_us_per_floe_step,polyfloe_over_lammps" >"$OUT/polyfloe_vs_lammps.csv"
# The polygons against the disk pack of the nearest size: ContactOnly (no drift terms, like the disks) and the
# DensePack with every drift term; one thread, as LAMMPS runs.
grep -E '^BM_DensePack(ContactOnly)?/[0-9]+/1(/iterations:[0-9]+)?(_median)? ' "$WORK/poly" | while read -r line; do
  kind=$(sed -E 's|^BM_(DensePack(ContactOnly)?)/.*|\1|' <<<"$line")
  floes=$(sed -E 's|^BM_DensePack(ContactOnly)?/([0-9]+).*|\2|' <<<"$line")
  us=$(grep -oE 'us_per_floe_step=[0-9.]+' <<<"$line" | cut -d= -f2)
  best=""; bestd=""
  for n in "${!lammps_ns[@]}"; do
    d=$(awk -v a="$n" -v b="$floes" 'BEGIN { r = a / b; print (r > 1 ? r : 1 / r) }')
    if [[ -z "$bestd" ]] || awk -v x="$d" -v y="$bestd" 'BEGIN { exit !(x < y) }'; then best=$n; bestd=$d; fi
  done
  ratio=$(awk -v u="$us" -v l="${lammps_ns[$best]:-0}" 'BEGIN { if (l > 0) printf "%.2f", u * 1000 / l; else print "-" }')
  echo "$kind,$floes,$us,$ratio" >>"$OUT/polyfloe_vs_lammps.csv"
  printf 'PolyFloe %-23s %8d floes   %7.0f ns per floe-step   %s x LAMMPS (%s disks)\n' "$kind" "$floes" \
    "$(awk -v u="$us" 'BEGIN { print u * 1000 }')" "$ratio" "$best"
done
echo "results: $OUT/lammps.csv, $OUT/polyfloe_vs_lammps.csv, $OUT/bench_step_densepack.json"
